// SPDX-License-Identifier: GPL-3.0-or-later
// Loads and supports: gravity, prescribed-velocity constraints and moving walls do the work the
// energy balance says they do, and bodies move as they should.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

ModelSpec block(double E = 1e9) {
  ModelSpec s;
  MaterialParams mat;
  mat.name = "rubbery";
  mat.density = 1000.0;
  mat.youngs_modulus = E;
  mat.poisson_ratio = 0.3;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = test::kuhn_box(3, 3, 3, Vec3(0.1, 0.1, 0.1), 0.2);
  s.bodies.push_back(b);
  return s;
}

// The block with its base held and its top face driven along z at `speed`.
ModelSpec driven_block(double speed) {
  ModelSpec s = block();
  ConstraintSpec base;
  base.body = 0;
  base.region.kind = RegionSpec::Kind::Plane;
  base.fix = {true, true, true};
  s.constraints.push_back(base);
  ConstraintSpec top;
  top.body = 0;
  top.region.kind = RegionSpec::Kind::Plane;
  top.region.plane_point = Vec3(0, 0, 0.1);
  top.velocity = Vec3(0.0, 0.0, speed);
  s.constraints.push_back(top);
  return s;
}

}  // namespace

// Free fall: the centre of mass follows z0 + v0 t - g t^2 / 2 and kinetic energy equals the
// work of gravity.
TEST(Loading, FreeFallUnderGravity) {
  ModelSpec s = block();
  s.simulation.gravity = Vec3(0, 0, -9.81);
  s.bodies[0].velocity = Vec3(0, 0, 2.0);
  Simulation sim(build_model(s));
  const double z0 = sim.body_motion(0).com.z();
  while (sim.time() < 2e-3) sim.step();
  const double t = sim.time();
  const BodyState b = sim.body_motion(0);
  EXPECT_NEAR(b.com.z(), z0 + 2.0 * t - 0.5 * 9.81 * t * t, 1e-12);
  EXPECT_NEAR(b.vcom.z(), 2.0 - 9.81 * t, 1e-10);
  const Energies e = sim.energies();
  EXPECT_GT(std::fabs(e.external_work), 0.0);
  EXPECT_LT(std::fabs(sim.balance_error()), 1e-9);
}

// A prescribed velocity on the top face drives the block against its fixed base: the top moves
// exactly as prescribed, and the work of the driving supports balances the stored energy.
TEST(Loading, PrescribedVelocityWorkIsAccounted) {
  Simulation sim(build_model(driven_block(-0.5)));
  while (sim.time() < 2e-3) sim.step();
  const Model& m = sim.model();
  for (int n = 0; n < m.node_count; ++n) {
    if (std::fabs(m.X[3 * n + 2] - 0.1) < 1e-12) {
      ASSERT_NEAR(m.x[3 * n + 2] - m.X[3 * n + 2], -0.5 * sim.time(), 1e-12);
    }
  }
  const Energies e = sim.energies();
  std::printf("driven block: external work %.4g J, elastic %.4g J, kinetic %.4g J, balance %.2e\n",
              e.external_work, e.internal, e.kinetic, sim.balance_error());
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_GT(e.internal, 0.1 * e.external_work);
  EXPECT_LT(std::fabs(sim.balance_error()), 2e-3);
}

// A wall moving at 0.5 m/s into a resting block pushes it: the block gains momentum in the
// wall's direction and the wall's work equals the energy the block holds.
TEST(Loading, MovingWallWorkIsAccounted) {
  ModelSpec s = block();
  WallSpec w;
  w.name = "pusher";
  w.point = Vec3(0, 0, -1e-4);
  w.normal = Vec3(0, 0, 1);
  w.velocity = Vec3(0, 0, 0.5);
  s.walls.push_back(w);
  Simulation sim(build_model(s));
  while (sim.time() < 3e-3) sim.step();
  const BodyState b = sim.body_motion(0);
  const Energies e = sim.energies();
  std::printf("pushed block: vcom_z %.4f m/s, wall work %.4g J, kinetic %.4g J, balance %.2e\n",
              b.vcom.z(), e.external_work, e.kinetic, sim.balance_error());
  EXPECT_GT(b.vcom.z(), 0.3);
  EXPECT_GT(e.external_work, 0.0);
  EXPECT_LT(std::fabs(sim.balance_error()), 2e-3);
  EXPECT_LT(sim.wall_force(0).z(),
            0.0 + 1e-300);  // the block pushes back on the wall (or not at all)
}

// A wall with a velocity history: its velocity is the piecewise-linear history (held after the
// last point) and its position the exact integral, whatever the steps.
TEST(Loading, WallFollowsItsVelocityHistory) {
  ModelSpec s = block();
  WallSpec w;
  w.name = "far";
  w.point = Vec3(0.5, 0, -1.0);  // far below the block: no contact
  w.normal = Vec3(0, 0, 1);
  w.velocity_history = {{0.0, Vec3(0, 0, 0)}, {1e-3, Vec3(0, 0, 1)}, {2e-3, Vec3(2, 0, -1)}};
  s.walls.push_back(w);
  Simulation sim(build_model(s));
  auto expected_z = [](double t) {  // integral of vz, by hand
    if (t <= 1e-3) return -1.0 + 0.5 * t * t / 1e-3;
    if (t <= 2e-3) return -1.0 + 0.5e-3 + (t - 1e-3) - (t - 1e-3) * (t - 1e-3) / 1e-3;
    return -1.0 + 0.5e-3 - (t - 2e-3);
  };
  auto expected_x = [](double t) {
    if (t <= 1e-3) return 0.5;
    if (t <= 2e-3) return 0.5 + (t - 1e-3) * (t - 1e-3) / 1e-3;
    return 0.5 + 1e-3 + 2.0 * (t - 2e-3);
  };
  int checked = 0;
  while (sim.time() < 3e-3) {
    sim.step();
    const double t = sim.time();
    const Vec3 p = sim.wall_position(0);
    ASSERT_NEAR(p.z(), expected_z(t), 1e-15) << "t = " << t;
    ASSERT_NEAR(p.x(), expected_x(t), 1e-15) << "t = " << t;
    ASSERT_EQ(p.y(), 0.0);
    const Vec3 v = sim.model().walls[0].velocity;
    const double vz = t <= 1e-3 ? t / 1e-3 : (t <= 2e-3 ? 1.0 - 2.0 * (t - 1e-3) / 1e-3 : -1.0);
    const double vx = t <= 1e-3 ? 0.0 : (t <= 2e-3 ? 2.0 * (t - 1e-3) / 1e-3 : 2.0);
    ASSERT_NEAR(v.z(), vz, 1e-12) << "t = " << t;
    ASSERT_NEAR(v.x(), vx, 1e-12) << "t = " << t;
    ++checked;
  }
  EXPECT_GT(checked, 10);
  EXPECT_EQ(sim.wall_force(0), Vec3::Zero());
}

// A wall that starts from rest and speeds up pushes the block; the work it does (trapezoidal in
// its force and velocity) balances the energies, and a wall starting from rest sends a far
// weaker stress wave than one starting at full speed.
TEST(Loading, WallWithVelocityHistoryDoesAccountedWork) {
  auto peak_force = [](bool smooth, double* balance) {
    ModelSpec s = block();
    WallSpec w;
    w.name = "pusher";
    w.point = Vec3(0, 0, 0);
    w.normal = Vec3(0, 0, 1);
    if (smooth)
      w.velocity_history = {{0.0, Vec3::Zero()}, {1e-3, Vec3(0, 0, 0.5)}};
    else
      w.velocity = Vec3(0, 0, 0.5);
    s.walls.push_back(w);
    Simulation sim(build_model(s));
    double peak = 0.0;
    while (sim.time() < 1e-3) {
      sim.step();
      peak = std::max(peak, -sim.wall_force(0).z());
    }
    *balance = sim.balance_error();
    EXPECT_GT(sim.energies().external_work, 0.0);
    return peak;
  };
  double balance_smooth = 0.0, balance_sudden = 0.0;
  const double smooth = peak_force(true, &balance_smooth);
  const double sudden = peak_force(false, &balance_sudden);
  std::printf("pushed block: peak wall force %.4g N from rest, %.4g N at once; balance %.2e\n",
              smooth, sudden, balance_smooth);
  EXPECT_LT(std::fabs(balance_smooth), 2e-3);
  EXPECT_LT(smooth, 0.5 * sudden);
}

// The largest principal stress the history and summary report: a block pulled slowly at its
// top face (base held) is in tension of about E times its strain, and the reported value is
// the largest eigenvalue over all Gauss points, computed here independently with Eigen.
TEST(Loading, LargestPrincipalStressOfAPulledBlock) {
  // quasi-static: rho c v is 5 % of the final stress
  Simulation sim(build_model(driven_block(0.01)));
  while (sim.time() < 2e-3) sim.step();
  const Model& m = sim.model();
  double expected = -HUGE_VAL;
  for (std::size_t g = 0; g < m.stress.size() / 6; ++g) {
    // Model::stress is [element][component][point]
    const double* first = m.stress.data() + 24 * (g / 4) + g % 4;
    const double t[6] = {first[0], first[4], first[8], first[12], first[16], first[20]};
    Eigen::Matrix3d S;
    S << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
    expected = std::max(expected,
                        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues().maxCoeff());
  }
  const double strain = 0.01 * sim.time() / 0.1;
  std::printf("pulled block: largest principal stress %.5g Pa, E strain %.5g Pa\n",
              sim.max_principal_stress(0), 1e9 * strain);
  EXPECT_NEAR(sim.max_principal_stress(0), expected, 1e-9 * std::fabs(expected));
  EXPECT_GT(expected, 0.9e9 * strain);
  EXPECT_LT(expected, 3.0e9 * strain);  // ends held sideways raise it near the corners only
}
