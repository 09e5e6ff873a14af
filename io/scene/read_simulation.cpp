// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>
#include <tuple>

#include "io/scene/toml_reader.hpp"

namespace femdem::scene {
namespace {

// The bounds of a run's schedule (docs/SCENES.md): a frame of even a small model is a
// megabyte, a history row a few hundred bytes, and the steps of a longer end time would take
// years at any step an explicit run can have.
constexpr double kMaxFrames = 1e5;
constexpr double kMaxHistoryRows = 1e8;
constexpr double kMaxEndTime = 1e6;

}  // namespace

// ---------------------------------------------------------------------------------------------
// Sections

void Reader::read_simulation(const toml::table& root, ModelSpec& spec, toml::table& out) const {
  const toml::node* n = root.get("simulation");
  if (!n) fail(&root, "simulation", "required table [simulation] is missing (it needs end_time)");
  const toml::table& t = require_table(n, "simulation");
  const std::string p = "simulation";
  check_keys(t, p,
             {"end_time",
              "time_step_safety",
              "contact_time_step_safety",
              "time_step",
              "output_interval",
              "history_interval",
              "gravity",
              "threads",
              "bulk_viscosity_linear",
              "bulk_viscosity_quadratic",
              "mass_scaling_time_step",
              "mass_scaling_limit",
              "deformation_damping",
              "rest_kinetic_fraction",
              "rest_hold_time",
              "rebalance_threshold",
              "stable_step",
              "stable_step_interval",
              "checkpoint_interval",
              "checkpoint_wall_interval",
              "energy_balance_limit"});
  SimulationSettings& s = spec.simulation;
  s.end_time = positive(t, "end_time", p, std::nullopt, &t);
  s.time_step_safety = positive(t, "time_step_safety", p, s.time_step_safety, &t);
  if (s.time_step_safety > 1.0)
    fail(t.get("time_step_safety"), "simulation.time_step_safety",
         "must be in (0, 1] (a fraction of the stable time step), got " +
             format_number(s.time_step_safety));
  s.contact_time_step_safety =
      positive(t, "contact_time_step_safety", p, s.contact_time_step_safety, &t);
  if (s.contact_time_step_safety > 1.0)
    fail(t.get("contact_time_step_safety"), "simulation.contact_time_step_safety",
         "must be in (0, 1] (a fraction of the contact springs' own stable step), got " +
             format_number(s.contact_time_step_safety));
  s.time_step = positive(t, "time_step", p, 0.0, &t);
  if (const auto v = opt_string(t, "stable_step", p)) {
    if (*v == "assembled")
      s.stable_step = SimulationSettings::StableStep::assembled;
    else if (*v == "element")
      s.stable_step = SimulationSettings::StableStep::element;
    else
      fail(t.get("stable_step"), "simulation.stable_step",
           "must be \"assembled\" (the whole model's highest frequency, measured) or "
           "\"element\" (the element-by-element bound), got \"" +
               *v + "\"");
  }
  if (auto n = opt_integer(t, "stable_step_interval", p)) {
    if (*n < 1 || *n > 1000000)
      fail(t.get("stable_step_interval"), "simulation.stable_step_interval",
           "must be a number of steps in [1, 1000000], got " + std::to_string(*n));
    s.stable_step_interval = static_cast<int>(*n);
  }
  s.output_interval = positive(t, "output_interval", p, s.end_time / 50.0, &t);
  s.history_interval = positive(t, "history_interval", p, s.output_interval / 20.0, &t);
  // A schedule of absurd size would fill the disk, or spin for ever where the intervals vanish
  // against the time's round-off: refused with the bound.
  if (!(s.end_time <= kMaxEndTime))
    fail(t.get("end_time"), "simulation.end_time",
         "must be at most " + format_number(kMaxEndTime) + " s, got " + format_number(s.end_time));
  for (const auto& [key, interval, most] :
       {std::tuple{"output_interval", s.output_interval, kMaxFrames},
        std::tuple{"history_interval", s.history_interval, kMaxHistoryRows}}) {
    const double count = s.end_time / interval;
    if (!(count <= most) || !(interval > s.end_time * 1e-15))
      fail(t.get(key) ? t.get(key) : t.get("end_time"), dotted(p, key),
           std::string(key) + " = " + format_number(interval) + " s gives " + format_number(count) +
               (std::string(key) == "output_interval" ? " frames" : " rows") +
               " over end_time = " + format_number(s.end_time) + " s, more than the " +
               format_number(most) + " a run may write: make it longer");
  }
  for (const char* key : {"checkpoint_interval", "checkpoint_wall_interval"}) {
    const bool wall = std::string(key) == "checkpoint_wall_interval";
    double& v = wall ? s.checkpoint_wall_interval : s.checkpoint_interval;
    v = number(t, key, p, v, &t);
    if (!(v >= 0.0) || !std::isfinite(v))
      fail(t.get(key), dotted(p, key),
           std::string("must be 0 (off) or a positive number of ") +
               (wall ? "wall-clock" : "simulated") + " seconds, got " + format_number(v));
  }
  s.energy_balance_limit = number(t, "energy_balance_limit", p, s.energy_balance_limit, &t);
  if (!(s.energy_balance_limit >= 0.0 && s.energy_balance_limit <= 1.0))
    fail(t.get("energy_balance_limit"), "simulation.energy_balance_limit",
         "must be 0 (off) or a fraction in (0, 1], got " + format_number(s.energy_balance_limit));
  if (auto g = opt_vec3(t, "gravity", p)) s.gravity = *g;
  if (auto th = opt_integer(t, "threads", p)) {
    if (*th < 0 || *th > 4096)
      fail(t.get("threads"), "simulation.threads",
           "must be 0 (all cores) or a positive number of threads, got " + std::to_string(*th));
    s.threads = static_cast<int>(*th);
  }
  for (const char* key : {"bulk_viscosity_linear", "bulk_viscosity_quadratic"}) {
    const double v = number(t, key, p, 0.0, &t);
    if (v < 0.0 || v > 10.0)
      fail(t.get(key), dotted(p, key), "must lie in [0, 10], got " + format_number(v));
    (std::string(key) == "bulk_viscosity_linear" ? s.bulk_viscosity_linear
                                                 : s.bulk_viscosity_quadratic) = v;
  }
  s.mass_scaling_time_step = number(t, "mass_scaling_time_step", p, 0.0, &t);
  if (s.mass_scaling_time_step < 0.0)
    fail(t.get("mass_scaling_time_step"), "simulation.mass_scaling_time_step",
         "must be 0 (off) or a positive time step, got " + format_number(s.mass_scaling_time_step));
  if (s.mass_scaling_time_step > 0.0 && s.time_step > 0.0)
    fail(t.get("mass_scaling_time_step"), "simulation.mass_scaling_time_step",
         "works with the automatic step only: remove simulation.time_step (the step is then "
         "never below mass_scaling_time_step)");
  if (const toml::node* dn = t.get("deformation_damping")) {
    // { ratio = xi, frequency = f }: alpha = 2 xi omega makes the mode at f damped at xi
    const toml::table& d = require_table(dn, "simulation.deformation_damping");
    const std::string dp = "simulation.deformation_damping";
    check_keys(d, dp, {"ratio", "frequency"});
    const double ratio = number(d, "ratio", dp, std::nullopt, &d);
    if (ratio < 0.0 || ratio > 1.0)
      fail(d.get("ratio"), dotted(dp, "ratio"),
           "must be a fraction of critical damping in [0, 1], got " + format_number(ratio));
    const double frequency = positive(d, "frequency", dp, std::nullopt, &d);
    s.deformation_damping = 4.0 * M_PI * frequency * ratio;
    toml::table o;
    o.insert_or_assign("ratio", ratio);
    o.insert_or_assign("frequency", frequency);
    out.insert_or_assign("deformation_damping", std::move(o));
  }
  s.rest_kinetic_fraction = number(t, "rest_kinetic_fraction", p, 0.0, &t);
  if (s.rest_kinetic_fraction < 0.0 || s.rest_kinetic_fraction >= 1.0)
    fail(t.get("rest_kinetic_fraction"), "simulation.rest_kinetic_fraction",
         "must be 0 (off) or a fraction of the peak kinetic energy in (0, 1), got " +
             format_number(s.rest_kinetic_fraction));
  s.rest_hold_time = number(t, "rest_hold_time", p, 0.0, &t);
  s.rebalance_threshold = number(t, "rebalance_threshold", p, s.rebalance_threshold, &t);
  if (s.rest_hold_time < 0.0)
    fail(t.get("rest_hold_time"), "simulation.rest_hold_time",
         "must not be negative, got " + format_number(s.rest_hold_time));
  s.mass_scaling_limit = positive(t, "mass_scaling_limit", p, s.mass_scaling_limit, &t);
  if (t.get("mass_scaling_limit") && s.mass_scaling_time_step == 0.0)
    fail(t.get("mass_scaling_limit"), "simulation.mass_scaling_limit",
         "needs simulation.mass_scaling_time_step (mass scaling is off)");
  if (t.get("rest_hold_time") && s.rest_kinetic_fraction == 0.0)
    fail(t.get("rest_hold_time"), "simulation.rest_hold_time",
         "needs simulation.rest_kinetic_fraction (the stop-at-rest threshold)");
  out.insert_or_assign("end_time", s.end_time);
  out.insert_or_assign("time_step_safety", s.safety());
  out.insert_or_assign("contact_time_step_safety", s.contact_time_step_safety);
  if (s.time_step > 0.0) out.insert_or_assign("time_step", s.time_step);
  const bool assembled = s.stable_step == SimulationSettings::StableStep::assembled;
  out.insert_or_assign("stable_step", assembled ? "assembled" : "element");
  if (assembled) out.insert_or_assign("stable_step_interval", s.stable_step_interval);
  out.insert_or_assign("output_interval", s.output_interval);
  out.insert_or_assign("history_interval", s.history_interval);
  out.insert_or_assign("checkpoint_interval", s.checkpoint_interval);
  out.insert_or_assign("checkpoint_wall_interval", s.checkpoint_wall_interval);
  out.insert_or_assign("energy_balance_limit", s.energy_balance_limit);
  out.insert_or_assign("gravity", toml::array{s.gravity.x(), s.gravity.y(), s.gravity.z()});
  out.insert_or_assign("threads", s.threads);
  out.insert_or_assign("bulk_viscosity_linear", s.bulk_viscosity_linear);
  out.insert_or_assign("bulk_viscosity_quadratic", s.bulk_viscosity_quadratic);
  if (s.mass_scaling_time_step > 0.0) {
    out.insert_or_assign("mass_scaling_time_step", s.mass_scaling_time_step);
    out.insert_or_assign("mass_scaling_limit", s.mass_scaling_limit);
  }
  if (s.rest_kinetic_fraction > 0.0) {
    out.insert_or_assign("rest_kinetic_fraction", s.rest_kinetic_fraction);
    out.insert_or_assign("rest_hold_time",
                         s.rest_hold_time > 0.0 ? s.rest_hold_time : s.output_interval);
  }
}

}  // namespace femdem::scene
