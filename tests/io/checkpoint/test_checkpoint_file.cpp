// SPDX-License-Identifier: GPL-3.0-or-later
// checkpoint.h5: every kind of array comes back as it went in, the file is replaced atomically
// (a failed write leaves the previous checkpoint and no temporary file), and a checkpoint that
// does not fit what it is loaded into is refused naming the array.
#include "io/checkpoint/checkpoint_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace femdem {
namespace {

namespace fs = std::filesystem;

struct Record {
  double a = 0.0;
  std::int32_t b = 0;
  std::uint8_t c = 0;
};

fs::path folder() {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "checkpoint_file";
  fs::create_directories(d);
  return d;
}

CheckpointInfo info(double t) {
  return {kCheckpointFormat, "test (abc)", "0123456789abcdef", t, 7};
}

struct State {
  std::vector<double> x = {1.0, -0.0, std::numeric_limits<double>::denorm_min(), HUGE_VAL, NAN};
  std::vector<std::int64_t> steps = {std::numeric_limits<std::int64_t>::min(), 3};
  std::vector<std::uint32_t> ids = {0xffffffffu};
  std::vector<std::uint8_t> empty;
  std::vector<Record> records = {{1.5, -2, 3}, {2.5, 4, 255}};
  std::vector<Vec3> points = {Vec3(1, 2, 3)};
  std::size_t count = 42;
  bool flag = true;
  std::string text = std::string("a\0b\nc", 5);
  void exchange(StateArchive& a) {
    using L = StateArchive::Length;
    const StateArchive::Scope scope(a, "part");
    a.array("x", x);
    a.array("steps", steps, L::variable);
    a.array("ids", ids);
    a.array("empty", empty, L::variable);
    a.array("records", records, L::variable);
    a.array("points", points, L::variable);
    a.value("count", count);
    a.value("flag", flag);
    a.text("text", text);
  }
};

TEST(CheckpointFile, EveryKindOfArrayComesBackBitForBit) {
  const fs::path p = folder() / "roundtrip.h5";
  State saved;
  write_checkpoint(p, info(0.25), [&](StateArchive& a) { saved.exchange(a); });
  const CheckpointInfo read = read_checkpoint_info(p);
  EXPECT_EQ(read.format, kCheckpointFormat);
  EXPECT_EQ(read.femdem_version, "test (abc)");
  EXPECT_EQ(read.scene_digest, "0123456789abcdef");
  EXPECT_EQ(read.time, 0.25);
  EXPECT_EQ(read.step, 7);
  State loaded;
  loaded.x.assign(5, 0.0);  // fixed length: the model gives it
  loaded.ids.assign(1, 0);
  loaded.steps.clear(), loaded.records.clear(), loaded.points.clear(), loaded.count = 0;
  loaded.flag = false, loaded.text.clear(), loaded.empty = {9};
  read_checkpoint(p, [&](StateArchive& a) { loaded.exchange(a); });
  ASSERT_EQ(loaded.x.size(), 5u);
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(std::memcmp(&loaded.x[i], &saved.x[i], sizeof(double)), 0) << i;
  EXPECT_EQ(loaded.steps, saved.steps);
  EXPECT_EQ(loaded.ids, saved.ids);
  EXPECT_TRUE(loaded.empty.empty());
  ASSERT_EQ(loaded.records.size(), 2u);
  EXPECT_EQ(loaded.records[1].a, 2.5);
  EXPECT_EQ(loaded.records[1].b, 4);
  EXPECT_EQ(loaded.records[1].c, 255);
  ASSERT_EQ(loaded.points.size(), 1u);
  EXPECT_EQ(loaded.points[0], Vec3(1, 2, 3));
  EXPECT_EQ(loaded.count, 42u);
  EXPECT_TRUE(loaded.flag);
  EXPECT_EQ(loaded.text, saved.text);
}

TEST(CheckpointFile, AFailedWriteLeavesThePreviousCheckpointAndNoTemporaryFile) {
  const fs::path p = folder() / "atomic.h5";
  State s;
  write_checkpoint(p, info(1.0), [&](StateArchive& a) { s.exchange(a); });
  EXPECT_THROW(write_checkpoint(p, info(2.0),
                                [&](StateArchive& a) {
                                  s.exchange(a);
                                  throw std::runtime_error("disk full");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_checkpoint_info(p).time, 1.0);
  for (const auto& e : fs::directory_iterator(folder()))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

// The message of loading `p` into `load`, or "" if it loads.
std::string refusal(const fs::path& p, const std::function<void(StateArchive&)>& load) {
  try {
    read_checkpoint(p, load);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckpointFile, RefusesWhatDoesNotFitNamingTheArray) {
  const fs::path p = folder() / "refuse.h5";
  State s;
  write_checkpoint(p, info(1.0), [&](StateArchive& a) { s.exchange(a); });
  std::vector<double> wrong_length(4);
  EXPECT_NE(refusal(p, [&](StateArchive& a) { a.array("part/x", wrong_length); })
                .find("'part/x' holds 5 items where the scene's model has 4"),
            std::string::npos);
  EXPECT_NE(refusal(p,
                    [&](StateArchive& a) {
                      std::vector<std::int32_t> v(5);
                      a.array("part/x", v);
                    })
                .find("'part/x' is not of type int32"),
            std::string::npos);
  struct Bigger {  // a record that grew a member since the checkpoint was written
    double a, b, c;
  };
  static_assert(sizeof(Record) == 16 && sizeof(Bigger) == 24);
  std::vector<Bigger> bigger;
  EXPECT_NE(refusal(p,
                    [&](StateArchive& a) {
                      a.array("part/records", bigger, StateArchive::Length::variable);
                    })
                .find("'part/records' holds records of 16 bytes where this femdem has 24"),
            std::string::npos);
  std::vector<double> missing(1);
  EXPECT_NE(refusal(p, [&](StateArchive& a) { a.array("part/nothing", missing); })
                .find("'part/nothing' is missing"),
            std::string::npos);
  // not a checkpoint, and not a whole file
  const fs::path junk = folder() / "junk.h5";
  std::ofstream(junk) << "not hdf5";
  EXPECT_THROW(read_checkpoint_info(junk), CheckpointError);
  const fs::path half = folder() / "half.h5";
  {
    std::ifstream in(p, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(half, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  EXPECT_THROW(read_checkpoint(half, [&](StateArchive& a) { s.exchange(a); }), CheckpointError);
  EXPECT_THROW(read_checkpoint_info(folder() / "absent.h5"), CheckpointError);
}

}  // namespace
}  // namespace femdem
