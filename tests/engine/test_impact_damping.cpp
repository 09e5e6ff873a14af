// SPDX-License-Identifier: GPL-3.0-or-later
// Impact damping (contact.impact_damping, engine/impact_damping.hpp): a dashpot on the rigid
// motions of two bodies in contact, c = 2 xi sqrt(k m_eff).
// Reference: a mass on a linear spring and dashpot, released at contact with speed v, leaves
// with e v; e = exp(-pi xi / sqrt(1 - xi^2)) if the dashpot may pull, higher when it is released
// as soon as it would (as here): that reference is integrated numerically below.
// The contacts are soft against the blocks (penalty factor 0.05 on the wall, 0.002 between the
// blocks) so that the blocks move nearly as rigid bodies on the contact spring.
//  - a block landing flat on a wall: e for xi 0, 0.1, 0.3;
//  - two blocks head-on: the same e for their relative speed, momentum kept to round-off, the
//    energy balance closed with the damping's work counted as contact dissipation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/simulation.hpp"
#include "support/rubbery_blocks.hpp"

using namespace femdem;
using femdem::test::box_at;
using femdem::test::momentum;
using femdem::test::rubbery;

namespace {

double linear_restitution(double xi) {
  return std::exp(-M_PI * xi / std::sqrt(1.0 - xi * xi));
}

// The same contact as a unit mass on a unit spring and a dashpot 2 xi that never pulls (the
// total force is kept >= 0: once it would pull, the mass leaves with its speed then), by RK4
// in fine steps from first touch at unit speed. Its restitution is above the linear one.
double no_pull_restitution(double xi) {
  double x = 0.0, v = 1.0;  // penetration and its rate
  const double h = 1e-4;
  auto a = [xi](double x, double v) { return -std::max(x + 2.0 * xi * v, 0.0); };
  for (int i = 0; i < 1000000; ++i) {
    if (v < 0.0 && x + 2.0 * xi * v <= 0.0) break;
    const double k1x = v, k1v = a(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = a(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = a(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = a(x + h * k3x, v + h * k3v);
    x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
  return -v;
}

struct Impact {
  double restitution = 0.0, momentum_drift = 0.0, balance = 0.0, dissipated = 0.0, kinetic0 = 0.0;
};

// A 0.1 m block at 1 m/s onto a floor (z = 0), 1 mm above it, no gravity.
Impact block_on_wall(double xi) {
  ModelSpec s;
  s.materials.push_back(rubbery());
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = box_at(Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 1e-3));
  b.velocity = Vec3(0, 0, -1.0);
  s.bodies = {b};
  WallSpec w;
  w.name = "floor";
  w.penalty_factor = 0.05;
  s.walls = {w};
  s.contact.impact_damping = xi;
  Simulation sim(build_model(s));
  Impact r;
  r.kinetic0 = sim.energies().kinetic;
  const double balance0 = sim.energies().balance();
  while (sim.time() < 0.01) sim.step(0.01 - sim.time());
  r.restitution = sim.body_state(0).vcom.z() / 1.0;
  r.balance = (sim.energies().balance() - balance0) / r.kinetic0;
  r.dissipated = sim.energies().contact_dissipation / r.kinetic0;
  std::printf(
      "block on wall, xi %.2f: e %.4f (spring-dashpot %.4f), dissipated %.4f of the kinetic "
      "energy, balance %.1e\n",
      xi, r.restitution, no_pull_restitution(xi), r.dissipated, r.balance);
  return r;
}

// Two 0.1 m blocks head-on at 1 m/s each, 1 mm apart, no gravity, to 30 ms.
Impact two_blocks(double xi) {
  ModelSpec s = femdem::test::two_blocks_closing(Vec3(0, 0, 0.101), 2.0);
  // A contact between bodies is stiffer than a wall's at the same factor: 0.002 keeps it soft
  // against the blocks (at 0.05 the blocks ring, e 0.95 undamped and 0.65 at xi 0.1).
  s.contact.penalty_factor = 0.002;
  s.contact.impact_damping = xi;
  Simulation sim(build_model(s));
  const Model& m = sim.model();
  Impact r;
  r.kinetic0 = sim.energies().kinetic;
  const double balance0 = sim.energies().balance();
  const double p0 = sim.body_state(0).mass * 1.0;
  while (sim.time() < 0.03) sim.step(0.03 - sim.time());
  r.restitution = (sim.body_state(1).vcom.z() - sim.body_state(0).vcom.z()) / 2.0;
  r.momentum_drift = momentum(m).norm() / p0;  // against one body's momentum, 1 m/s x mass
  r.balance = (sim.energies().balance() - balance0) / r.kinetic0;
  r.dissipated = sim.energies().contact_dissipation / r.kinetic0;
  std::printf(
      "two blocks, xi %.2f: e %.4f (spring-dashpot %.4f), dissipated %.4f, momentum %.1e, "
      "balance %.1e\n",
      xi, r.restitution, no_pull_restitution(xi), r.dissipated, r.momentum_drift, r.balance);
  return r;
}

}  // namespace

TEST(ImpactDamping, BlockOnAWallReboundsWithTheRestitutionOfItsDampingRatio) {
  const Impact elastic = block_on_wall(0.0);
  EXPECT_GT(elastic.restitution, 0.95);
  EXPECT_EQ(elastic.dissipated, 0.0);
  for (const double xi : {0.1, 0.3}) {
    const Impact r = block_on_wall(xi);
    EXPECT_NEAR(r.restitution, no_pull_restitution(xi), 0.03) << xi;
    EXPECT_LT(r.restitution, linear_restitution(0.5 * xi)) << xi;
    // what the rebound lost is what the dashpot dissipated (what is left vibrates)
    EXPECT_NEAR(r.dissipated, 1.0 - r.restitution * r.restitution, 0.05) << xi;
    EXPECT_LT(std::fabs(r.balance), 1e-3) << xi;
  }
}

TEST(ImpactDamping, TwoBlocksHeadOnKeepMomentumAndLoseTheirRelativeSpeed) {
  const Impact elastic = two_blocks(0.0);
  EXPECT_GT(elastic.restitution, 0.95);
  for (const double xi : {0.1, 0.3}) {
    const Impact r = two_blocks(xi);
    EXPECT_NEAR(r.restitution, no_pull_restitution(xi), 0.03) << xi;
    EXPECT_LT(r.restitution, linear_restitution(0.5 * xi)) << xi;
    EXPECT_LT(r.momentum_drift, 1e-12) << xi;
    EXPECT_GT(r.dissipated, 0.5 * (1.0 - r.restitution * r.restitution)) << xi;
    EXPECT_LT(std::fabs(r.balance), 1e-3) << xi;
  }
}
