// SPDX-License-Identifier: GPL-3.0-or-later
// The body-contact bound of the stable step. Two bodies with the same (aligned) mesh touching
// exactly: coincident corners, edges and faces make overlaps at round-off level, where the
// secant stiffness N^2 / 2E of a pair is not a measure of anything (E cancels to nothing) and
// used to collapse the step. The bound must not collapse there, and must still guard stability
// where a contact is the stiffest thing in the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/simulation.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

MaterialParams steel() {
  MaterialParams mat;
  mat.name = "steel";
  mat.density = 7800.0;
  mat.youngs_modulus = 110e9;
  mat.poisson_ratio = 0.3;
  return mat;
}

// Two 1 mm cubes of the same Kuhn mesh, b stacked exactly on a (its bottom face triangles
// coincide with a's top face triangles), closing at 2 v; the pair sits 1 m from the origin so
// that its coordinates carry round-off like a scene's.
ModelSpec aligned_cubes(double v, double penalty_factor) {
  const double s = 1e-3;
  const Vec3 at(1.0, 0.5, 0.25);
  ModelSpec spec;
  spec.materials.push_back(steel());
  BodySpec a, b;
  a.name = std::string(1, 'a');  // not from a literal: GCC 12's false -Wrestrict (bug 105329)
  a.material = 0;
  a.mesh = test::kuhn_box(2, 2, 2, Vec3(s, s, s));
  for (Vec3& p : a.mesh.nodes) p += at;
  a.velocity = Vec3(0, 0, v);
  b = a;
  b.name = std::string(1, 'b');
  for (Vec3& p : b.mesh.nodes) p.z() += s;
  b.velocity = Vec3(0, 0, -v);
  spec.bodies = {a, b};
  spec.contact.penalty_factor = penalty_factor;
  return spec;
}

struct RunResult {
  double dt0 = 0.0, min_dt = HUGE_VAL, max_balance = 0.0, max_contact_energy = 0.0;
  double max_speed = 0.0;
  std::int64_t steps = 0;
};

RunResult run(ModelSpec spec, double end_time, std::int64_t max_steps) {
  Simulation sim(build_model(spec));
  EXPECT_TRUE(sim.body_contact().active());
  RunResult r;
  r.dt0 = sim.dt();
  while (sim.time() < end_time && r.steps < max_steps) {
    sim.step(end_time - sim.time());
    ++r.steps;
    r.min_dt = std::min(r.min_dt, sim.dt());
    r.max_balance = std::max(r.max_balance, std::fabs(sim.balance_error()));
    r.max_contact_energy = std::max(r.max_contact_energy, sim.energies().contact);
    const auto& vel = sim.model().v;
    for (std::size_t i = 0; i < vel.size(); ++i)
      r.max_speed = std::max(r.max_speed, std::fabs(vel[i]));
  }
  EXPECT_GE(sim.time(), end_time) << "stuck after " << r.steps << " steps";
  return r;
}

}  // namespace

// Aligned cubes closing from exact touching so slowly (1e-9 m/s: 1e-17 m per step, a tenth
// of the round-off of their coordinates) that for many steps their overlaps are slivers at
// round-off level. Before the stiffness bound one such pair took N^2 / 2E to ~1e21 N/m and the
// step to 4e-15 s within 150 steps (3000 steps did not reach 1e-6 s). Now the step stays
// within a factor 3 of the step at t = 0 (which already counts a flat contact on the pairs whose
// faces lie flush within reach, BodyContact::omega_squared_bound; nothing touching may be stiffer
// than 4 times that: a factor 2 in dt, and the elements' frequency adds to it), and the motion
// stays that of the slow approach.
TEST(ContactTimeStep, AlignedTouchingCubesDoNotCollapseTheStep) {
  ModelSpec lone = aligned_cubes(0.0, 1.0);
  lone.bodies.pop_back();
  const double dt_elements = Simulation(build_model(lone)).dt();
  const double v = 1e-9;
  const RunResult r = run(aligned_cubes(v, 1.0), 1e-6, 3000);
  std::printf(
      "element step %.4g s, with contact %.4g s at t = 0, smallest %.4g s, %lld steps, "
      "largest node speed %.3g m/s\n",
      dt_elements, r.dt0, r.min_dt, static_cast<long long>(r.steps), r.max_speed);
  EXPECT_GT(r.min_dt, r.dt0 / 3.0);
  EXPECT_GT(r.min_dt, dt_elements / 5.0);
  // No blow-up: the elastic response to the contact stress sigma ~ k d / A (d = 2 v t) is
  // v_p = sigma / (rho c) ~ 1e-8 m/s here (6e-8 m/s measured at 1e-6 s, 2.4e-7 m/s at 1e-5 s:
  // growing with d, not exponentially); an unstable step grows by orders of magnitude.
  EXPECT_LT(r.max_speed, 1e-6);
}

// Aligned cubes pressed together at 0.5 m/s: a real contact, flush faces, exact touching at
// t = 0, two elements thick, so the contact's own mode is the highest one: the worst case for
// the energy balance. Contact springs are resolved at 0.5 of their own limit whatever the safety
// factor (SimulationSettings::contact_stiffness_margin); without that the balance at the default
// safety 0.8 was 2.4 % (automatic stiffness) and 17.6 % (p = 1 E). Measured with it: 1.33 % and
// 2.80 % (at safety 0.5: 0.72 % and 2.68 %) while the step counted a flat contact on every node
// of a candidate pair; since the bodies' springs are bounded every step and only pairs with
// faces flush within reach are counted before they touch (2026-12-07): 1.71 % and 2.55 %.
TEST(ContactTimeStep, AlignedCubesPressedTogetherKeepTheEnergyBalance) {
  for (const double penalty_factor : {0.0, 1.0}) {
    const RunResult r = run(aligned_cubes(0.5, penalty_factor), 2e-6, 3000);
    std::printf(
        "penalty factor %g: step %.4g s at t = 0, smallest %.4g s, %lld steps, energy balance "
        "%.2e, peak contact energy %.3g J\n",
        penalty_factor, r.dt0, r.min_dt, static_cast<long long>(r.steps), r.max_balance,
        r.max_contact_energy);
    EXPECT_GT(r.max_contact_energy, 1e-7);
    EXPECT_GT(r.min_dt, r.dt0 / 3.0);
    EXPECT_LT(r.max_balance, penalty_factor > 0.0 ? 3e-2 : 2e-2);
  }
}

// The same with a penalty 100 times stiffer: the contact, not the elements, sets the step, and
// the run still conserves energy (the bound is active and sound). Balance measured 1.2 % with
// the flat contact counted on every candidate node, 2.40 % since only pairs with faces flush
// within reach are (2026-12-07): edges and corners meet first here, and each contact is counted
// from the step after it starts, its stiffness growing from zero with its overlap.
TEST(ContactTimeStep, StiffContactBoundKeepsTheRunStable) {
  ModelSpec lone = aligned_cubes(0.0, 100.0);
  lone.bodies.pop_back();
  const double dt_elements = Simulation(build_model(lone)).dt();
  ModelSpec spec = aligned_cubes(2.0, 100.0);
  // lateral offset: edges and corners meet too, not only flush faces
  for (Vec3& p : spec.bodies[1].mesh.nodes) p += Vec3(0.3e-3, 0.2e-3, 0.0);
  const RunResult r = run(spec, 1.5e-6, 40000);
  std::printf(
      "element step %.4g s, contact-limited %.4g s at t = 0, smallest %.4g s, %lld steps, "
      "energy balance %.2e, peak contact energy %.3g J\n",
      dt_elements, r.dt0, r.min_dt, static_cast<long long>(r.steps), r.max_balance,
      r.max_contact_energy);
  EXPECT_LT(r.dt0, 0.5 * dt_elements);  // the contact bound is the one acting
  EXPECT_GT(r.min_dt, 0.1 * r.dt0);
  EXPECT_GT(r.max_contact_energy, 0.0);
  EXPECT_LT(r.max_balance, 3e-2);
}

// Flush faces closing at speed from a gap: the stiff springs (penalty 100 E) of a flat overlap
// act from its first instant, so the step must be the contact's before the faces touch, not the
// step after (one step of the elements' length on them would kick the nodes by (omega dt)^2 / 2,
// about 1e3, times the closing speed here). The pair is counted once its faces may close within
// the step (BodyContact::omega_squared_bound): the step falls from the elements' before the
// first touch, the energy balance stays that of the cubes pressed from touching (1.82 %
// measured), and no node moves much faster than the bodies met.
TEST(ContactTimeStep, FlatFacesClosingAtSpeedAreCountedBeforeTheyTouch) {
  const double v = 2.0, gap = 1e-6;  // 0.25 us to close at 4 m/s
  ModelSpec lone = aligned_cubes(0.0, 100.0);
  lone.bodies.pop_back();
  const double dt_elements = Simulation(build_model(lone)).dt();
  ModelSpec spec = aligned_cubes(v, 100.0);
  for (Vec3& p : spec.bodies[1].mesh.nodes) p.z() += gap;
  Simulation sim(build_model(spec));
  const double dt0 = sim.dt();
  double dt_at_first_touch = 0.0, max_speed = 0.0, max_balance = 0.0;
  while (sim.time() < 0.5e-6) {
    const double dt_before = sim.dt();
    sim.step(0.5e-6 - sim.time());
    if (dt_at_first_touch == 0.0 && sim.body_contact().touching_pairs() > 0)
      dt_at_first_touch = dt_before;
    max_balance = std::max(max_balance, std::fabs(sim.balance_error()));
    for (const double u : sim.model().v) max_speed = std::max(max_speed, std::fabs(u));
  }
  std::printf(
      "element step %.4g s, at t = 0 %.4g s, the step that first touched %.4g s, energy balance "
      "%.2e, largest node speed %.3g m/s\n",
      dt_elements, dt0, dt_at_first_touch, max_balance, max_speed);
  EXPECT_NEAR(dt0, dt_elements, 1e-2 * dt_elements);  // apart: the elements' (estimates to 1 %)
  ASSERT_GT(dt_at_first_touch, 0.0);
  EXPECT_LT(dt_at_first_touch, 0.1 * dt_elements);  // already the contact's
  EXPECT_LT(max_balance, 3e-2);
  // (the impact's elastic waves: 2.27 v measured, 2026-12-07; a first step of the elements'
  // length on these springs would give about 1e3 v)
  EXPECT_LT(max_speed, 4.0 * v);
}

// simulation.contact_time_step_safety: the cubes of the test above, whose highest mode is the
// contact's, take a step in proportion to it (the contact springs are resolved at that fraction
// of their own limit: 0.8 / 0.5 = 1.6 times the default's step, less the elements' share of the
// mode), never above the safety's own (1.0 resolves them at the safety 0.8, as 0.8 does). The
// price is the reason for the default: this impact of edges and corners on stiff springs keeps
// its balance within 2.4 % at 0.5 (above) and 5.8 % at 0.8 (measured 2026-12-07; 1.2 % and 4.3 %
// while every candidate node counted a flat contact), bounded but not what a default may cost.
TEST(ContactTimeStep, ContactSafetySetsTheStepOfAContactLedMode) {
  ModelSpec spec = aligned_cubes(2.0, 100.0);
  for (Vec3& p : spec.bodies[1].mesh.nodes) p += Vec3(0.3e-3, 0.2e-3, 0.0);
  const auto step_at = [&](double contact_safety) {
    ModelSpec s = spec;
    s.simulation.contact_time_step_safety = contact_safety;
    return Simulation(build_model(s)).dt();
  };
  const double dt_default = step_at(SimulationSettings::kContactSafety);
  const double dt_08 = step_at(0.8);
  std::printf("step at t = 0: contact springs at 0.5 %.4g s, at 0.8 %.4g s (%.3f times)\n",
              dt_default, dt_08, dt_08 / dt_default);
  EXPECT_GT(dt_08 / dt_default, 1.45);
  EXPECT_LE(dt_08 / dt_default, 1.6 * (1.0 + 1e-9));
  EXPECT_EQ(step_at(1.0), dt_08);
  ModelSpec fast = spec;
  fast.simulation.contact_time_step_safety = 0.8;
  const RunResult r = run(fast, 1.5e-6, 40000);
  std::printf("at 0.8: smallest step %.4g s, %lld steps, energy balance %.2e\n", r.min_dt,
              static_cast<long long>(r.steps), r.max_balance);
  EXPECT_GT(r.max_contact_energy, 0.0);
  EXPECT_GT(r.min_dt, 0.5 * dt_08);
  EXPECT_LT(r.max_balance, 6e-2);
}

// The automatic contact stiffness (engine/contact_stiffness.hpp, penalty_factor 0): steel cubes
// pressed together, and a soft cube (E 1 GPa, rho 1000) pressed onto a steel one. The step in
// contact stays at least half the step the bodies alone take at the contact's safety 0.5 (issue
// 17; measured 0.54 on steel, 0.94 soft on steel; against the bodies alone at the default 0.8:
// 0.43 and 0.94); on the soft-on-stiff pair it is the softer side's modulus that sets the
// penalty, so the soft body's light nodes do not get a spring scaled to steel, and the step is
// nearly the steel elements' own.
TEST(ContactTimeStep, AutomaticStiffnessKeepsAtLeastHalfTheStepOfTheBodiesAlone) {
  for (const bool soft_on_stiff : {false, true}) {
    ModelSpec spec = aligned_cubes(0.5, 0.0);
    if (soft_on_stiff) {
      MaterialParams soft = steel();
      soft.name = "soft";
      soft.youngs_modulus = 1e9;
      soft.density = 1000.0;
      spec.materials.push_back(soft);
      spec.bodies[1].material = 1;
    }
    double dt_alone = HUGE_VAL;  // at the contact's safety 0.5 (above)
    for (int keep = 0; keep < 2; ++keep) {
      ModelSpec lone = spec;
      lone.bodies.erase(lone.bodies.begin() + (1 - keep));
      lone.simulation.time_step_safety = 0.5;
      dt_alone = std::min(dt_alone, Simulation(build_model(lone)).dt());
    }
    const RunResult r = run(spec, 2e-6, 3000);
    std::printf(
        "%s: step of the bodies alone %.4g s, smallest in contact %.4g s (%.2f of it), %lld "
        "steps, energy balance %.2e, peak contact energy %.3g J\n",
        soft_on_stiff ? "soft on steel" : "steel on steel", dt_alone, r.min_dt, r.min_dt / dt_alone,
        static_cast<long long>(r.steps), r.max_balance, r.max_contact_energy);
    EXPECT_GT(r.max_contact_energy, 1e-8);
    EXPECT_GE(r.min_dt, 0.5 * dt_alone);
    if (soft_on_stiff) {
      // against the bodies alone at the default safety: an element-led mode keeps it, but for
      // what the step follows between estimates, the bound with its contact springs counted
      // contact_stiffness_margin() stiffer, which may move 10 % (kRecheck), and for up to 5
      // steps more, before it is re-measured (measured 0.87)
      EXPECT_GE(r.min_dt, 0.85 * dt_alone * SimulationSettings::kAssembledSafety / 0.5);
    }
    EXPECT_LT(r.max_balance, 2e-2);
  }
}
