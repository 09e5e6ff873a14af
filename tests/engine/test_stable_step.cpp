// SPDX-License-Identifier: GPL-3.0-or-later
// The stable step the engine chooses by itself with simulation.stable_step = "assembled":
// safe and sharp. For each model the run is stable at the default step, and a run
// with a fixed step 1.25 times the estimated limit (its smallest over the run) diverges and is
// caught: the estimate is within 25 % of the true limit, on the safe side. Central differences
// are stable for omega dt <= 2 exactly, so a mode above the limit grows by a factor of about 4
// per step at 1.25 times it: the runs below start with every mode excited (random velocities)
// and the growth shows within a few dozen steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

MaterialParams steel() {
  MaterialParams mat;
  mat.name = "steel";
  mat.density = 7800.0;
  mat.youngs_modulus = 200e9;
  mat.poisson_ratio = 0.3;
  return mat;
}

[[maybe_unused]] MaterialParams copper() {
  MaterialParams mat;
  mat.name = "copper";
  mat.density = 8930.0;
  mat.youngs_modulus = 117e9;
  mat.poisson_ratio = 0.35;
  auto& vm = mat.model.emplace<VonMisesParams>();
  vm.yield_stress = 400e6;
  return mat;
}

ModelSpec one_body(Tet10Mesh mesh, MaterialParams mat, double end_time) {
  ModelSpec spec;
  spec.materials.push_back(std::move(mat));
  BodySpec b;
  b.name = std::string("body");
  b.material = 0;
  b.mesh = std::move(mesh);
  spec.bodies.push_back(b);
  spec.simulation.end_time = end_time;
  spec.simulation.stable_step = SimulationSettings::StableStep::assembled;
  return spec;
}

// Small random velocities on every node (amplitude v): every mode is in the initial state.
void excite(Model& m, double v, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-v, v);
  for (double& a : m.v) a += u(rng);
}

struct Outcome {
  bool diverged = false;
  std::int64_t steps = 0;
  double smallest_limit = HUGE_VAL;  // the estimated stable step, smallest over the run
  double max_balance = 0.0;
};

Outcome run(const ModelSpec& spec, double v_noise, std::int64_t max_steps) {
  Model m = build_model(spec);
  excite(m, v_noise, 5);
  Outcome o;
  try {
    Simulation sim(std::move(m));
    o.smallest_limit = sim.stable_dt();
    while (sim.time() < spec.simulation.end_time && o.steps < max_steps) {
      sim.step(spec.simulation.end_time - sim.time());
      ++o.steps;
      o.smallest_limit = std::min(o.smallest_limit, sim.stable_dt());
      o.max_balance = std::max(o.max_balance, std::fabs(sim.balance_error()));
    }
  } catch (const InstabilityError&) {
    o.diverged = true;
  }
  return o;
}

// Stable at the default step; diverges (caught) at 1.25 times the smallest estimated limit.
// Stable means bounded: with every mode excited the energy measured at whole steps swings by
// about (omega dt)^2 / 4 of the highest mode's share (omega dt = 1 at the default safety 0.5),
// while a diverging run grows without bound and stops.
void expect_sharp(const ModelSpec& spec, double v_noise, std::int64_t steps,
                  double balance_tolerance) {
  const Outcome stable = run(spec, v_noise, steps);
  ASSERT_FALSE(stable.diverged);
  EXPECT_EQ(stable.steps, steps);
  EXPECT_LT(stable.max_balance, balance_tolerance);
  ModelSpec over = spec;
  over.simulation.time_step = 1.25 * stable.smallest_limit;
  const Outcome unstable = run(over, v_noise, steps);
  EXPECT_TRUE(unstable.diverged) << "a fixed step of 1.25 x " << stable.smallest_limit << " s ran "
                                 << unstable.steps << " steps";
}

}  // namespace

TEST(StableStep, SingleElementIsSharp) {
  Tet10Mesh mesh = test::kuhn_box(1, 1, 1, Vec3(1e-2, 1e-2, 1e-2));
  mesh.elements.resize(1);
  ModelSpec spec = one_body(std::move(mesh), steel(), 1.0);
  expect_sharp(spec, 1e-3, 400, 0.3);
}

TEST(StableStep, BarIsSharp) {
  ModelSpec spec = one_body(test::kuhn_box(8, 2, 2, Vec3(8e-2, 2e-2, 2e-2)), steel(), 1.0);
  expect_sharp(spec, 1e-3, 400, 0.3);
}

TEST(StableStep, DistortedMeshIsSharp) {
  ModelSpec spec = one_body(test::kuhn_box(4, 4, 4, Vec3(1e-2, 1e-2, 1e-2), 0.35, 9), steel(), 1.0);
  expect_sharp(spec, 1e-3, 400, 0.3);
}
