// SPDX-License-Identifier: GPL-3.0-or-later
// Sharpness of the assembled stable step on a plastic impact: the Taylor bar of
// scenes/taylor_bar.toml on its 1.6 mm mesh, without mass scaling, to 40 us (the foot is crushed
// and the step has fallen to its smallest by then). A run at a fixed step equal to the smallest
// estimated limit of the automatic run stays stable; at 1.25 times it, it diverges and stops with
// exit code 3: the estimate is within 25 % of the true limit, on the safe side. (Central
// differences are stable for omega dt <= 2; measured 2026-12-02: stable at 1.0, caught at 1.25,
// 1.5 and 2.0 times.)
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "support/sanitizers.hpp"
#include "support/scene_run.hpp"

namespace {

const std::string kOptions =
    "--no-plot --threads 1 --set simulation.mass_scaling_time_step=0 "
    "--set bodies.rod.mesh.element_size=1.6e-3 --set simulation.stable_step=assembled "
    "--set simulation.end_time=40e-6 --set simulation.time_step_safety=0.8 ";

}  // namespace

TEST(StableStep, PlasticImpactIsSharp) {
  if (femdem::test::kUnderSanitizers)
    GTEST_SKIP() << femdem::test::kSkippedUnderSanitizers
                 << "a measurement of the estimate's sharpness; its code runs in "
                    "HighestFrequency.* and every scene test, the stop on divergence in "
                    "HostileInput.AStepFarAboveTheStableOneStopsOnTheEnergyBalance";
  const auto automatic =
      femdem::test::run_shipped_scene("taylor_bar.toml", "stable_step/auto", kOptions);
  ASSERT_EQ(automatic.command.code, 0) << automatic.command.output;
  ASSERT_TRUE(automatic.summary.contains("extra"));
  const double safety = 0.8;  // as set above (the default): dt = safety x the estimated limit
  const auto& dt = automatic.history.at("dt");
  // the smallest step of the run, away from the last (shortened to land on end_time)
  const double smallest_limit = *std::min_element(dt.begin(), dt.end() - 1) / safety;
  EXPECT_GT(automatic.summary["extra"]["stable_step_estimates"].get<double>(), 10);

  char at_limit[64], above[64];
  std::snprintf(at_limit, sizeof at_limit, "--set simulation.time_step=%.6e", smallest_limit);
  std::snprintf(above, sizeof above, "--set simulation.time_step=%.6e", 1.25 * smallest_limit);
  const auto stable = femdem::test::run_shipped_scene("taylor_bar.toml", "stable_step/at_limit",
                                                      kOptions + at_limit);
  EXPECT_EQ(stable.command.code, 0) << stable.command.output;
  const auto unstable =
      femdem::test::run_shipped_scene("taylor_bar.toml", "stable_step/above", kOptions + above);
  EXPECT_EQ(unstable.command.code, 3) << unstable.command.output;
}
