// SPDX-License-Identifier: GPL-3.0-or-later
// The thesis' plastic oscillating cube (thesis 3.3, L4957-5221; VALIDATION.md section 1):
// 1 m cube, base fixed, 1 m/s horizontal initial velocity, rho 1000, E 30 GPa, nu 0.3, von Mises
// sigma_y = 0.4 MPa, perfectly plastic, 3 ms. Kinetic + elastic + dissipated energy stays
// constant (thesis: "total energy stays constant"; we require 1 %), most of the energy is
// dissipated in the first swing, and the dissipation converges as the mesh is refined.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

struct CubeResult {
  double initial_kinetic = 0.0;
  double dissipated = 0.0;
  double max_balance_error = 0.0;
  double final_kinetic_plus_elastic = 0.0;
};

CubeResult plastic_cube(int cells, FbarMode fbar) {
  ModelSpec s;
  MaterialParams mat;
  mat.name = "soft";
  mat.density = 1000.0;
  mat.youngs_modulus = 30e9;
  mat.poisson_ratio = 0.3;
  mat.model.emplace<VonMisesParams>().yield_stress = 0.4e6;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "cube";
  b.material = 0;
  b.mesh = test::kuhn_box(cells, cells, cells, Vec3(1, 1, 1));
  b.velocity = Vec3(1.0, 0.0, 0.0);
  b.fbar = fbar;
  s.bodies.push_back(b);
  ConstraintSpec base;
  base.body = 0;
  base.region.kind = RegionSpec::Kind::Plane;
  base.fix = {true, true, true};
  s.constraints.push_back(base);
  s.simulation.end_time = 3e-3;
  Simulation sim(build_model(s));
  CubeResult r;
  r.initial_kinetic = sim.energies().kinetic;
  while (sim.time() < 3e-3) {
    sim.step();
    const Energies e = sim.energies();
    const double total = e.kinetic + e.internal + e.plastic_dissipation;
    r.max_balance_error =
        std::max(r.max_balance_error, std::fabs(total - r.initial_kinetic) / r.initial_kinetic);
  }
  const Energies e = sim.energies();
  r.dissipated = e.plastic_dissipation;
  r.final_kinetic_plus_elastic = e.kinetic + e.internal;
  return r;
}

}  // namespace

TEST(PlasticDynamics, OscillatingCubeBalanceAndConvergence) {
  double previous = 0.0, previous_change = HUGE_VAL;
  for (int cells : {4, 6, 8}) {
    const CubeResult r = plastic_cube(cells, FbarMode::Off);
    const double fraction = r.dissipated / r.initial_kinetic;
    std::printf(
        "plastic cube h = 1/%d: dissipated %.4f of the initial kinetic energy, balance error %.4f "
        "%%\n",
        cells, fraction, 100 * r.max_balance_error);
    EXPECT_LT(r.max_balance_error, 0.01);
    EXPECT_GT(fraction, 0.5);  // most of the energy goes in plastic work
    EXPECT_LT(fraction, 1.0);
    if (previous > 0.0) {
      const double change = std::fabs(fraction - previous);
      EXPECT_LT(change, previous_change) << "dissipation must converge with refinement";
      previous_change = change;
    }
    previous = fraction;
  }
}

TEST(PlasticDynamics, OscillatingCubeBalanceWithFbar) {
  for (FbarMode mode : {FbarMode::VolumeAverage, FbarMode::Centroid, FbarMode::Nodal}) {
    const CubeResult r = plastic_cube(4, mode);
    std::printf("plastic cube F-bar %s: dissipated %.4f, balance error %.4f %%\n", to_string(mode),
                r.dissipated / r.initial_kinetic, 100 * r.max_balance_error);
    EXPECT_LT(r.max_balance_error, 0.01);
  }
}
