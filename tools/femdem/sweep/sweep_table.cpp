// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/sweep/sweep_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace femdem::sweep {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Run folders

static std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

void assign_short_names(std::vector<Axis>& axes) {
  std::size_t depth = 1;
  while (true) {
    std::set<std::string> seen;
    bool unique = true;
    bool more = false;
    for (auto& a : axes) {
      const auto parts = key_parts(a.key);
      const std::size_t n = std::min(depth, parts.size());
      if (n < parts.size()) more = true;
      std::string s;
      for (std::size_t i = parts.size() - n; i < parts.size(); ++i)
        s += (s.empty() ? "" : ".") + parts[i];
      a.short_name = s;
      unique = seen.insert(s).second && unique;
    }
    if (unique || !more) return;
    ++depth;
  }
}

// A folder-name-friendly rendering of a value: brackets, braces, quotes and spaces dropped,
// anything else unusual replaced by '_'.
std::string folder_text(const std::string& value) {
  std::string s;
  for (char c : value) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
        c == ',' || c == '_')
      s += c;
    else if (c == '[' || c == ']' || c == '{' || c == '}' || c == '"' || c == '\'' || c == ' ' ||
             c == '(' || c == ')')
      continue;
    else
      s += '_';
  }
  if (s.size() > 40) s = s.substr(0, 40);
  if (s.empty()) s = "_";
  return s;
}

// ---------------------------------------------------------------------------------------------
// Results

// The resolved scene a run recorded in its run.log, if any.
std::optional<std::string> logged_resolved_scene(const fs::path& run_log) {
  std::ifstream in(run_log, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::string begin = "# resolved scene\n", end = "\n# end of resolved scene";
  const std::size_t a = text.find(begin);
  if (a == std::string::npos) return std::nullopt;
  const std::size_t b = text.find(end, a + begin.size());
  if (b == std::string::npos) return std::nullopt;
  return text.substr(a + begin.size(), b - a - begin.size());
}

std::optional<Json> read_summary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    return Json::parse(in);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

static std::string number_text(const Json& v) {
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_unsigned()) return std::to_string(v.get<unsigned long long>());
  char buf[64];
  // Shortest text that reads back to the same double.
  const double d = v.get<double>();
  for (int prec = 1; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, d);
    if (std::strtod(buf, nullptr) == d) break;
  }
  return buf;
}

// summary.json flattened to dotted columns: vectors of three as .x/.y/.z, a null restitution as
// two empty columns (so the columns do not depend on whether a body bounced).
void flatten(const Json& j, const std::string& prefix, Fields& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      // the scene is the same for every run; the checkpoint is the run folder's bookkeeping
      if (prefix.empty() && (it.key() == "scene" || it.key() == "checkpoint")) continue;
      flatten(it.value(), prefix + it.key() + ".", out);
    }
    return;
  }
  const std::string name = prefix.substr(0, prefix.size() - 1);
  if (j.is_array()) {
    static const char* xyz[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < j.size(); ++i)
      flatten(j[i], prefix + (j.size() == 3 ? xyz[i] : std::to_string(i)) + ".", out);
  } else if (j.is_null()) {
    if (name.size() >= 26 && name.ends_with("coefficient_of_restitution")) {
      out.emplace_back(name + ".com", "");
      out.emplace_back(name + ".kinetic_energy", "");
    } else {
      out.emplace_back(name, "");
    }
  } else if (j.is_number()) {
    out.emplace_back(name, number_text(j));
  } else if (j.is_boolean()) {
    out.emplace_back(name, j.get<bool>() ? "true" : "false");
  } else if (j.is_string()) {
    out.emplace_back(name, j.get<std::string>());
  }
}

static std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

// sweep.csv: the finished runs in sweep order; the columns are the union over them.
std::string csv_text(const std::vector<Axis>& axes, const std::vector<Run>& runs) {
  std::vector<std::string> columns;
  std::set<std::string> known;
  for (const auto& r : runs) {
    if (r.outcome == Outcome::pending || r.outcome == Outcome::running) continue;
    for (const auto& [k, v] : r.fields)
      if (known.insert(k).second) columns.push_back(k);
  }
  std::string out;
  for (const auto& a : axes) out += csv_field(a.key) + ",";
  out += "run,exit_code";
  for (const auto& c : columns) {
    out += ',';
    out += csv_field(c);
  }
  out += '\n';
  for (const auto& r : runs) {
    if (r.outcome == Outcome::pending || r.outcome == Outcome::running) continue;
    for (const auto& v : r.values) out += csv_field(v) + ",";
    out += csv_field(r.name) + "," + std::to_string(r.exit_code);
    std::map<std::string, std::string> m(r.fields.begin(), r.fields.end());
    for (const auto& c : columns) {
      out += ",";
      if (auto it = m.find(c); it != m.end()) out += csv_field(it->second);
    }
    out += "\n";
  }
  return out;
}

std::string run_label(const std::vector<Axis>& axes, const Run& r) {
  std::string s;
  for (std::size_t a = 0; a < axes.size(); ++a)
    s += (a ? ", " : "") + axes[a].short_name + "=" + r.values[a];
  return s;
}

}  // namespace femdem::sweep
