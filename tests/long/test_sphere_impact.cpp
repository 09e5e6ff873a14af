// SPDX-License-Identifier: GPL-3.0-or-later
// The thesis' elastic-plastic sphere (VALIDATION.md section 3; thesis 3.4.1): R 0.1 m, E 35 GPa,
// nu 0.3, von Mises sigma_y 0.1 GPa, rho 2500, h 0.015 m, onto a rigid wall, swept over 10, 20,
// 30 and 50 m/s with `femdem sweep`. Acceptance (reference notes, seed002-part1.md 3.9): the
// restitution falls with speed and follows Thornton (1997) with a fitted yield velocity; the
// thesis' numerical V_y = 7 m/s is an artefact of its coarse contact patch, the theory
// V_y = 1.56 sqrt(p_y^5 / (E*^4 rho)) gives 0.007 m/s (p_y = 1.6 sigma_y) to 0.028 m/s
// (p_y = 2.8 sigma_y). An elastic sphere comes back with e close to 1.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/scene_run.hpp"
#include "support/sweep_csv.hpp"

namespace {

namespace fs = std::filesystem;

double thornton(double v, double vy) {
  const double r = vy / v;
  if (r >= 1.0) return 1.0;
  return std::sqrt(6.0 * std::sqrt(3.0) / 5.0) * std::sqrt(1.0 - r * r / 6.0) *
         std::pow(r / (r + 2.0 * std::sqrt(1.2 - r * r / 5.0)), 0.25);
}

using femdem::test::split_csv_line;

}  // namespace

TEST(SphereImpact, RestitutionFollowsThorntonWithTheTheoreticalYieldVelocity) {
  const fs::path out = fs::path(FEMDEM_TEST_TMP) / "long" / "sphere_impact_sweep";
  fs::remove_all(out);
  const auto r = femdem::test::run_command(
      std::string("'") + FEMDEM_EXE + "' sweep '" + FEMDEM_SOURCE_DIR +
      "/scenes/sphere_impact.toml' --vary "
      "'bodies.ball.velocity=[0,0,-10],[0,0,-20],[0,0,-30],[0,0,-50]' --jobs 2 "
      "--threads-per-job 1 --no-plot --quiet --out '" +
      out.string() + "'");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(out / "sweep.csv");
  std::string line;
  std::getline(in, line);
  const auto header = split_csv_line(line);
  std::size_t ce = header.size();
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == "bodies.ball.coefficient_of_restitution.com") ce = i;
  ASSERT_LT(ce, header.size());
  const std::vector<double> speeds = {10, 20, 30, 50};
  std::vector<double> e;
  while (std::getline(in, line)) e.push_back(std::stod(split_csv_line(line)[ce]));
  ASSERT_EQ(e.size(), speeds.size());
  // least-squares V_y on a log grid, then refined
  auto cost = [&](double vy) {
    double c = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) c += std::pow(thornton(speeds[i], vy) - e[i], 2);
    return c;
  };
  double best = 1e-4;
  for (double vy = 1e-4; vy < 10.0; vy *= 1.01)
    if (cost(vy) < cost(best)) best = vy;
  const double rms = std::sqrt(cost(best) / e.size());
  for (std::size_t i = 0; i < e.size(); ++i)
    std::printf("V %.0f m/s: e %.4f, Thornton(fitted) %.4f\n", speeds[i], e[i],
                thornton(speeds[i], best));
  std::printf("fitted V_y %.4f m/s (theory 0.007-0.028), rms %.4f\n", best, rms);
  for (std::size_t i = 1; i < e.size(); ++i) EXPECT_LT(e[i], e[i - 1]);
  EXPECT_GT(best, 0.003);
  EXPECT_LT(best, 0.1);
  EXPECT_LT(rms, 0.03);
}

// A yield stress too high to reach makes the same sphere elastic.
TEST(SphereImpact, ElasticSphereComesBack) {
  const auto run =
      femdem::test::run_shipped_scene("sphere_impact.toml", "long/sphere_impact_elastic",
                                      "--set materials.soft_metal.yield_stress=1e15 --threads 2");
  ASSERT_EQ(run.command.code, 0) << run.command.output;
  const auto& s = run.summary;
  const auto& e = s["bodies"]["ball"]["coefficient_of_restitution"];
  ASSERT_FALSE(e.is_null());
  std::printf("elastic sphere at 20 m/s: e %.4f\n", e["com"].get<double>());
  EXPECT_GT(e["com"].get<double>(), 0.95);  // what is missing stays in elastic waves
}
