// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// summary.json: the run's scalar results (docs/OUTPUTS.md), read by `sweep` and by
// scripts. Written atomically: a half-written summary never exists.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/compaction.hpp"

namespace femdem {

enum class RunStatus { completed, unstable, interrupted };
const char* to_string(RunStatus status);  // "completed", "unstable", "interrupted"

struct EnergySummary {
  double kinetic = 0.0;
  double internal = 0.0;
  double plastic_dissipation = 0.0;
  double contact = 0.0;
  double contact_dissipation = 0.0;
  double viscous_dissipation = 0.0;
  double mass_scaling_dissipation = 0.0;
  double external_work = 0.0;
  double balance_error = 0.0;
};

struct Restitution {
  double com = 0.0;             // |v_com| after the last contact / before the first
  double kinetic_energy = 0.0;  // sqrt(KE_after / KE_before)
};

struct BodySummary {
  std::string name;
  double mass = 0.0;        // rho V0
  double added_mass = 0.0;  // by simulation.mass_scaling_time_step
  double volume = 0.0;
  std::array<double, 3> com{}, vcom{};
  std::array<double, 3> angular_velocity{};  // rad/s about the centre of mass
  double kinetic_energy = 0.0;
  std::array<double, 3> bbox_min{}, bbox_max{};
  double max_equivalent_plastic_strain = 0.0;
  // Largest principal stress (tension positive) over the body and the run, sampled at the
  // history rows, and when it occurred.
  double max_principal_stress = 0.0;
  double max_principal_stress_time = 0.0;
  std::optional<Restitution> coefficient_of_restitution;  // null unless it touched and left
};

// Closed-die compaction results (the scene's [compaction] section), from the history rows.
struct CompactionSummary {
  double max_punch_pressure = 0.0, max_punch_force = 0.0, max_radial_pressure = 0.0;
  double initial_relative_density = 0.0, final_relative_density = 0.0;
  double max_relative_density = 0.0, relative_density_at_max_pressure = 0.0;
  double final_punch_displacement = 0.0, initial_solid_volume = 0.0;
  double final_volume_change = 0.0, max_abs_volume_change = 0.0;
  // The pressure window both fits use (the loading part of the curve within it).
  double fit_pressure_min = 0.0, fit_pressure_max = 0.0;
  HeckelFit heckel;
  KawakitaFit kawakita;
};

// The run's last checkpoint (checkpoint.h5): where `femdem resume` continues from.
struct CheckpointSummary {
  std::string file;   // path of checkpoint.h5
  double time = 0.0;  // s, simulated time it holds
  std::int64_t step = 0;
  std::string resume;  // the command that continues the run
};
struct RunSummary {
  std::string scene;  // scene file as given
  RunStatus status = RunStatus::completed;
  double end_time = 0.0;  // simulated time reached
  std::int64_t steps = 0;
  double time_step = 0.0;
  double wall_time_s = 0.0;
  int threads = 0;
  std::int64_t nodes = 0;
  std::int64_t elements = 0;
  EnergySummary energy;
  std::vector<BodySummary> bodies;              // written as an object keyed by name, in this order
  std::map<std::string, double> extra;          // further named scalars, written under "extra"
  std::optional<CompactionSummary> compaction;  // written as "compaction" when present
  std::optional<CheckpointSummary> checkpoint;  // written as "checkpoint" when present
};

// The JSON text (2-space indented, keys in the order of docs/OUTPUTS.md, doubles in shortest
// round-trip form; non-finite numbers become null). The keys come from one table
// (summary_writer.cpp) that also makes the tables of docs/OUTPUTS.md (summary_keys_markdown).
std::string summary_to_json(const RunSummary& summary);

// The Markdown tables of summary.json's keys (top level, energy, per body, compaction) with
// their units and meanings, as docs/OUTPUTS.md shows them.
std::string summary_keys_markdown();

// Writes summary_to_json(summary) to `path` atomically (temp file + fsync + rename).
// Throws std::runtime_error.
void write_summary(const std::filesystem::path& path, const RunSummary& summary);

}  // namespace femdem
