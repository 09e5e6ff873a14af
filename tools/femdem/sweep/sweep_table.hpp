// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The runs of a sweep and its table: each run's values and sub-folder name, its outcome, its
// summary.json flattened to columns, and sweep.csv made from them (docs/OUTPUTS.md).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace femdem::sweep {

using Json = nlohmann::ordered_json;
using Fields = std::vector<std::pair<std::string, std::string>>;

struct Axis {
  std::string key;
  std::vector<std::string> values;
  std::string short_name;  // the key's last parts, enough to tell the axes apart
};

enum class Outcome { pending, running, skipped, completed, diverged, failed, interrupted };

struct Run {
  std::vector<std::string> values;  // one per axis
  std::string name;                 // sub-folder
  std::string resolved;             // resolved scene
  Outcome outcome = Outcome::pending;
  int exit_code = 0;
  Fields fields;  // flattened summary.json
  double started = 0.0;
  bool resume = false;  // interrupted with a checkpoint of the same scene: resumed, not rerun
};

// Gives every axis the shortest tail of its dotted key that tells it from the others.
void assign_short_names(std::vector<Axis>& axes);
// A folder-name-friendly rendering of a value: brackets, braces, quotes and spaces dropped,
// anything else unusual replaced by '_'.
std::string folder_text(const std::string& value);
// The resolved scene a run recorded in its run.log, if any.
std::optional<std::string> logged_resolved_scene(const std::filesystem::path& run_log);
std::optional<Json> read_summary(const std::filesystem::path& path);
// summary.json flattened to dotted columns: vectors of three as .x/.y/.z, a null restitution as
// two empty columns (so the columns do not depend on whether a body bounced).
void flatten(const Json& j, const std::string& prefix, Fields& out);
// sweep.csv: the finished runs in sweep order; the columns are the union over them.
std::string csv_text(const std::vector<Axis>& axes, const std::vector<Run>& runs);
// "short_name=value, ..." of a run, for the progress lines.
std::string run_label(const std::vector<Axis>& axes, const Run& r);

}  // namespace femdem::sweep
