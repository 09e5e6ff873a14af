// SPDX-License-Identifier: GPL-3.0-or-later
// Contact between bodies in the time loop: two blocks colliding conserve momentum to round-off
// and energy to the integrator's accuracy, push each other with equal and opposite forces, and
// separate; 1 and 2 threads give the same bits; a block sliding on a fixed meshed plate stops
// where rigid-body Coulomb friction says.
#include <gtest/gtest.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <cmath>

#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"
#include "support/rubbery_blocks.hpp"

using namespace femdem;
using femdem::test::box_at;
using femdem::test::momentum;
using femdem::test::rubbery;

namespace {

// Two 0.1 m blocks 1 mm apart, closing at 2 m/s, offset sideways so that the impact is not
// symmetric (edges and faces meet).
ModelSpec two_blocks() {
  ModelSpec s = femdem::test::two_blocks_closing(Vec3(0.03, 0.02, 0.101), 2.0);
  s.bodies[1].angular_velocity = Vec3(0, 0, 5.0);
  // a softer penalty than the default 100 E keeps the step (and the test) 3x longer
  s.contact.penalty_factor = 10.0;
  return s;
}

}  // namespace

// The energy error is that of the integrator across contact onset and release: about 1 % at the
// default step (0.5 of the stable estimate), and it shrinks with the step.
TEST(BodyContact, CollidingBlocksConserveMomentumAndEnergy) {
  for (const double safety : {0.5, 0.25}) {
    ModelSpec spec = two_blocks();
    spec.simulation.time_step_safety = safety;
    Simulation sim(build_model(spec));
    ASSERT_TRUE(sim.body_contact().active());
    const Vec3 p0 = momentum(sim.model());
    const double speed = 1.0;
    double peak_force = 0.0, worst_imbalance = 0.0;
    bool touched = false;
    while (sim.time() < 2.5e-3) {
      sim.step();
      const BodyState a = sim.body_motion(0), b = sim.body_motion(1);
      peak_force = std::max(peak_force, a.contact_force.norm());
      worst_imbalance = std::max(worst_imbalance, (a.contact_force + b.contact_force).norm());
      touched = touched || sim.body_contact().touching_pairs() > 0;
    }
    const BodyState a = sim.body_motion(0), b = sim.body_motion(1);
    const Vec3 p = momentum(sim.model());
    std::printf(
        "safety %.2f: peak contact force %.4g N, imbalance %.2e N, vz after %.4f / %.4f "
        "m/s, energy balance %.2e, broadphase runs %lld\n",
        safety, peak_force, worst_imbalance, a.vcom.z(), b.vcom.z(), sim.balance_error(),
        static_cast<long long>(sim.body_contact().broadphase_runs()));
    EXPECT_TRUE(touched);
    EXPECT_GT(peak_force, 1e3);
    EXPECT_LT(worst_imbalance, 1e-9 * peak_force);  // equal and opposite
    EXPECT_LT((p - p0).norm(), 1e-12 * a.mass * speed);
    // they bounced apart (an elastic flat impact keeps some energy in vibration, so e < 1)
    EXPECT_LT(a.vcom.z(), -0.3 * speed);
    EXPECT_GT(b.vcom.z(), 0.3 * speed);
    EXPECT_EQ(sim.body_contact().touching_pairs(), 0u);
    EXPECT_LT(std::fabs(sim.balance_error()), safety > 0.3 ? 2e-2 : 2e-3);
  }
}

TEST(BodyContact, OneAndTwoThreadsGiveTheSameBits) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  std::vector<double> x[2], v[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    ModelSpec s = two_blocks();
    s.contact.friction = 0.3;  // exercise the friction springs too
    Simulation sim(build_model(s));
    while (sim.time() < 1.2e-3) sim.step();
    x[threads - 1] = sim.model().x;
    v[threads - 1] = sim.model().v;
  }
  omp_set_num_threads(1);
  EXPECT_EQ(x[0], x[1]);
  EXPECT_EQ(v[0], v[1]);
#endif
}

// A block sliding at v0 on a fixed meshed plate under gravity g stops after v0^2 / (2 mu g),
// as on a wall; the pair friction overrides the common one.
TEST(BodyContact, BlockSlidingOnAFixedPlateStopsAtTheRigidBodyDistance) {
  const double mu = 0.4, g = 400.0, v0 = 1.0;
  ModelSpec s;
  s.contact.penalty_factor = 10.0;
  s.materials.push_back(rubbery());
  BodySpec plate, block;
  plate.name = "plate";
  plate.material = 0;
  plate.fixed = true;
  plate.mesh = test::kuhn_box(6, 3, 1, Vec3(0.3, 0.15, 0.05));
  for (Vec3& p : plate.mesh.nodes) p += Vec3(-0.05, -0.025, -0.05);
  block.name = "block";
  block.material = 0;
  block.mesh = box_at(Vec3(0.05, 0.05, 0.05), Vec3(0, 0.025, 0), 2);
  block.velocity = Vec3(v0, 0, 0);
  s.bodies = {plate, block};
  s.contact.friction = 0.0;
  s.contact.pairs.push_back({0, 1, mu});
  s.simulation.gravity = Vec3(0, 0, -g);
  Simulation sim(build_model(s));
  const double x0 = sim.body_motion(1).com.x();
  const double t_stop = v0 / (mu * g);
  while (sim.time() < 0.5 * t_stop) sim.step();
  const double v_half = sim.body_motion(1).vcom.x();
  while (sim.time() < 1.6 * t_stop) sim.step();
  const BodyState b = sim.body_motion(1);
  const double distance = b.com.x() - x0, expected = v0 * v0 / (2 * mu * g);
  std::printf(
      "v at t_stop/2 %.4f (rigid 0.5); distance %.5f m (rigid %.5f); v end %.2e; "
      "balance %.2e\n",
      v_half, distance, expected, b.vcom.x(), sim.balance_error());
  EXPECT_NEAR(v_half, 0.5 * v0, 0.05 * v0);
  EXPECT_NEAR(distance, expected, 0.05 * expected);
  EXPECT_LT(std::fabs(b.vcom.x()), 0.02 * v0);
  EXPECT_GT(sim.energies().contact_dissipation, 0.8 * 0.5 * b.mass * v0 * v0);
  EXPECT_LT(std::fabs(sim.balance_error()), 1e-2);
}
