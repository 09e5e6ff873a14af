// SPDX-License-Identifier: GPL-3.0-or-later
// The dissipative options (wall contact damping, artificial bulk viscosity) take
// energy out of the system, and the energy they take is accounted for: the balance
// kinetic + internal + contact + dissipations - external work stays constant.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/simulation.hpp"
#include "io/mesh/mesh_generators.hpp"

using namespace femdem;

namespace {

struct Outcome {
  double restitution = 0.0;  // vertical speed after / before
  Energies energies;
  double balance_error = 0.0;
};

// An elastic steel ball (R 10 mm, h 3.4 mm) dropped at 1 m/s on a wall, run for 60 us.
Outcome drop(double damping, double q_linear, double q_quadratic) {
  ModelSpec s;
  MaterialParams steel;
  steel.name = "steel";
  steel.density = 7850.0;
  steel.youngs_modulus = 210e9;
  steel.poisson_ratio = 0.3;
  s.materials.push_back(steel);
  BodySpec b;
  b.name = "ball";
  b.material = 0;
  b.mesh = generate_sphere(0.01, 3.4e-3);
  for (auto& p : b.mesh.nodes) p.z() += 0.010001;
  b.velocity = Vec3(0, 0, -1.0);
  s.bodies.push_back(b);
  WallSpec w;
  w.name = "floor";
  w.damping = damping;
  s.walls.push_back(w);
  s.simulation.end_time = 60e-6;
  s.simulation.bulk_viscosity_linear = q_linear;
  s.simulation.bulk_viscosity_quadratic = q_quadratic;
  Simulation sim(build_model(s));
  while (sim.time() < 60e-6) sim.step();
  Outcome o;
  o.restitution = sim.body_motion(0).vcom.z() / 1.0;
  o.energies = sim.energies();
  o.balance_error = sim.balance_error();
  return o;
}

}  // namespace

TEST(Dissipation, WallDampingIsAccounted) {
  const Outcome o = drop(0.5, 0.0, 0.0);
  std::printf("damped penalty wall: restitution %.4f, contact dissipation %.3g J, balance %.2e\n",
              o.restitution, o.energies.contact_dissipation, o.balance_error);
  EXPECT_GT(o.energies.contact_dissipation, 0.0);
  EXPECT_LT(o.restitution, 1.0);
  EXPECT_GT(o.restitution, 0.5);
  EXPECT_LT(std::fabs(o.balance_error), 2e-3);
}

TEST(Dissipation, BulkViscosityIsAccounted) {
  const Outcome o = drop(0.0, 0.06, 1.5);
  std::printf("bulk viscosity: restitution %.4f, viscous dissipation %.3g J, balance %.2e\n",
              o.restitution, o.energies.viscous_dissipation, o.balance_error);
  EXPECT_GT(o.energies.viscous_dissipation, 0.0);
  EXPECT_LT(o.restitution, 1.0);
  EXPECT_LT(std::fabs(o.balance_error), 2e-3);
}
