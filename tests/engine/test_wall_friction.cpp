// SPDX-License-Identifier: GPL-3.0-or-later
// Coulomb friction against rigid walls, checked against rigid-body mechanics: a block sliding on
// a floor decelerates at mu g and stops after v0^2 / (2 mu g); on a slope steeper than atan(mu)
// it slides with a = g (sin t - mu cos t); on a gentler one it sticks. Friction work is
// dissipated and the energy balance closes.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

// A stiff 0.1 m cube resting on the floor z = 0 (gravity tilted to model a slope: the floor's
// frame is the slope's frame). The wall dashpot removes the bounce of the first contact.
ModelSpec block_on_floor(double mu, Vec3 gravity, Vec3 velocity) {
  ModelSpec s;
  MaterialParams mat;
  mat.name = "stiff";
  mat.density = 1000.0;
  mat.youngs_modulus = 1e8;
  mat.poisson_ratio = 0.25;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = test::kuhn_box(2, 2, 2, Vec3(0.1, 0.1, 0.1));
  b.velocity = velocity;
  s.bodies.push_back(b);
  WallSpec w;
  w.name = "floor";
  w.point = Vec3(0, 0, 0);
  w.normal = Vec3(0, 0, 1);
  w.friction = mu;
  w.damping = 0.5;
  s.walls.push_back(w);
  s.simulation.gravity = gravity;
  return s;
}

void run_until(Simulation& sim, double t) {
  while (sim.time() < t) sim.step(t - sim.time());
}

}  // namespace

TEST(WallFriction, SlidingBlockStopsAtTheRigidBodyDistance) {
  const double mu = 0.4, g = 100.0, v0 = 1.0;
  Simulation sim(build_model(block_on_floor(mu, Vec3(0, 0, -g), Vec3(v0, 0, 0))));
  const double x0 = sim.body_motion(0).com.x();
  const double t_stop = v0 / (mu * g);  // 0.025 s
  run_until(sim, 0.5 * t_stop);
  const double v_half = sim.body_motion(0).vcom.x();
  run_until(sim, 2.0 * t_stop);
  const BodyState b = sim.body_motion(0);
  const double distance = b.com.x() - x0, expected = v0 * v0 / (2.0 * mu * g);
  const Energies e = sim.energies();
  std::printf(
      "v at t_stop/2 %.4f (rigid %.4f); distance %.5f m (rigid %.5f); v end %.2e; "
      "friction+damping work %.4g J of %.4g J; balance %.2e\n",
      v_half, 0.5 * v0, distance, expected, b.vcom.x(), e.contact_dissipation,
      e.external_work + 0.5 * sim.body_motion(0).mass * v0 * v0, sim.balance_error());
  EXPECT_NEAR(v_half, 0.5 * v0, 0.03 * v0);
  EXPECT_NEAR(distance, expected, 0.03 * expected);
  EXPECT_LT(std::fabs(b.vcom.x()), 0.01 * v0);  // stopped, and stays stopped
  EXPECT_GT(e.contact_dissipation, 0.9 * 0.5 * b.mass * v0 * v0);
  EXPECT_LT(std::fabs(sim.balance_error()), 5e-3);
}

TEST(WallFriction, BlockOnASlopeSlidesOrSticksAsCoulombSays) {
  const double mu = 0.5, g = 100.0, T = 0.03;
  for (const double tan_theta : {0.7 * mu, 1.6 * mu}) {
    const double th = std::atan(tan_theta);
    const Vec3 gravity(g * std::sin(th), 0.0, -g * std::cos(th));
    Simulation sim(build_model(block_on_floor(mu, gravity, Vec3::Zero())));
    // the block settles onto the floor first (it slips until the normal force builds up)
    run_until(sim, T / 3);
    const BodyState b0 = sim.body_motion(0);
    run_until(sim, T);
    const BodyState b1 = sim.body_motion(0);
    const double dt = sim.time() - T / 3, slid = b1.com.x() - b0.com.x();
    const double a = g * (std::sin(th) - mu * std::cos(th));
    std::printf("tan(theta) = %.2f mu: acceleration %.4g m/s^2 (rigid %.4g), slid %.3e m\n",
                tan_theta / mu, (b1.vcom.x() - b0.vcom.x()) / dt, std::max(a, 0.0), slid);
    if (a < 0.0) {
      // Sticking. The block still shears elastically under the slope load and, undamped,
      // oscillates about that state: its centre moves by up to the static shear
      // gamma H / 2 = (m g sin t / A) / G * H / 2 either way, but does not creep (a creep at
      // 0.1 % of the frictionless acceleration would exceed the bound below).
      const double G = 1e8 / (2 * 1.25), shear = 1.0 * g * std::sin(th) / (0.1 * 0.1) / G * 0.1;
      EXPECT_LT(std::fabs(slid), shear);
      // the energies here are only those of the settling (1e-4 J): a looser relative bound
      EXPECT_LT(std::fabs(sim.balance_error()), 0.05);
    } else {
      EXPECT_NEAR((b1.vcom.x() - b0.vcom.x()) / dt, a, 0.02 * a);
      EXPECT_LT(std::fabs(sim.balance_error()), 5e-3);
    }
  }
}
