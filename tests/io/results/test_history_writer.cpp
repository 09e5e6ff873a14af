// SPDX-License-Identifier: GPL-3.0-or-later
// HistoryWriter: header, exact round trip of doubles, flushing, and the standard columns.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

#include "io/results/history_writer.hpp"

namespace fs = std::filesystem;
using namespace femdem;

namespace {

fs::path test_file(const std::string& name) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "history_writer";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

double parse(const std::string& s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  EXPECT_EQ(r.ec, std::errc()) << s;
  return v;
}

}  // namespace

TEST(HistoryWriter, HeaderAndExactRoundTrip) {
  const fs::path p = test_file("roundtrip.csv");
  const std::vector<double> row1 = {0.0, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 0.1 + 0.2};
  const std::vector<double> row2 = {std::nextafter(1.0, 2.0), -0.0, 1e-7, 123456789.0, 5e-324};
  {
    HistoryWriter h(p, {"time", "dt", "a", "b", "c"}, 0.0);
    EXPECT_EQ(lines_of(p).size(), 1u);  // the header is on disk at once
    h.write_row(row1);
    EXPECT_EQ(lines_of(p).size(), 2u);  // flush interval 0: every row
    h.write_row(row2);
    EXPECT_EQ(h.rows(), 2);
    EXPECT_THROW(h.write_row(std::vector<double>{1.0}), std::invalid_argument);
  }
  const auto lines = lines_of(p);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "time,dt,a,b,c");
  for (int r = 0; r < 2; ++r) {
    const auto f = split(lines[r + 1]);
    const auto& want = r == 0 ? row1 : row2;
    ASSERT_EQ(f.size(), want.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double got = parse(f[i]);
      EXPECT_EQ(got, want[i]) << f[i];
      EXPECT_EQ(std::signbit(got), std::signbit(want[i])) << f[i];
    }
  }
  EXPECT_EQ(split(lines[1])[1], "0.3333333333333333");  // shortest round trip, not %.17g noise
}

TEST(HistoryWriter, NonFiniteAndQuotedNames) {
  const fs::path p = test_file("nonfinite.csv");
  {
    HistoryWriter h(p, {"time", "odd,name", "q\"uote"});
    h.write_row(std::vector<double>{std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::infinity(),
                                    -std::numeric_limits<double>::infinity()});
  }
  const auto lines = lines_of(p);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "time,\"odd,name\",\"q\"\"uote\"");
  EXPECT_EQ(lines[1], "nan,inf,-inf");
}

TEST(HistoryWriter, BuffersUntilIntervalAndFlushes) {
  const fs::path p = test_file("interval.csv");
  HistoryWriter h(p, {"time"}, 3600.0);
  for (int i = 0; i < 100; ++i) h.write_row(std::vector<double>{double(i)});
  EXPECT_EQ(lines_of(p).size(), 1u);  // only the header so far
  h.flush();
  EXPECT_EQ(lines_of(p).size(), 101u);
  h.close();
  EXPECT_THROW(h.write_row(std::vector<double>{1.0}), std::logic_error);
}

// A writer killed at an arbitrary moment leaves complete lines. The writer hands the kernel
// pieces that end on a line break and stay inside one page of the file, which SIGKILL cannot
// cut; only a row that straddles a page boundary is written across it, and a kill landing inside
// that one write() can leave its head as a last line without '\n' (seen once in CI before the
// page-aligned pieces, when whole 1 MiB buffers went in one write()). So: every line but the
// last is a complete, correct row, and the last is either complete or a prefix of the next row.
TEST(HistoryWriter, KilledWriterLeavesCompleteLines) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    const fs::path p = test_file("killed.csv");
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      HistoryWriter h(p, {"time", "a", "b", "c", "d", "e", "f", "g"}, 0.001);
      std::vector<double> row(8);
      for (long i = 0;; ++i) {
        for (int c = 0; c < 8; ++c) row[c] = i + c / 7.0;
        h.write_row(row);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100 + 37 * attempt));
    kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    std::ifstream in(p, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(text.empty());
    std::string tail;
    if (text.back() != '\n') {
      tail = text.substr(text.rfind('\n') + 1);
      text.resize(text.size() - tail.size());
    }
    std::vector<std::string> lines;
    for (std::size_t b = 0, e; (e = text.find('\n', b)) != std::string::npos; b = e + 1) {
      lines.push_back(text.substr(b, e - b));
    }
    ASSERT_GT(lines.size(), 10u);
    std::string expected;
    for (std::size_t l = 1; l <= lines.size(); ++l) {
      std::vector<double> row(8);
      for (int c = 0; c < 8; ++c) row[c] = double(l - 1) + c / 7.0;
      expected.clear();
      for (int c = 0; c < 8; ++c) {
        char buf[32];
        const auto r = std::to_chars(buf, buf + sizeof buf, row[c]);
        if (c) expected += ',';
        expected.append(buf, r.ptr);
      }
      if (l == lines.size()) break;  // `expected` is now the row after the last complete one
      ASSERT_EQ(lines[l], expected) << "line " << l;
    }
    if (!tail.empty()) {
      EXPECT_EQ(expected.compare(0, tail.size(), tail), 0) << "torn last line '" << tail << "'";
    }
  }
}
