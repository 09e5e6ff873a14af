// SPDX-License-Identifier: GPL-3.0-or-later
// The 64-sphere die compaction (scenes/compaction_64_spheres.toml; thesis section 6.3.2) in
// small: 8 spheres of 2.5 mm in simple-cubic 2 x 2 x 2 order in a rigid 5 mm box, lid pressed
// to about 4 % strain, through the femdem program and its [compaction] columns. Checked
// against the geometry alone, not against earlier output:
// - the initial relative density is the lattice's, pi/6, within 1e-3 with the 2-cells-per-radius
//   sphere (a run of one step: the volume of 384 curved TET10 is within 4e-4 of the sphere's);
//   the coarse sphere of the run (48 TET10, 1 cell per radius) holds 0.56 % less, so there
//   pi/6 within 1e-2;
// - D follows the geometric estimate D0 x (V/V0) x h0 / h, with h the floor-lid gap from the
//   walls' own position columns and A the box's 25 mm^2 (not the compaction columns);
// - the spheres keep their volume within 1 % (von Mises flow is isochoric; only the elastic
//   compression, of order p / K = 1e-4 here, changes it);
// - with frictionless box walls the lid force equals the floor force once the packing carries
//   the load quasi-statically (averaged over the last quarter of the run: node-penalty contact
//   on a coarse mesh makes the force a staircase, see docs/VALIDATION.md section 6).
// Same material, contact (automatic stiffness, the defaults' step) and lid speed (1 m/s after
// a 0.1 ms ramp) as the 64-sphere scene, coarse mesh (48 TET10 per sphere).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "support/history_csv.hpp"
#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

const char* const kScene = R"(title = "8 spheres in simple-cubic order"
[simulation]
end_time = 2.7e-4
output_interval = 2.7e-4
history_interval = 2e-6
[[materials]]
name = "powder"
model = "von_mises"
density = 7800.0
youngs_modulus = 110e9
poisson_ratio = 0.3
yield_stress = 30e6
hardening_modulus = 0.1e9
[[packings]]
name = "p"
material = "powder"
mesh = { generator = "sphere", cells_per_radius = 1 }
generate = { container = "box", size = [0.005, 0.005, 0.005], arrangement = "simple_cubic", diameter = 2.5e-3, orientation = "random", seed = 1 }
[contact]
friction = 0.15
[[walls]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
[[walls]]
name = "lid"
point = [0.0, 0.0, 0.005]
normal = [0.0, 0.0, -1.0]
velocity_history = [[0.0, 0.0, 0.0, 0.0], [1e-4, 0.0, 0.0, -1.0]]
[[walls]]
name = "x0"
point = [0.0, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
[[walls]]
name = "x1"
point = [0.005, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
[[walls]]
name = "y0"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
[[walls]]
name = "y1"
point = [0.0, 0.005, 0.0]
normal = [0.0, -1.0, 0.0]
[compaction]
punch = "lid"
bottom = "floor"
die_walls = ["x0", "x1", "y0", "y1"]
die_area = 2.5e-5
die_perimeter = 0.02
)";

std::map<std::string, std::vector<double>> run(const std::string& name, const std::string& sets) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "compaction_spheres" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml") << kScene;
  const auto r = femdem::test::run_command(
      std::string("'") + FEMDEM_EXE + "' run '" + (dir / "scene.toml").string() +
      "' --quiet --no-plot --threads 1 --out '" + (dir / "out").string() + "' " + sets);
  EXPECT_EQ(r.code, 0) << r.output;
  return femdem::test::read_history(dir / "out" / "history.csv");
}

}  // namespace

TEST(CompactionSpheres, EightSimpleCubicSpheresDensifyAsTheGeometrySays) {
  const double lattice = std::numbers::pi / 6.0;
  {
    const auto h0 = run("start",
                        "--set packings.p.mesh.cells_per_radius=2 --set "
                        "simulation.end_time=1e-7 --set simulation.history_interval=1e-7 "
                        "--set simulation.output_interval=1e-7");
    ASSERT_TRUE(h0.count("compaction.relative_density")) << "no compaction columns";
    EXPECT_NEAR(h0.at("compaction.relative_density").front(), lattice, 1e-3);
  }
  const auto h = run("run", "");
  ASSERT_TRUE(h.count("compaction.relative_density")) << "no compaction columns";
  const auto& D = h.at("compaction.relative_density");
  const auto& C = h.at("compaction.column_strain");
  const auto& vr = h.at("compaction.volume_ratio");
  const auto& punch = h.at("compaction.punch_force");
  const auto& bottom = h.at("compaction.bottom_force");
  const std::size_t n = D.size();
  ASSERT_GT(n, 100u);

  EXPECT_NEAR(D.front(), lattice, 1e-2);
  EXPECT_GT(C.back(), 0.03);  // pressed past 3 % strain

  const auto& lid = h.at("lid.position_z");
  const auto& floor = h.at("floor.position_z");
  const double area = 25e-6, gap0 = lid.front() - floor.front();
  EXPECT_NEAR(gap0, 5e-3, 1e-12);
  double max_dv = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    max_dv = std::max(max_dv, std::abs(vr[i] - 1.0));
    const double gap = lid[i] - floor[i];
    const double estimate = D.front() * vr[i] * gap0 / gap;
    EXPECT_NEAR(D[i] / estimate, 1.0, 1e-9) << "row " << i;
    EXPECT_NEAR(C[i], 1.0 - gap / gap0, 1e-12) << "row " << i;
  }
  // and the initial D is the powder's volume over the box
  EXPECT_NEAR(D.front() * area * gap0 / h.at("compaction.solid_volume").front(), 1.0, 1e-12);
  EXPECT_LT(max_dv, 0.01);
  EXPECT_GT(D.back(), D.front() / (1.0 - C.back()) * 0.99);  // D rose with the strain

  double sum_punch = 0.0, sum_bottom = 0.0;
  for (std::size_t i = 3 * n / 4; i < n; ++i) {
    sum_punch += punch[i];
    sum_bottom += bottom[i];
  }
  std::printf(
      "D %.5f -> %.5f at strain %.4f (estimate %.5f); max |V/V0 - 1| %.2e; "
      "lid %.1f N, floor %.1f N (last quarter means)\n",
      D.front(), D.back(), C.back(), D.front() * vr.back() / (1.0 - C.back()), max_dv,
      sum_punch / (n - 3 * n / 4), sum_bottom / (n - 3 * n / 4));
  EXPECT_GT(sum_punch, 0.0);
  EXPECT_NEAR(sum_bottom / sum_punch, 1.0, 0.03);
}
