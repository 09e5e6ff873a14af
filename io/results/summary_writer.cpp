// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/results/summary_writer.hpp"

#include <nlohmann/json.hpp>
#include <span>

#include "io/atomic_file.hpp"

namespace femdem {

namespace {

using Json = nlohmann::ordered_json;

// One key of summary.json: its unit ("-" for a ratio, count or text), its meaning and its
// value read from an S. The writer and the tables of docs/OUTPUTS.md both walk these lists.
template <class S>
struct SummaryKey {
  const char* name;
  const char* unit;
  const char* meaning;
  Json (*value)(const S&);
};

Json vec3(const std::array<double, 3>& v) {
  return Json::array({v[0], v[1], v[2]});
}

const SummaryKey<RunSummary> kRunKeys[] = {
    {"scene", "-", "the scene file as given", [](const RunSummary& s) { return Json(s.scene); }},
    {"status", "-",
     "`completed`, `unstable` (the run diverged, exit code 3) or `interrupted` (by a signal)",
     [](const RunSummary& s) { return Json(to_string(s.status)); }},
    {"end_time", "s", "simulated time reached",
     [](const RunSummary& s) { return Json(s.end_time); }},
    {"steps", "-", "time steps taken", [](const RunSummary& s) { return Json(s.steps); }},
    {"time_step", "s", "the last step", [](const RunSummary& s) { return Json(s.time_step); }},
    {"wall_time_s", "s", "wall time of the whole run",
     [](const RunSummary& s) { return Json(s.wall_time_s); }},
    {"threads", "-", "OpenMP threads", [](const RunSummary& s) { return Json(s.threads); }},
    {"nodes", "-", "nodes of the model", [](const RunSummary& s) { return Json(s.nodes); }},
    {"elements", "-", "TET10 elements of the model",
     [](const RunSummary& s) { return Json(s.elements); }},
};

const SummaryKey<EnergySummary> kEnergyKeys[] = {
    {"kinetic", "J", "kinetic energy at the end",
     [](const EnergySummary& e) { return Json(e.kinetic); }},
    {"internal", "J", "stored elastic energy at the end",
     [](const EnergySummary& e) { return Json(e.internal); }},
    {"plastic_dissipation", "J", "plastic work over the run",
     [](const EnergySummary& e) { return Json(e.plastic_dissipation); }},
    {"contact", "J", "penalty energy stored in contacts at the end",
     [](const EnergySummary& e) { return Json(e.contact); }},
    {"contact_dissipation", "J",
     "work of friction, wall dashpots, impact damping and rolling resistance",
     [](const EnergySummary& e) { return Json(e.contact_dissipation); }},
    {"viscous_dissipation", "J", "work of bulk viscosity and deformation damping",
     [](const EnergySummary& e) { return Json(e.viscous_dissipation); }},
    {"mass_scaling_dissipation", "J", "kinetic energy given up by mass scaling",
     [](const EnergySummary& e) { return Json(e.mass_scaling_dissipation); }},
    {"external_work", "J", "work of gravity, moving walls and driven nodes",
     [](const EnergySummary& e) { return Json(e.external_work); }},
    {"balance_error", "-", "the history's `energy_balance_error` at the end",
     [](const EnergySummary& e) { return Json(e.balance_error); }},
};

const SummaryKey<BodySummary> kBodyKeys[] = {
    {"mass", "kg", "ρV₀ of the body", [](const BodySummary& b) { return Json(b.mass); }},
    {"added_mass", "kg", "what `simulation.mass_scaling_time_step` added (0 without it)",
     [](const BodySummary& b) { return Json(b.added_mass); }},
    {"volume", "m³", "current volume", [](const BodySummary& b) { return Json(b.volume); }},
    {"com", "m", "centre of mass [x, y, z]", [](const BodySummary& b) { return vec3(b.com); }},
    {"vcom", "m/s", "centre-of-mass velocity", [](const BodySummary& b) { return vec3(b.vcom); }},
    {"angular_velocity", "rad/s",
     "mean spin about the centre of mass (angular momentum through the current inertia tensor)",
     [](const BodySummary& b) { return vec3(b.angular_velocity); }},
    {"kinetic_energy", "J", "the body's kinetic energy",
     [](const BodySummary& b) { return Json(b.kinetic_energy); }},
    {"bbox_min", "m", "lower corner of the deformed body's bounding box",
     [](const BodySummary& b) { return vec3(b.bbox_min); }},
    {"bbox_max", "m", "upper corner", [](const BodySummary& b) { return vec3(b.bbox_max); }},
    {"max_equivalent_plastic_strain", "-", "largest over the Gauss points (it never decreases)",
     [](const BodySummary& b) { return Json(b.max_equivalent_plastic_strain); }},
    {"max_principal_stress", "Pa",
     "largest `<body>.max_principal_stress` of the history rows (sampled at the history "
     "interval)",
     [](const BodySummary& b) { return Json(b.max_principal_stress); }},
    {"max_principal_stress_time", "s", "when it occurred",
     [](const BodySummary& b) { return Json(b.max_principal_stress_time); }},
    {"coefficient_of_restitution", "-",
     "`{\"com\": v_after / v_before, \"kinetic_energy\": sqrt(KE_after / KE_before)}` from just "
     "before the first contact and just after the last; null unless the body touched and left",
     [](const BodySummary& b) {
       if (!b.coefficient_of_restitution) return Json(nullptr);
       return Json{{"com", b.coefficient_of_restitution->com},
                   {"kinetic_energy", b.coefficient_of_restitution->kinetic_energy}};
     }},
};

using Compaction = CompactionSummary;
const SummaryKey<Compaction> kCompactionKeys[] = {
    {"max_punch_pressure", "Pa", "largest punch pressure",
     [](const Compaction& c) { return Json(c.max_punch_pressure); }},
    {"max_punch_force", "N", "largest punch force",
     [](const Compaction& c) { return Json(c.max_punch_force); }},
    {"max_radial_pressure", "Pa", "largest die-wall pressure",
     [](const Compaction& c) { return Json(c.max_radial_pressure); }},
    {"initial_relative_density", "-", "D at the first row",
     [](const Compaction& c) { return Json(c.initial_relative_density); }},
    {"final_relative_density", "-", "D at the last row",
     [](const Compaction& c) { return Json(c.final_relative_density); }},
    {"max_relative_density", "-", "largest D",
     [](const Compaction& c) { return Json(c.max_relative_density); }},
    {"relative_density_at_max_pressure", "-", "D at the largest punch pressure",
     [](const Compaction& c) { return Json(c.relative_density_at_max_pressure); }},
    {"final_punch_displacement", "m", "punch travel at the end",
     [](const Compaction& c) { return Json(c.final_punch_displacement); }},
    {"initial_solid_volume", "m³", "the powder's solid volume at t = 0",
     [](const Compaction& c) { return Json(c.initial_solid_volume); }},
    {"final_volume_change", "-", "V/V0 − 1 at the end",
     [](const Compaction& c) { return Json(c.final_volume_change); }},
    {"max_abs_volume_change", "-", "largest |V/V0 − 1|",
     [](const Compaction& c) { return Json(c.max_abs_volume_change); }},
};

const SummaryKey<Compaction> kHeckelKeys[] = {
    {"K", "1/Pa", "slope of ln(1 / (1 − D)) against P",
     [](const Compaction& c) { return Json(c.heckel.K); }},
    {"A", "-", "intercept", [](const Compaction& c) { return Json(c.heckel.A); }},
    {"yield_pressure", "Pa", "1 / K, the mean yield pressure",
     [](const Compaction& c) { return Json(c.heckel.yield_pressure); }},
    {"r2", "-", "R² of the fit", [](const Compaction& c) { return Json(c.heckel.r2); }},
    {"pressure_min", "Pa", "lower end of the fitted pressures",
     [](const Compaction& c) { return Json(c.fit_pressure_min); }},
    {"pressure_max", "Pa", "upper end",
     [](const Compaction& c) { return Json(c.fit_pressure_max); }},
    {"points", "-", "history rows used", [](const Compaction& c) { return Json(c.heckel.points); }},
};

const SummaryKey<Compaction> kKawakitaKeys[] = {
    {"a", "-", "limiting column strain, 1 / slope of P / C against P",
     [](const Compaction& c) { return Json(c.kawakita.a); }},
    {"b", "1/Pa", "slope / intercept", [](const Compaction& c) { return Json(c.kawakita.b); }},
    {"r2", "-", "R² of the fit", [](const Compaction& c) { return Json(c.kawakita.r2); }},
    {"pressure_min", "Pa", "lower end of the fitted pressures",
     [](const Compaction& c) { return Json(c.fit_pressure_min); }},
    {"pressure_max", "Pa", "upper end",
     [](const Compaction& c) { return Json(c.fit_pressure_max); }},
    {"points", "-", "history rows used",
     [](const Compaction& c) { return Json(c.kawakita.points); }},
};

const SummaryKey<CheckpointSummary> kCheckpointKeys[] = {
    {"file", "-", "the checkpoint file (in the output folder)",
     [](const CheckpointSummary& c) { return Json(c.file); }},
    {"time", "s", "the simulated time it holds",
     [](const CheckpointSummary& c) { return Json(c.time); }},
    {"step", "-", "the step it holds", [](const CheckpointSummary& c) { return Json(c.step); }},
    {"resume", "-",
     "the command that continues the run from it (with `--set simulation.end_time=...`: "
     "extends it)",
     [](const CheckpointSummary& c) { return Json(c.resume); }},
};

template <class S>
Json object_of(std::span<const SummaryKey<S>> keys, const S& s) {
  Json j = Json::object();
  for (const SummaryKey<S>& k : keys) j[k.name] = k.value(s);
  return j;
}

template <class S>
void append_table(std::string& md, const std::string& title, std::span<const SummaryKey<S>> keys,
                  const char* prefix) {
  md += "\n" + title + "\n\n| key | unit | meaning |\n|---|---|---|\n";
  for (const SummaryKey<S>& k : keys)
    md += std::string("| `") + prefix + k.name + "` | " + k.unit + " | " + k.meaning + " |\n";
}

}  // namespace

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed:
      return "completed";
    case RunStatus::unstable:
      return "unstable";
    case RunStatus::interrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string summary_to_json(const RunSummary& s) {
  Json j = object_of<RunSummary>(kRunKeys, s);
  j["energy"] = object_of<EnergySummary>(kEnergyKeys, s.energy);
  Json bodies = Json::object();
  for (const BodySummary& b : s.bodies) bodies[b.name] = object_of<BodySummary>(kBodyKeys, b);
  j["bodies"] = std::move(bodies);
  Json extra = Json::object();
  for (const auto& [key, value] : s.extra) extra[key] = value;
  j["extra"] = std::move(extra);
  if (s.compaction) {
    Json c = object_of<Compaction>(kCompactionKeys, *s.compaction);
    c["heckel"] = object_of<Compaction>(kHeckelKeys, *s.compaction);
    c["kawakita"] = object_of<Compaction>(kKawakitaKeys, *s.compaction);
    j["compaction"] = std::move(c);
  }
  if (s.checkpoint) j["checkpoint"] = object_of<CheckpointSummary>(kCheckpointKeys, *s.checkpoint);
  // Invalid UTF-8 in a name is replaced rather than thrown on: the summary must get written.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string summary_keys_markdown() {
  std::string md;
  append_table<RunSummary>(md, "summary.json, top level:", kRunKeys, "");
  append_table<EnergySummary>(md, "`energy` (at the end of the run):", kEnergyKeys, "");
  append_table<BodySummary>(md, "`bodies.<body>`, for every body in the scene's order:", kBodyKeys,
                            "");
  append_table<Compaction>(md, "`compaction` (scenes with `[compaction]`):", kCompactionKeys, "");
  append_table<Compaction>(md, "`compaction.heckel`:", kHeckelKeys, "");
  append_table<Compaction>(md, "`compaction.kawakita`:", kKawakitaKeys, "");
  append_table<CheckpointSummary>(
      md,
      "`checkpoint` (the run's last checkpoint, written at the end of the run, on a signal "
      "and periodically; `femdem resume`):",
      kCheckpointKeys, "");
  return md;
}

void write_summary(const std::filesystem::path& path, const RunSummary& summary) {
  write_file_atomically(path, summary_to_json(summary), /*durable=*/true);
}

}  // namespace femdem
