// SPDX-License-Identifier: GPL-3.0-or-later
// Elastic dynamics against analytic references (VALIDATION.md section 1): the bar's axial
// vibration (seed 003, section 3.4a) and the thesis' oscillating cube (thesis 3.3).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

ConstraintSpec constraint(RegionSpec::Kind kind, std::array<bool, 3> fix, Vec3 lo = Vec3::Zero(),
                          Vec3 hi = Vec3::Zero()) {
  ConstraintSpec c;
  c.body = 0;
  c.region.kind = kind;
  c.region.box_min = lo;
  c.region.box_max = hi;
  c.fix = fix;
  return c;
}

}  // namespace

// Bar: E = 100, rho = 1, nu = 0, L = 10, one end fixed, lateral rollers; initial velocity
// v0 sin(pi x / 2L) excites the fundamental mode only: T = 4L/c = 4.0, tip amplitude
// v0/omega1 = 0.6366 v0 L/c (seed 003 eqs. 15-16). Period within 1 %, energy within 0.5 %
// over 10 periods.
TEST(ElasticDynamics, BarVibrationPeriodAmplitudeAndEnergy) {
  ModelSpec s;
  MaterialParams mat;
  mat.name = "bar";
  mat.density = 1.0;
  mat.youngs_modulus = 100.0;
  mat.poisson_ratio = 0.0;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "bar";
  b.material = 0;
  b.mesh = test::kuhn_box(20, 1, 1, Vec3(10.0, 1.0, 1.0));
  s.bodies.push_back(b);
  s.constraints.push_back(constraint(RegionSpec::Kind::All, {false, true, true}));
  s.constraints.push_back(
      constraint(RegionSpec::Kind::Box, {true, true, true}, Vec3(-1, -1, -1), Vec3(0, 2, 2)));
  s.simulation.end_time = 40.0;
  Model m = build_model(s);
  const double v0 = 1e-3, L = 10.0, c = 10.0;
  for (int n = 0; n < m.node_count; ++n)
    if (m.dof_mode[3 * n] == 0) m.v[3 * n] = v0 * std::sin(M_PI * m.X[3 * n] / (2 * L));
  // tip node: the x = L corner at y = z = 0
  int tip = -1;
  for (int n = 0; n < m.node_count; ++n)
    if (std::fabs(m.X[3 * n] - L) < 1e-12 && std::fabs(m.X[3 * n + 1]) < 1e-12 &&
        std::fabs(m.X[3 * n + 2]) < 1e-12)
      tip = n;
  ASSERT_GE(tip, 0);
  Simulation sim(std::move(m));
  const double E0 = sim.energies().kinetic;
  double prev_u = 0.0, prev_t = 0.0, umax = 0.0, max_err = 0.0;
  std::vector<double> downward_crossings;
  while (sim.time() < 40.0) {
    sim.step();
    const double u = sim.model().x[3 * tip] - L;
    umax = std::max(umax, std::fabs(u));
    if (prev_u > 0.0 && u <= 0.0)
      downward_crossings.push_back(prev_t + (sim.time() - prev_t) * prev_u / (prev_u - u));
    prev_u = u;
    prev_t = sim.time();
    const Energies e = sim.energies();
    max_err = std::max(max_err, std::fabs(e.kinetic + e.internal - E0) / E0);
  }
  ASSERT_GE(downward_crossings.size(), 9u);
  const double period = (downward_crossings.back() - downward_crossings.front()) /
                        static_cast<double>(downward_crossings.size() - 1);
  std::printf(
      "bar: period %.5f (4.0), tip amplitude %.6g (%.6g), energy error %.3g %%, steps %lld\n",
      period, umax, 0.63662 * v0 * L / c, 100 * max_err, static_cast<long long>(sim.steps()));
  EXPECT_NEAR(period, 4.0, 0.01 * 4.0);
  EXPECT_NEAR(umax, 2.0 / M_PI * v0 * L / c, 0.01 * 2.0 / M_PI * v0 * L / c);
  EXPECT_LT(max_err, 0.005);
}

// Oscillating cube (thesis 3.3, L4957-5125): 1 m cube, base fixed, 1 m/s horizontal initial
// velocity, rho 1000, E 30 GPa, nu 0.3, elastic. The thesis reports a total energy error below
// 0.3 % over 3 ms.
class OscillatingCube : public ::testing::TestWithParam<FbarMode> {};

TEST_P(OscillatingCube, ConservesEnergy) {
  ModelSpec s;
  MaterialParams mat;
  mat.name = "concrete";
  mat.density = 1000.0;
  mat.youngs_modulus = 30e9;
  mat.poisson_ratio = 0.3;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "cube";
  b.material = 0;
  b.mesh = test::kuhn_box(8, 8, 8, Vec3(1, 1, 1), 0.15);
  b.velocity = Vec3(1.0, 0.0, 0.0);
  b.fbar = GetParam();  // every F-bar variant must keep the energy: their forces derive from it
  s.bodies.push_back(b);
  ConstraintSpec base;
  base.body = 0;
  base.region.kind = RegionSpec::Kind::Plane;
  base.fix = {true, true, true};
  s.constraints.push_back(base);
  s.simulation.end_time = 3e-3;
  Simulation sim(build_model(s));
  const double E0 = sim.energies().kinetic;
  EXPECT_NEAR(E0, 500.0, 500.0 * 0.1);  // 1/2 rho V v^2 less the fixed base
  double max_err = 0.0, max_internal = 0.0;
  while (sim.time() < 3e-3) {
    sim.step();
    const Energies e = sim.energies();
    max_err = std::max(max_err, std::fabs(e.kinetic + e.internal - E0) / E0);
    max_internal = std::max(max_internal, e.internal);
  }
  std::printf(
      "cube (F-bar %s): energy error %.4f %%, peak elastic energy %.1f J of %.1f J, %lld steps\n",
      to_string(GetParam()), 100 * max_err, max_internal, E0, static_cast<long long>(sim.steps()));
  EXPECT_GT(max_internal, 0.9 * E0);  // it really oscillates
  EXPECT_LT(max_err, 0.003);
  EXPECT_LT(std::fabs(sim.balance_error()), 0.003);
}

INSTANTIATE_TEST_SUITE_P(Fbar, OscillatingCube,
                         ::testing::Values(FbarMode::Off, FbarMode::VolumeAverage,
                                           FbarMode::Centroid, FbarMode::Nodal, FbarMode::SubTet),
                         [](const auto& info) { return std::string(to_string(info.param)); });
