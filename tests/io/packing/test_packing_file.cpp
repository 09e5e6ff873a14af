// SPDX-License-Identifier: GPL-3.0-or-later
// The packing file (io/packing/packing.hpp): a saved packing reads back exactly, a hand-written
// file needs only the column line, bad files name the line, and the shipped die packing is
// valid.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "engine/errors.hpp"
#include "io/packing/packing.hpp"
#include "support/packing_checks.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::InputError;
using femdem::Packing;
using femdem::PackingParams;
using femdem::Vec3;
using femdem::test::expect_inside;
using femdem::test::min_relative_gap;
using femdem::test::random_box;
using femdem::test::tmp_dir;
using femdem::test::write_text;

TEST(Packing, SaveLoadRoundTrip) {
  PackingParams p = random_box(60, 5.0, 10.0);
  p.shape = "grain";
  const Packing pk = femdem::generate_packing(p);
  const fs::path file = tmp_dir("roundtrip") / "grains.csv";
  femdem::write_packing(file.string(), pk);
  const Packing back = femdem::read_packing(file.string());
  ASSERT_EQ(back.particles.size(), pk.particles.size());
  for (std::size_t i = 0; i < pk.particles.size(); ++i) {
    EXPECT_EQ(back.particles[i].centre, pk.particles[i].centre);
    EXPECT_EQ(back.particles[i].radius, pk.particles[i].radius);
    EXPECT_EQ(back.particles[i].orientation.coeffs(), pk.particles[i].orientation.coeffs());
    EXPECT_EQ(back.particles[i].shape, "grain");
  }
  EXPECT_EQ(back.params_text, femdem::packing_params_text(p));
  EXPECT_EQ(back.generator, pk.generator);
  // a hand-written file needs only the column line
  write_text(file, "id,shape,x,y,z,radius,qw,qx,qy,qz\n1,sphere,0,0,1,1,1,0,0,0\n");
  EXPECT_EQ(femdem::read_packing(file.string()).particles.size(), 1u);
}

TEST(Packing, BadFilesNameTheLine) {
  const fs::path dir = tmp_dir("badfiles");
  const std::string head = "# x\nid,shape,x,y,z,radius,qw,qx,qy,qz\n";
  struct Case {
    std::string text;
    int line;
    std::string contains;
  } cases[] = {
      {"id,x,y\n", 1, "column line"},
      {head + "1,sphere,0,0,1,1,1,0,0\n", 3, "10 fields"},
      {head + "1,sphere,0,zero,1,1,1,0,0,0\n", 3, "'zero'"},
      {head + "1,sphere,0,0,1,-1,1,0,0,0\n", 3, "radius"},
      {head + "1,sphere,0,0,1,1,1,0,0,0\n2,sphere,0,0,1,1,2,0,0,0\n", 4, "unit length"},
      {head, 0, "no particles"},
  };
  for (const auto& c : cases) {
    write_text(dir / "bad.csv", c.text);
    try {
      femdem::read_packing((dir / "bad.csv").string());
      ADD_FAILURE() << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line, c.line) << e.describe();
      EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.describe();
    }
  }
  EXPECT_THROW(femdem::read_packing((dir / "missing.csv").string()), InputError);
}

// The shipped packing for die compaction (scenes/packings/powder_die_250.csv, written by the
// `femdem pack` command in docs/OUTPUTS.md): complete, without overlaps, inside its die.
TEST(Packing, ShippedDiePackingIsValid) {
  const Packing pk =
      femdem::read_packing(std::string(FEMDEM_SOURCE_DIR) + "/scenes/packings/powder_die_250.csv");
  ASSERT_EQ(pk.particles.size(), 250u);
  PackingParams p;
  p.container = "cylinder";
  p.radius = 4e-3;
  p.height = 12e-3;
  EXPECT_GE(min_relative_gap(pk), 0.0);
  expect_inside(p, pk);
  EXPECT_NE(pk.params_text.find("count = 250"), std::string::npos) << pk.params_text;
  EXPECT_NE(pk.params_text.find("friction = 0.5"), std::string::npos) << pk.params_text;
}

}  // namespace
