// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The packing tests (tests/io/packing/test_packing*.cpp, tests/tools/test_pack_command.cpp):
// a fresh folder per test, small file helpers, brute-force checks of a packing (no overlap,
// inside its container) and a small random box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "io/packing/packing.hpp"

namespace femdem::test {

inline std::filesystem::path tmp_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(FEMDEM_TEST_TMP) / "packing" / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// Brute force over all pairs: the smallest (distance - r_i - r_j) / (r_i + r_j).
inline double min_relative_gap(const Packing& pk) {
  double g = std::numeric_limits<double>::infinity();
  const auto& ps = pk.particles;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      const double rs = ps[i].radius + ps[j].radius;
      g = std::min(g, ((ps[i].centre - ps[j].centre).norm() - rs) / rs);
    }
  return g;
}

// Every particle inside the container (top included), within a relative tolerance.
inline void expect_inside(const PackingParams& p, const Packing& pk, double tol = 1e-9) {
  for (const auto& q : pk.particles) {
    const Vec3& c = q.centre;
    const double r = q.radius, t = tol * r;
    if (p.container == "box") {
      EXPECT_GE(c.x() - r, -t);
      EXPECT_GE(c.y() - r, -t);
      EXPECT_GE(c.z() - r, -t);
      EXPECT_LE(c.x() + r, p.size.x() + t);
      EXPECT_LE(c.y() + r, p.size.y() + t);
      EXPECT_LE(c.z() + r, p.size.z() + t);
    } else {
      EXPECT_LE(std::hypot(c.x(), c.y()) + r, p.radius + t);
      EXPECT_GE(c.z() - r, -t);
      EXPECT_LE(c.z() + r, p.height + t);
    }
  }
}

inline PackingParams random_box(std::int64_t count, double side_d, double height_d) {
  PackingParams p;
  const double d = 1e-3;
  p.size = Vec3(side_d * d, side_d * d, height_d * d);
  p.arrangement = "random";
  p.count = count;
  p.diameter = d;
  p.seed = 7;
  return p;
}

}  // namespace femdem::test
