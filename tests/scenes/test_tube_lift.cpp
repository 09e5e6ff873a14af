// SPDX-License-Identifier: GPL-3.0-or-later
// A tube ([[tubes]]) lifted off what it holds, through the femdem program. A 4 mm elastic cube
// stands in a square tube whose sides press 10 um into each of its four faces; the tube rests
// while deformation damping settles the cube's ringing (a granular column is at rest when its
// tube is lifted), then rises at 2 m/s. Answers that follow from the geometry alone:
// - the sides' extent travels with the tube: once its lower end has passed the cube's top face
//   every side carries exactly nothing (with a fixed extent they would squeeze the cube for ever);
// - the tube moves by the exact integral of its velocity history;
// - frictionless sides push only across the axis: the cube gets no vertical momentum while the
//   tube covers it; with friction 0.3 the squeezed cube is carried up with the tube (the sides'
//   friction sees their own motion along their plane);
// - a side is thin: a second body standing beyond the +x side (further behind its plane than
//   the tube's thickness) is outside the tube and is never touched (a half-space wall would
//   throw it with a 2 mm overlap);
// - the release closes the energy balance (the plate's ends push the nodes out continuously:
//   with an extent that cut nodes off, a node re-entering it deep behind the side created a
//   quarter of the run's energy in a step).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/scene_run.hpp"

namespace {

struct TubeRun {
  std::map<std::string, std::vector<double>> h;
};

TubeRun run_tube(const std::string& name, double friction) {
  const std::string text = R"(title = "tube lift"
[simulation]
end_time = 5e-3
output_interval = 2.5e-3
history_interval = 2e-5
deformation_damping = { ratio = 0.5, frequency = 20000.0 }
[[materials]]
name = "m"
model = "elastic"
density = 1000
youngs_modulus = 1e9
poisson_ratio = 0.3
[[bodies]]
name = "cube"
material = "m"
mesh = { generator = "box", size = [4e-3, 4e-3, 4e-3], element_size = 2e-3 }
[[bodies]]
name = "outside"
material = "m"
mesh = { generator = "box", size = [4e-3, 2e-3, 4e-3], element_size = 2e-3 }
position = [6e-3, 1e-3, 0]
[[tubes]]
name = "tube"
centre = [2e-3, 2e-3, -1e-3]
radius = 1.99e-3
sides = 4
height = 6e-3
thickness = 2e-4
friction = )" + std::to_string(friction) +
                           R"(
velocity_history = [[0, 0, 0, 0], [1e-3, 0, 0, 0], [1.1e-3, 0, 0, 2]]
[contact]
initial_overlap = 0.05
)";
  const auto run = femdem::test::run_scene_text("tube_lift/" + name, text);
  EXPECT_EQ(run.command.code, 0) << run.command.output;
  return {run.history};
}

// the tube's lift: at rest to 1 ms, 0 -> 2 m/s over 0.1 ms, then 2 m/s
double lift(double t) {
  if (t <= 1e-3) return 0.0;
  if (t <= 1.1e-3) return 0.5 * 2e4 * (t - 1e-3) * (t - 1e-3);
  return 1e-4 + 2.0 * (t - 1.1e-3);
}

double side_force(const TubeRun& r, std::size_t i) {
  double f = 0.0;
  for (int k = 1; k <= 4; ++k) {
    const std::string w = "tube_" + std::to_string(k);
    f +=
        std::hypot(r.h.at(w + ".force_x")[i], r.h.at(w + ".force_y")[i], r.h.at(w + ".force_z")[i]);
  }
  return f;
}

}  // namespace

TEST(TubeLift, AFrictionlessTubeLetsGoOfWhatItHeldOnceItsLowerEndHasPassed) {
  const TubeRun r = run_tube("frictionless", 0.0);
  const auto& t = r.h.at("time");
  ASSERT_GT(t.size(), 200u);
  // the lower end (at z = -1 mm + lift) passes the cube's top face (z = 4 mm) at 3.55 ms
  const double t_free = 1.1e-3 + (5e-3 - 1e-4) / 2.0;
  double held = 0.0;
  std::size_t n_held = 0, n_free = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (int k = 1; k <= 4; ++k)
      EXPECT_NEAR(r.h.at("tube_" + std::to_string(k) + ".position_z")[i], -1e-3 + lift(t[i]), 1e-12)
          << "t = " << t[i];
    // while the tube covers the cube its sides push across the axis only: no vertical momentum
    // but the round-off of the internal forces' sum. As the lower end passes each row of
    // squeezed nodes, the plate's end pushes the released bulge down (for each node about
    // k d^2 / (2 v): d its squeeze, v the lift speed), never up: an end that cut into nodes from
    // below would throw the cube upwards. The squeezed cube is spat out of the sleeve, as a
    // cork from a bottle neck pulled off it: measured -0.26 m/s once the bottom face is out,
    // -1.71 m/s at the end, 1 % of the squeeze's energy (89 N per side: extreme; the grains of
    // a settled column carry their weight only).
    if (t[i] < 1.5e-3) {
      EXPECT_LT(std::fabs(r.h.at("cube.vcom_z")[i]), 1e-12) << "t = " << t[i];
    }
    EXPECT_LT(r.h.at("cube.vcom_z")[i], 1e-12) << "t = " << t[i];
    // outside the tube: never touched
    EXPECT_EQ(r.h.at("outside.vcom_x")[i], 0.0) << "t = " << t[i];
    EXPECT_EQ(r.h.at("outside.com_x")[i], r.h.at("outside.com_x").front());
    if (t[i] > 0.2e-3 && t[i] < 1.5e-3) held += side_force(r, i), ++n_held;
    if (t[i] > t_free + 0.02e-3) {
      EXPECT_EQ(side_force(r, i), 0.0) << "t = " << t[i];
      ++n_free;
    }
  }
  held /= static_cast<double>(n_held);
  std::printf("mean force of the four sides while they hold the cube: %.4g N\n", held);
  EXPECT_GT(held, 1.0);  // 10 um into a 1 GPa cube: tens of newtons
  EXPECT_GT(n_free, 50u);
  const auto& e = r.h.at("energy_balance_error");
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_LT(std::fabs(e[i]), 0.01) << "t = " << t[i];
}

TEST(TubeLift, AFrictionalTubeCarriesTheCubeItSqueezes) {
  const TubeRun r = run_tube("friction", 0.3);
  const auto& t = r.h.at("time");
  const std::size_t last = t.size() - 1;
  // stuck to the sides, the cube rises with the tube and keeps being held
  EXPECT_NEAR(r.h.at("cube.vcom_z")[last], 2.0, 0.05);
  EXPECT_NEAR(r.h.at("cube.com_z")[last] - r.h.at("cube.com_z").front(), lift(t[last]),
              0.05 * lift(t[last]));
  EXPECT_GT(side_force(r, last), 1.0);
  EXPECT_EQ(r.h.at("outside.vcom_x")[last], 0.0);
}
