// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/output_tables.hpp"

#include <span>

#include "tools/femdem/run/compaction_curve.hpp"
#include "tools/femdem/run/peak_monitor.hpp"
#include "tools/femdem/run/rest_monitor.hpp"

namespace femdem {
namespace {

using Run = HistorySample;

// Columns of the whole run, first in every row.
constexpr OutputEntry<Run> kRunColumns[] = {
    {"time", "s", "simulated time", [](const Run& s) { return s.time; }},
    {"dt", "s", "time step", [](const Run& s) { return s.dt; }},
    {"kinetic_energy", "J", "kinetic energy of all bodies",
     [](const Run& s) { return s.energies.kinetic; }},
    {"internal_energy", "J", "stored elastic (Hencky) energy",
     [](const Run& s) { return s.energies.internal; }},
    {"plastic_dissipation", "J", "plastic work so far",
     [](const Run& s) { return s.energies.plastic_dissipation; }},
    {"contact_energy", "J", "penalty energy stored in contacts now (walls and bodies)",
     [](const Run& s) { return s.energies.contact; }},
    {"contact_dissipation", "J",
     "work of friction, wall dashpots (`damping`), impact damping and rolling resistance so far",
     [](const Run& s) { return s.energies.contact_dissipation; }},
    {"viscous_dissipation", "J",
     "work of the artificial bulk viscosity and of `simulation.deformation_damping` so far",
     [](const Run& s) { return s.energies.viscous_dissipation; }},
    {"mass_scaling_dissipation", "J",
     "kinetic energy given up by nodes that gained mass from `simulation.mass_scaling_time_step` "
     "(they keep their momentum)",
     [](const Run& s) { return s.energies.mass_scaling_dissipation; }},
    {"external_work", "J", "work done on the bodies by gravity, moving walls and driven nodes",
     [](const Run& s) { return s.energies.external_work; }},
    {"total_energy", "J",
     "kinetic + internal + plastic_dissipation + contact + contact_dissipation + "
     "viscous_dissipation + mass_scaling_dissipation - external_work: constant in an exact "
     "solution",
     [](const Run& s) { return s.energies.balance(); }},
    {"energy_balance_error", "-",
     "change of total_energy since t = 0 over the largest energy seen in the run",
     [](const Run& s) { return s.balance_error; }},
};

// Per body, named `<body>.<column>`.
constexpr OutputEntry<BodySample> kBodyColumns[] = {
    {"com_x", "m", "centre of mass", [](const BodySample& b) { return b.motion.com.x(); }},
    {"com_y", "m", "", [](const BodySample& b) { return b.motion.com.y(); }},
    {"com_z", "m", "", [](const BodySample& b) { return b.motion.com.z(); }},
    {"vcom_x", "m/s", "centre-of-mass velocity",
     [](const BodySample& b) { return b.motion.vcom.x(); }},
    {"vcom_y", "m/s", "", [](const BodySample& b) { return b.motion.vcom.y(); }},
    {"vcom_z", "m/s", "", [](const BodySample& b) { return b.motion.vcom.z(); }},
    {"kinetic_energy", "J", "the body's kinetic energy",
     [](const BodySample& b) { return b.motion.kinetic_energy; }},
    {"contact_force_x", "N", "total force of walls and other bodies on the body",
     [](const BodySample& b) { return b.motion.contact_force.x(); }},
    {"contact_force_y", "N", "", [](const BodySample& b) { return b.motion.contact_force.y(); }},
    {"contact_force_z", "N", "", [](const BodySample& b) { return b.motion.contact_force.z(); }},
    {"max_principal_stress", "Pa",
     "largest principal Cauchy stress (tension positive) over the body's Gauss points: the "
     "peak tension that cracks concrete",
     [](const BodySample& b) { return b.max_principal_stress; }},
};

// Per wall, named `<wall>.<column>`.
constexpr OutputEntry<WallSample> kWallColumns[] = {
    {"force_x", "N", "force the bodies exert on the wall",
     [](const WallSample& w) { return w.force.x(); }},
    {"force_y", "N", "", [](const WallSample& w) { return w.force.y(); }},
    {"force_z", "N", "", [](const WallSample& w) { return w.force.z(); }},
    {"position_x", "m", "the wall's point (it moves with the wall)",
     [](const WallSample& w) { return w.position.x(); }},
    {"position_y", "m", "", [](const WallSample& w) { return w.position.y(); }},
    {"position_z", "m", "", [](const WallSample& w) { return w.position.z(); }},
    {"max_penetration", "m", "depth of the deepest body node behind the wall now",
     [](const WallSample& w) { return w.penetration; }},
    {"max_penetration_per_size", "-",
     "largest depth behind the wall over the depth of the element behind the node",
     [](const WallSample& w) { return w.penetration_per_size; }},
};

// When bodies can touch each other.
constexpr OutputEntry<Run> kContactColumns[] = {
    {"contact.max_penetration", "m",
     "deepest overlap between two bodies now: over the touching pairs of contact "
     "sub-tetrahedra, the largest 2E/N (E the pair's penalty energy, N its normal force), the "
     "depth of a flat overlap",
     [](const Run& s) { return s.max_penetration.value_or(0.0); }},
    {"contact.max_penetration_per_size", "-",
     "largest overlap over the element size: per touching pair, its depth over the thinner of "
     "the two elements' depths behind their boundary faces",
     [](const Run& s) { return s.max_penetration_per_size; }},
};

// With [compaction]. n is the die axis (the bottom wall's normal, into the powder), A and Π the
// die's cross-section and perimeter; forces are those of the powder on the walls.
using Compaction = CompactionSample;
constexpr OutputEntry<Compaction> kCompactionColumns[] = {
    {"compaction.punch_displacement", "m",
     "travel of the punch towards the bottom since t = 0: (x_punch(0) − x_punch) · n",
     [](const Compaction& c) { return c.punch_displacement; }},
    {"compaction.punch_force", "N",
     "force on the punch along n: f_punch · n (positive when pressed)",
     [](const Compaction& c) { return c.punch_force; }},
    {"compaction.punch_pressure", "Pa", "mean punch pressure P = punch_force / A",
     [](const Compaction& c) { return c.punch_pressure; }},
    {"compaction.bottom_force", "N", "force on the bottom against n: −f_bottom · n",
     [](const Compaction& c) { return c.bottom_force; }},
    {"compaction.die_normal_force", "N", "Σ over die walls of the outward normal force −f_w · n_w",
     [](const Compaction& c) { return c.die_normal_force; }},
    {"compaction.die_axial_force", "N",
     "Σ over die walls of −f_w · n: the die-wall friction, towards the bottom while the punch "
     "presses (then punch_force ≈ bottom_force + die_axial_force quasi-statically)",
     [](const Compaction& c) { return c.die_axial_force; }},
    {"compaction.radial_pressure", "Pa",
     "die-wall pressure: die_normal_force / (Π × height), the wetted area taken as the whole "
     "column height (NaN when `die_perimeter` is 0)",
     [](const Compaction& c) { return c.radial_pressure; }},
    {"compaction.height", "m", "punch to bottom along n: (x_punch − x_bottom) · n",
     [](const Compaction& c) { return c.height; }},
    {"compaction.solid_volume", "m³",
     "current volume of the powder bodies, ∫ det F over their deformed elements",
     [](const Compaction& c) { return c.solid_volume; }},
    {"compaction.relative_density", "-", "D = solid_volume / (A × height)",
     [](const Compaction& c) { return c.relative_density; }},
    {"compaction.volume_ratio", "-",
     "solid_volume / its value at t = 0 (volume conservation check: 1 for a plastically "
     "incompressible powder, below 1 by the elastic compression)",
     [](const Compaction& c) { return c.volume_ratio; }},
    {"compaction.column_strain", "-",
     "Kawakita's C = (V0 − V) / V0 of the column V = A × height: 1 − height / height(0)",
     [](const Compaction& c) { return c.column_strain; }},
};

// summary.json "extra" keys: written when `present` holds.
struct SummaryKey {
  const char* name;
  const char* unit;
  const char* meaning;
  const char* when;
  bool (*present)(const RunRecord&);
  double (*value)(const RunRecord&);
};

bool always(const RunRecord&) {
  return true;
}
bool resting(const RunRecord& r) {
  return r.rest.enabled();
}
bool assembled(const RunRecord& r) {
  return r.sim.model().settings.stable_step == SimulationSettings::StableStep::assembled;
}
bool body_contact(const RunRecord& r) {
  return r.sim.body_contact().active();
}
bool has_walls(const RunRecord& r) {
  return !r.sim.model().walls.empty();
}

constexpr SummaryKey kSummaryKeys[] = {
    {"setup_time_s", "s", "wall time to read the scene and build the model", "always", always,
     [](const RunRecord& r) { return r.setup_time_s; }},
    {"loop_time_s", "s", "wall time of the time loop", "always", always,
     [](const RunRecord& r) { return r.loop_time_s; }},
    {"element_updates_per_s", "1/s",
     "steps × elements / loop_time_s: the run's element-update rate, contact and outputs "
     "included",
     "always", always,
     [](const RunRecord& r) {
       return static_cast<double>(r.sim.steps()) * r.sim.model().element_count / r.loop_time_s;
     }},
    {"stable_time_step", "s", "the stable step estimate at the end", "always", always,
     [](const RunRecord& r) { return r.sim.stable_dt(); }},
    {"stable_time_step_bound", "s",
     "the element-and-contact bound at the end (elements and walls, with the touching bodies' "
     "springs added): `stable_time_step` over it is what the assembled "
     "estimate gained",
     "always", always, [](const RunRecord& r) { return r.sim.stable_bound(); }},
    {"stable_step_estimates", "-",
     "assembled estimates of the highest frequency made (Lanczos, `simulation.stable_step`)",
     "`simulation.stable_step` = \"assembled\"", assembled,
     [](const RunRecord& r) { return static_cast<double>(r.sim.frequency_estimates()); }},
    {"stable_step_iterations", "-",
     "their Lanczos iterations in all, each one application of the stiffness (about the cost of "
     "an elastic element pass)",
     "`simulation.stable_step` = \"assembled\"", assembled,
     [](const RunRecord& r) { return static_cast<double>(r.sim.frequency_iterations()); }},
    {"rest_kinetic_fraction", "-", "the scene's threshold, so that tools need not read the scene",
     "`simulation.rest_kinetic_fraction` > 0", resting,
     [](const RunRecord& r) { return r.rest.fraction(); }},
    {"peak_kinetic_energy", "J", "largest total kinetic energy at a history row",
     "`simulation.rest_kinetic_fraction` > 0", resting,
     [](const RunRecord& r) { return r.rest.peak(); }},
    {"peak_kinetic_energy_time", "s", "when it occurred", "`simulation.rest_kinetic_fraction` > 0",
     resting, [](const RunRecord& r) { return r.rest.peak_time(); }},
    {"at_rest_time", "s", "when the run came to rest and stopped", "the run came to rest",
     [](const RunRecord& r) { return r.rest.at_rest(); },
     [](const RunRecord& r) { return r.rest.rest_time(); }},
    {"broadphase_runs", "-", "how often the broadphase (NBS) ran", "bodies can touch each other",
     body_contact,
     [](const RunRecord& r) {
       return static_cast<double>(r.sim.body_contact().broadphase_runs());
     }},
    {"contact_pair_evaluations", "-",
     "candidate sub-tet pairs (those listed as able to touch before the next broadphase), summed "
     "over the steps; a candidate whose boxes are apart that step is counted but not put through "
     "the pair kernel",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) {
       return static_cast<double>(r.sim.body_contact().pair_evaluations());
     }},
    {"contact_touching_pair_evaluations", "-", "of those, the pairs that overlapped",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) {
       return static_cast<double>(r.sim.body_contact().touching_evaluations());
     }},
    {"contact_max_penetration", "m", "largest `contact.max_penetration` of the history rows",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) { return r.peaks.penetration(); }},
    {"contact_max_penetration_time", "s", "when it occurred", "bodies can touch each other",
     body_contact, [](const RunRecord& r) { return r.peaks.penetration_time(); }},
    {"contact_final_max_penetration", "m", "the deepest overlap at the end",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) { return r.sim.body_contact().max_penetration(); }},
    {"contact_max_penetration_per_size", "-",
     "largest `contact.max_penetration_per_size` of the history rows (the run log warns above "
     "0.1)",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) { return r.peaks.penetration_per_size(); }},
    {"contact_max_penetration_per_size_time", "s", "when it occurred",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) { return r.peaks.penetration_per_size_time(); }},
    {"walls_max_penetration", "m", "largest `<wall>.max_penetration` of the history rows",
     "the scene has walls", has_walls,
     [](const RunRecord& r) { return r.peaks.wall_penetration(); }},
    {"walls_max_penetration_per_size", "-",
     "largest `<wall>.max_penetration_per_size` of the history rows (the run log warns above "
     "0.1)",
     "the scene has walls", has_walls,
     [](const RunRecord& r) { return r.peaks.wall_penetration_per_size(); }},
    {"walls_max_penetration_per_size_time", "s", "when it occurred", "the scene has walls",
     has_walls, [](const RunRecord& r) { return r.peaks.wall_penetration_per_size_time(); }},
    {"contact_sub_tet_min_edge", "m",
     "smallest edge of the contact sub-tetrahedra: the scale to compare overlaps with",
     "bodies can touch each other", body_contact,
     [](const RunRecord& r) { return r.sim.model().contact_tet_min_edge; }},
    {"compaction_time_s", "s", "wall time spent on the compaction columns", "`[compaction]`",
     [](const RunRecord& r) { return r.compaction != nullptr; },
     [](const RunRecord& r) { return r.compaction->sample_time_s; }},
};

template <class S>
void append_values(std::span<const OutputEntry<S>> table, const S& s, std::vector<double>& row) {
  for (const OutputEntry<S>& c : table) row.push_back(c.value(s));
}

// One Markdown table of columns under its title.
template <class S>
void append_table(std::string& md, const char* title, std::span<const OutputEntry<S>> table,
                  const char* prefix) {
  md += std::string(md.empty() ? "" : "\n") + title +
        "\n\n| column | unit | meaning |\n|---|---|---|\n";
  for (const OutputEntry<S>& c : table)
    md += std::string("| `") + prefix + c.name + "` | " + c.unit + " | " + c.meaning + " |\n";
}

}  // namespace

std::vector<std::string> history_columns(const HistoryLayout& layout) {
  std::vector<std::string> c;
  for (const auto& e : kRunColumns) c.emplace_back(e.name);
  for (const std::string& b : layout.bodies)
    for (const auto& e : kBodyColumns) c.push_back(b + "." + e.name);
  for (const std::string& w : layout.walls)
    for (const auto& e : kWallColumns) c.push_back(w + "." + e.name);
  if (layout.body_contact)
    for (const auto& e : kContactColumns) c.emplace_back(e.name);
  if (layout.compaction)
    for (const auto& e : kCompactionColumns) c.emplace_back(e.name);
  return c;
}

void history_row(const HistorySample& s, std::vector<double>& row) {
  row.clear();
  append_values<Run>(kRunColumns, s, row);
  for (const BodySample& b : s.bodies) append_values<BodySample>(kBodyColumns, b, row);
  for (const WallSample& w : s.walls) append_values<WallSample>(kWallColumns, w, row);
  if (s.max_penetration) append_values<Run>(kContactColumns, s, row);
  if (s.compaction) append_values<Compaction>(kCompactionColumns, *s.compaction, row);
}

std::vector<std::pair<std::string, double>> summary_extra(const RunRecord& run) {
  std::vector<std::pair<std::string, double>> out;
  for (const SummaryKey& k : kSummaryKeys)
    if (k.present(run)) out.emplace_back(k.name, k.value(run));
  return out;
}

std::string output_tables_markdown() {
  std::string md;
  append_table<Run>(md, "Every run:", kRunColumns, "");
  append_table<BodySample>(md, "Then for every body, in the scene's order:", kBodyColumns,
                           "<body>.");
  append_table<WallSample>(md, "Then for every wall, in the scene's order:", kWallColumns,
                           "<wall>.");
  append_table<Run>(md, "Then, when bodies can touch each other:", kContactColumns, "");
  append_table<Compaction>(md, "Then, for scenes with `[compaction]`:", kCompactionColumns, "");
  md += summary_keys_markdown();
  md += "\n`extra`:\n\n| key | unit | meaning | written when |\n|---|---|---|---|\n";
  for (const SummaryKey& k : kSummaryKeys)
    md +=
        std::string("| `") + k.name + "` | " + k.unit + " | " + k.meaning + " | " + k.when + " |\n";
  return md;
}

}  // namespace femdem
