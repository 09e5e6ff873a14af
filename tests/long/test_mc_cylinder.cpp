// SPDX-License-Identifier: GPL-3.0-or-later
// Unconfined compression of the Mohr-Coulomb cylinder, the full scene
// (scenes/mc_cylinder_compression.toml; VALIDATION.md section 5; thesis section 4.4.3):
// 66.41 x 29.65 mm, E 35 GPa, nu 0.17, c 1.5 MPa, phi 15 deg, between two walls with friction
// that start from rest. Acceptance: the peak axial stress (wall force over the initial section)
// within 3 % of 2 c cos(phi) / (1 - sin(phi)) (3.91 MPa), computed from the scene's c and phi,
// and a shear band at 45 + phi/2 = 52.5 deg to the horizontal, measured by
// tools/plot_compression.py (a plane fitted through the most strained elements of the last
// frame).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/compression.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

TEST(McCylinder, PeakAndShearBandOfTheFullScene) {
  const fs::path out = fs::path(FEMDEM_TEST_TMP) / "long" / "mc_cylinder_compression";
  fs::remove_all(out);
  const auto r =
      femdem::test::run_command(std::string("'") + FEMDEM_EXE + "' run '" + FEMDEM_SOURCE_DIR +
                                "/scenes/mc_cylinder_compression.toml' --quiet "
                                "--threads 2 --out '" +
                                out.string() + "'");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto run = femdem::test::read_compression_run(out);
  EXPECT_EQ(run.model, "mohr_coulomb");
  const double peak = femdem::test::peak_stress(run);
  std::printf("%s: peak %.4f MPa, theory %.4f MPa (%+.2f %%); final strain %.4f\n",
              run.model.c_str(), peak / 1e6, run.theory_peak / 1e6,
              100.0 * (peak / run.theory_peak - 1.0), run.strain.back());
  EXPECT_NEAR(peak / run.theory_peak, 1.0, 0.03);
  EXPECT_GT(run.strain.back(), 0.03);

  // The band, from the last frame (strain about 3.5 %).
  const auto b =
      femdem::test::run_command(std::string("/usr/bin/python3 '") + FEMDEM_SOURCE_DIR +
                                "/tools/plot_compression.py' '" + out.string() + "' --json");
  ASSERT_EQ(b.code, 0) << b.output;
  const auto j = nlohmann::json::parse(b.output.substr(b.output.rfind("\n{") + 1));
  const double angle = j["band_angle_deg"].get<double>();
  std::printf("band angle %.1f deg (theory %.1f), thickness ratio %.2f\n", angle,
              run.theory_band_angle, j["band_thickness_ratio"].get<double>());
  EXPECT_NEAR(angle, run.theory_band_angle, 5.0);
}
