// SPDX-License-Identifier: GPL-3.0-or-later
// Unconfined compression of the Mohr-Coulomb cylinder (VALIDATION.md section 5;
// scenes/mc_cylinder_compression.toml), on a coarse mesh and only up to the peak, so that it
// runs in the default suite. Frictionless walls keep the state homogeneous, so the peak axial
// stress is exactly the unconfined strength 2 c cos(phi) / (1 - sin(phi)), computed here from
// the scene's c and phi. The full scene (mesh, friction, shear band) is tests/long.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "support/compression.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

TEST(CylinderCompression, CoarseFrictionlessPeakIsTheUnconfinedStrength) {
  const fs::path out = fs::path(FEMDEM_TEST_TMP) / "scenes" / "mc_cylinder_coarse";
  fs::remove_all(out);
  // 7.5 mm elements (864 TET10), frictionless walls, and a quicker start than the scene's (to
  // 0.1 m/s in 0.2 ms, held): 0.55 ms takes the walls past 1.2e-3 axial strain, ten times the
  // elastic limit, where the peak has long been reached. The wall speed at yield (6 cm/s) costs
  // about 1 % of dynamic overshoot (the scene's 2 cm/s about 0.4 %).
  const auto r = femdem::test::run_command(
      std::string("'") + FEMDEM_EXE + "' run '" + FEMDEM_SOURCE_DIR +
      "/scenes/mc_cylinder_compression.toml' --quiet --threads 2 --out '" + out.string() +
      "' --set bodies.cylinder.mesh.element_size=7.5e-3 --set simulation.end_time=0.55e-3"
      " --set simulation.output_interval=0.275e-3 --set walls.bottom.friction=0"
      " --set walls.top.friction=0"
      " --set 'walls.bottom.velocity_history=[[0, 0, 0, 0], [2e-4, 0, 0, 0.1]]'"
      " --set 'walls.top.velocity_history=[[0, 0, 0, 0], [2e-4, 0, 0, -0.1]]'");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto run = femdem::test::read_compression_run(out);
  EXPECT_EQ(run.model, "mohr_coulomb");
  ASSERT_GT(run.strain.back(), 1.2e-3);
  const double peak = femdem::test::peak_stress(run);
  std::printf("%s: peak %.4f MPa, theory %.4f MPa (%+.2f %%)\n", run.model.c_str(), peak / 1e6,
              run.theory_peak / 1e6, 100.0 * (peak / run.theory_peak - 1.0));
  EXPECT_NEAR(peak / run.theory_peak, 1.0, 0.03);
}
