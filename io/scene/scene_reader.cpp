// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/scene_reader.hpp"

#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"
#include "materials/piecewise_drucker_prager.hpp"
#include "materials/von_mises.hpp"

#include <toml++/toml.h>
#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/cad_mesh.hpp"
#include "io/mesh/gmsh_io.hpp"
#include "io/mesh/mesh_cache.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/packing/packing.hpp"

namespace femdem {

namespace fs = std::filesystem;

Eigen::Matrix3d rotation_from_degrees(const Vec3& rotation_degrees) {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(k * rotation_degrees.z(), Vec3::UnitZ()) *
          Eigen::AngleAxisd(k * rotation_degrees.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(k * rotation_degrees.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

void place_mesh(Tet10Mesh& mesh, const Vec3& rotation_degrees, const Vec3& position) {
  const Eigen::Matrix3d r = rotation_from_degrees(rotation_degrees);
  for (Vec3& p : mesh.nodes) p = r * p + position;
}

namespace {

// ---------------------------------------------------------------------------------------------
// Small helpers

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const std::size_t cost = (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                std::tolower(static_cast<unsigned char>(b[j - 1])))
                                   ? 0
                                   : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + cost});
      diag = up;
    }
  }
  return row[b.size()];
}

// " (did you mean 'xxx'?)" for the closest candidate within a few edits, else "".
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  std::size_t best = std::string::npos;
  std::string best_word;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best) {
      best = d;
      best_word = c;
    }
  }
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  if (best_word.empty() || best > limit || best >= std::max(word.size(), best_word.size()))
    return {};
  return " (did you mean '" + best_word + "'?)";
}

std::string join(const std::vector<std::string>& items, std::string_view sep = ", ") {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) s += sep;
    s += items[i];
  }
  return s;
}

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

std::string format_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, r.ptr);
}

// A TOML basic string literal holding s.
std::string toml_string_literal(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// The resolved scene as TOML text: sections in the order of the documentation, "name" first in
// each entry, sub-tables inline, numbers in shortest round-trip form (so it reads back exactly).
void write_toml_value(std::ostream& os, const toml::node& n);

void write_toml_float(std::ostream& os, double v) {
  std::string s = format_number(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a TOML float
  os << s;
}

std::vector<std::string> ordered_keys(const toml::table& t) {
  std::vector<std::string> keys;
  if (t.contains("name")) keys.push_back("name");
  for (const auto& [k, v] : t)
    if (k.str() != "name") keys.emplace_back(k.str());
  return keys;
}

void write_toml_value(std::ostream& os, const toml::node& n) {
  if (auto s = n.as_string()) {
    os << toml_string_literal(s->get());
  } else if (auto i = n.as_integer()) {
    os << i->get();
  } else if (auto f = n.as_floating_point()) {
    write_toml_float(os, f->get());
  } else if (auto b = n.as_boolean()) {
    os << (b->get() ? "true" : "false");
  } else if (auto a = n.as_array()) {
    os << "[";
    for (std::size_t i = 0; i < a->size(); ++i) {
      if (i) os << ", ";
      write_toml_value(os, *a->get(i));
    }
    os << "]";
  } else if (auto t = n.as_table()) {
    os << "{ ";
    bool first = true;
    for (const auto& k : ordered_keys(*t)) {
      if (!first) os << ", ";
      first = false;
      os << k << " = ";
      write_toml_value(os, *t->get(k));
    }
    os << (first ? "}" : " }");
  }
}

void write_toml_entries(std::ostream& os, const toml::table& t) {
  for (const auto& k : ordered_keys(t)) {
    os << k << " = ";
    write_toml_value(os, *t.get(k));
    os << "\n";
  }
}

std::string resolved_scene_text(const toml::table& root) {
  std::ostringstream os;
  for (const auto& [k, v] : root)
    if (!v.is_table() && !v.is_array()) {
      os << k.str() << " = ";
      write_toml_value(os, v);
      os << "\n";
    }
  for (const char* section : {"simulation", "materials", "bodies", "packings", "walls",
                              "constraints", "contact", "compaction"}) {
    const toml::node* n = root.get(section);
    if (!n) continue;
    if (const toml::table* t = n->as_table()) {
      os << "\n[" << section << "]\n";
      write_toml_entries(os, *t);
    } else if (const toml::array* a = n->as_array()) {
      for (const auto& e : *a) {
        os << "\n[[" << section << "]]\n";
        write_toml_entries(os, *e.as_table());
      }
    }
  }
  return os.str();
}

const std::vector<std::string> kGenerators = {"box", "cylinder", "sphere"};

// ---------------------------------------------------------------------------------------------
// The reader: walks the (overridden) TOML tree, checks it, fills the ModelSpec and the resolved
// scene.

class Reader {
 public:
  Reader(std::string scene_path, fs::path base_dir)
      : scene_path_(std::move(scene_path)), base_dir_(std::move(base_dir)) {}

  void apply_override(toml::table& root, const std::string& text);
  ModelSpec read(const toml::table& root, const std::string& stem, toml::table& resolved);

 private:
  struct Location {
    std::string file;
    int line = 0, column = 0;
    std::string note;  // " (set by --set ...)" for values from the command line
  };

  Location locate(const toml::node* node) const;
  Location locate(const toml::source_region& region, const toml::node* fallback) const;
  [[noreturn]] void fail(const toml::node* node, const std::string& key,
                         const std::string& message) const;
  [[noreturn]] void fail_at(const Location& at, const std::string& key,
                            const std::string& message) const;

  static std::string dotted(const std::string& prefix, std::string_view key) {
    return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
  }

  // Unknown keys are reported first, so that a typo is not also reported as a missing value.
  void check_keys(const toml::table& t, const std::string& prefix,
                  const std::vector<std::string>& allowed, const std::string& context = {}) const;
  const toml::table& require_table(const toml::node* n, const std::string& key) const;

  std::optional<double> opt_number(const toml::table& t, std::string_view k,
                                   const std::string& prefix) const;
  double number(const toml::table& t, std::string_view k, const std::string& prefix,
                std::optional<double> def, const toml::node* owner) const;
  double positive(const toml::table& t, std::string_view k, const std::string& prefix,
                  std::optional<double> def, const toml::node* owner) const;
  std::optional<std::string> opt_string(const toml::table& t, std::string_view k,
                                        const std::string& prefix) const;
  std::string string(const toml::table& t, std::string_view k, const std::string& prefix,
                     const toml::node* owner) const;
  std::optional<Vec3> opt_vec3(const toml::table& t, std::string_view k,
                               const std::string& prefix) const;
  bool boolean(const toml::table& t, std::string_view k, const std::string& prefix, bool def) const;
  class MaterialTable;
  std::optional<std::int64_t> opt_integer(const toml::table& t, std::string_view k,
                                          const std::string& prefix) const;

  // The tables of an array of tables, with their error-key prefixes ("bodies.ball" or
  // "bodies[2]" while the name is missing).
  std::vector<std::pair<const toml::table*, std::string>> entries(const toml::table& root,
                                                                  const std::string& key) const;
  std::string entry_name(const toml::table& t, const std::string& prefix,
                         std::set<std::string>& taken, const std::string& what,
                         std::optional<std::string> def = {}) const;

  void read_simulation(const toml::table& root, ModelSpec& spec, toml::table& out) const;
  void read_materials(const toml::table& root, ModelSpec& spec, toml::array& out) const;
  void read_bodies(const toml::table& root, ModelSpec& spec, toml::array& out,
                   std::set<std::string>& names) const;
  Tet10Mesh read_mesh(const toml::table& mesh, const std::string& prefix, toml::table& out) const;
  void read_walls(const toml::table& root, ModelSpec& spec, toml::array& out,
                  std::set<std::string>& names) const;
  void read_constraints(const toml::table& root, ModelSpec& spec, toml::array& out) const;
  RegionSpec read_region(const toml::table& c, const std::string& prefix, toml::table& out) const;
  void read_contact(const toml::table& root, ModelSpec& spec, toml::table& out) const;
  void read_compaction(const toml::table& root, ModelSpec& spec, toml::table& out,
                       std::set<std::string>& names) const;
  // [[packings]]: one body per particle of a packing file or generated packing.
  void read_packings(const toml::table& root, ModelSpec& spec, toml::array& out,
                     std::set<std::string>& names) const;
  PackingParams read_packing_params(const toml::table& g, const std::string& prefix,
                                    toml::table& out) const;

  std::string scene_path_;
  fs::path base_dir_;
  std::map<const toml::node*, std::string> override_nodes_;  // nodes created by --set

 public:
  // What happened while reading that the user should see in the log (CAD meshing, cache).
  mutable std::vector<std::string> notes_;
};

Reader::Location Reader::locate(const toml::node* node) const {
  if (!node) return {scene_path_, 0, 0, {}};
  return locate(node->source(), node);
}

Reader::Location Reader::locate(const toml::source_region& region,
                                const toml::node* fallback) const {
  if (region.path && *region.path != scene_path_)  // parsed from an override
    return {"", 0, 0, " (set by " + *region.path + ")"};
  if (region.path && region.begin)
    return {scene_path_,
            static_cast<int>(region.begin.line),
            static_cast<int>(region.begin.column),
            {}};
  if (fallback) {
    if (auto it = override_nodes_.find(fallback); it != override_nodes_.end())
      return {"", 0, 0, " (set by " + it->second + ")"};
    if (&fallback->source() != &region) return locate(fallback);
  }
  return {scene_path_, 0, 0, {}};
}

void Reader::fail(const toml::node* node, const std::string& key,
                  const std::string& message) const {
  fail_at(locate(node), key, message);
}

void Reader::fail_at(const Location& at, const std::string& key, const std::string& message) const {
  throw InputError(message + at.note, at.file, at.line, at.column, key);
}

void Reader::check_keys(const toml::table& t, const std::string& prefix,
                        const std::vector<std::string>& allowed, const std::string& context) const {
  for (const auto& [k, v] : t) {
    const std::string name(k.str());
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    std::string msg = "unknown key '" + name + "'";
    if (!context.empty()) msg += " " + context;
    msg += did_you_mean(name, allowed);
    if (allowed.empty())
      msg += "; no keys are allowed here";
    else
      msg += "; allowed: " + join(allowed);
    fail_at(locate(k.source(), &v), dotted(prefix, name), msg);
  }
}

const toml::table& Reader::require_table(const toml::node* n, const std::string& key) const {
  if (!n->is_table()) fail(n, key, "expected a table, got " + type_name(*n));
  return *n->as_table();
}

std::optional<double> Reader::opt_number(const toml::table& t, std::string_view k,
                                         const std::string& prefix) const {
  const toml::node* n = t.get(k);
  if (!n) return std::nullopt;
  double v = 0.0;
  if (auto i = n->as_integer())
    v = static_cast<double>(i->get());
  else if (auto f = n->as_floating_point())
    v = f->get();
  else
    fail(n, dotted(prefix, k), "expected a number, got " + type_name(*n));
  if (!std::isfinite(v)) fail(n, dotted(prefix, k), "must be a finite number");
  return v;
}

double Reader::number(const toml::table& t, std::string_view k, const std::string& prefix,
                      std::optional<double> def, const toml::node* owner) const {
  if (auto v = opt_number(t, k, prefix)) return *v;
  if (!def) fail(owner, dotted(prefix, k), "required value is missing");
  return *def;
}

double Reader::positive(const toml::table& t, std::string_view k, const std::string& prefix,
                        std::optional<double> def, const toml::node* owner) const {
  const double v = number(t, k, prefix, def, owner);
  if (t.get(k) && !(v > 0.0))
    fail(t.get(k), dotted(prefix, k), "must be positive, got " + format_number(v));
  return v;
}

std::optional<std::string> Reader::opt_string(const toml::table& t, std::string_view k,
                                              const std::string& prefix) const {
  const toml::node* n = t.get(k);
  if (!n) return std::nullopt;
  if (!n->is_string()) fail(n, dotted(prefix, k), "expected a string, got " + type_name(*n));
  return n->as_string()->get();
}

std::string Reader::string(const toml::table& t, std::string_view k, const std::string& prefix,
                           const toml::node* owner) const {
  auto s = opt_string(t, k, prefix);
  if (!s) fail(owner, dotted(prefix, k), "required value is missing");
  return *s;
}

std::optional<Vec3> Reader::opt_vec3(const toml::table& t, std::string_view k,
                                     const std::string& prefix) const {
  const toml::node* n = t.get(k);
  if (!n) return std::nullopt;
  const std::string key = dotted(prefix, k);
  const toml::array* a = n->as_array();
  if (!a) fail(n, key, "expected an array of 3 numbers [x, y, z], got " + type_name(*n));
  if (a->size() != 3)
    fail(n, key, "expected 3 numbers [x, y, z], got " + std::to_string(a->size()));
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const toml::node& e = *a->get(static_cast<std::size_t>(i));
    if (auto x = e.as_integer())
      v[i] = static_cast<double>(x->get());
    else if (auto f = e.as_floating_point())
      v[i] = f->get();
    else
      fail(
          &e, key,
          "expected 3 numbers [x, y, z], element " + std::to_string(i + 1) + " is " + type_name(e));
    if (!std::isfinite(v[i])) fail(&e, key, "must hold finite numbers");
  }
  return v;
}

bool Reader::boolean(const toml::table& t, std::string_view k, const std::string& prefix,
                     bool def) const {
  const toml::node* n = t.get(k);
  if (!n) return def;
  if (!n->is_boolean()) fail(n, dotted(prefix, k), "expected true or false, got " + type_name(*n));
  return n->as_boolean()->get();
}

std::optional<std::int64_t> Reader::opt_integer(const toml::table& t, std::string_view k,
                                                const std::string& prefix) const {
  const toml::node* n = t.get(k);
  if (!n) return std::nullopt;
  if (!n->is_integer()) fail(n, dotted(prefix, k), "expected an integer, got " + type_name(*n));
  return n->as_integer()->get();
}

std::vector<std::pair<const toml::table*, std::string>> Reader::entries(
    const toml::table& root, const std::string& key) const {
  std::vector<std::pair<const toml::table*, std::string>> out;
  const toml::node* n = root.get(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a)
    fail(n, key,
         "expected an array of tables (write each entry as [[" + key + "]]), got " + type_name(*n));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    std::string prefix = key + "[" + std::to_string(i) + "]";
    if (!e.is_table())
      fail(&e, prefix,
           "expected a table (write each entry as [[" + key + "]]), got " + type_name(e));
    const toml::table& t = *e.as_table();
    if (const toml::node* nm = t.get("name");
        nm && nm->is_string() && !nm->as_string()->get().empty())
      prefix = key + "." + nm->as_string()->get();
    out.emplace_back(&t, prefix);
  }
  return out;
}

std::string Reader::entry_name(const toml::table& t, const std::string& prefix,
                               std::set<std::string>& taken, const std::string& what,
                               std::optional<std::string> def) const {
  std::string name;
  if (auto s = opt_string(t, "name", prefix))
    name = *s;
  else if (def)
    name = *def;
  else
    fail(&t, dotted(prefix, "name"), "required value is missing (every " + what + " needs a name)");
  const toml::node* n = t.get("name");
  if (name.empty()) fail(n, dotted(prefix, "name"), "must not be empty");
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      fail(n ? n : &t, dotted(prefix, "name"),
           "'" + name + "': names may contain only letters, digits, '_' and '-'");
  if (!taken.insert(name).second)
    fail(n ? n : &t, dotted(prefix, "name"),
         "duplicate name '" + name + "' (" +
             (what == "body" || what == "wall"
                  ? std::string("bodies and walls share one set of names")
                  : "names of " + what + "s must be unique") +
             ")");
  return name;
}

// ---------------------------------------------------------------------------------------------
// Overrides

void Reader::apply_override(toml::table& root, const std::string& text) {
  const std::string origin = "--set " + text;
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError("expected KEY=VALUE, e.g. simulation.end_time=1e-3 (in " + origin + ")", {}, 0,
                     0, trim(text));
  const std::string key = trim(std::string_view(text).substr(0, eq));
  const std::string value_text = trim(std::string_view(text).substr(eq + 1));
  std::vector<std::string> parts;
  {
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = key.find('.', start);
      parts.push_back(trim(std::string_view(key).substr(start, dot - start)));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
  }
  for (const auto& p : parts)
    if (p.empty()) throw InputError("malformed key (empty part) in " + origin, {}, 0, 0, key);

  // The value: TOML if it parses as one, else a bare string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value_text, origin);
  } catch (const toml::parse_error&) {
    parsed = toml::parse("v = " + toml_string_literal(value_text), origin);
  }
  if (parsed.size() != 1 || !parsed.get("v"))
    parsed = toml::parse("v = " + toml_string_literal(value_text), origin);
  toml::node& value = *parsed.get("v");

  toml::table* table = &root;
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& part = parts[i];
    walked = walked.empty() ? part : walked + "." + part;
    toml::node* child = table->get(part);
    if (!child) {
      auto [it, inserted] = table->insert(part, toml::table{});
      (void)inserted;
      override_nodes_[&it->second] = origin;
      table = it->second.as_table();
      continue;
    }
    if (toml::table* t = child->as_table()) {
      table = t;
      continue;
    }
    if (toml::array* a = child->as_array(); a && a->is_array_of_tables()) {
      // The next part names an entry.
      const std::string& name = parts[++i];
      std::vector<std::string> names;
      toml::table* found = nullptr;
      for (auto& e : *a) {
        toml::table& t = *e.as_table();
        if (const toml::node* nm = t.get("name"); nm && nm->is_string()) {
          names.push_back(nm->as_string()->get());
          if (names.back() == name) found = &t;
        }
      }
      if (!found)
        throw InputError(
            "no entry of '" + walked + "' is named '" + name + "'" + did_you_mean(name, names) +
                (names.empty() ? "" : "; names: " + join(names)) + " (in " + origin + ")",
            {}, 0, 0, key);
      walked += "." + name;
      if (i + 1 == parts.size())
        throw InputError("cannot replace a whole entry; set its keys one by one, e.g. " + walked +
                             ".KEY=VALUE (in " + origin + ")",
                         {}, 0, 0, key);
      table = found;
      continue;
    }
    throw InputError("'" + walked + "' is " + type_name(*child) +
                         ", not a table or a named array of tables (in " + origin + ")",
                     {}, 0, 0, key);
  }
  // Move the value in: moving keeps its source region (path = the override text).
  value.visit([&](auto&& v) { table->insert_or_assign(parts.back(), std::move(v)); });
  override_nodes_[table->get(parts.back())] = origin;
}

// ---------------------------------------------------------------------------------------------
// Sections

void Reader::read_simulation(const toml::table& root, ModelSpec& spec, toml::table& out) const {
  const toml::node* n = root.get("simulation");
  if (!n) fail(&root, "simulation", "required table [simulation] is missing (it needs end_time)");
  const toml::table& t = require_table(n, "simulation");
  const std::string p = "simulation";
  check_keys(t, p,
             {"end_time", "time_step_safety", "time_step", "output_interval", "history_interval",
              "gravity", "threads", "bulk_viscosity_linear", "bulk_viscosity_quadratic",
              "mass_scaling_time_step", "mass_scaling_limit", "deformation_damping",
              "rest_kinetic_fraction", "rest_hold_time"});
  SimulationSettings& s = spec.simulation;
  s.end_time = positive(t, "end_time", p, std::nullopt, &t);
  s.time_step_safety = positive(t, "time_step_safety", p, s.time_step_safety, &t);
  if (s.time_step_safety > 1.0)
    fail(t.get("time_step_safety"), "simulation.time_step_safety",
         "must be in (0, 1] (a fraction of the stable time step), got " +
             format_number(s.time_step_safety));
  s.time_step = positive(t, "time_step", p, 0.0, &t);
  s.output_interval = positive(t, "output_interval", p, s.end_time / 50.0, &t);
  s.history_interval = positive(t, "history_interval", p, s.output_interval / 20.0, &t);
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
  out.insert_or_assign("time_step_safety", s.time_step_safety);
  if (s.time_step > 0.0) out.insert_or_assign("time_step", s.time_step);
  out.insert_or_assign("output_interval", s.output_interval);
  out.insert_or_assign("history_interval", s.history_interval);
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

// A [[materials]] entry as the model readers see it (materials/material_keys.hpp): the
// Reader's checks and messages, the values recorded into the entry's resolved table.
class Reader::MaterialTable final : public MaterialKeys {
 public:
  MaterialTable(const Reader& r, const toml::table& t, const std::string& prefix, toml::table& out)
      : r_(r), t_(t), p_(prefix), out_(out) {}
  bool has(std::string_view key) const override { return t_.contains(key); }
  double number(std::string_view key, std::optional<double> fallback) override {
    return r_.number(t_, key, p_, fallback, &t_);
  }
  double positive(std::string_view key, std::optional<double> fallback) override {
    return r_.positive(t_, key, p_, fallback, &t_);
  }
  std::optional<std::string> text(std::string_view key) override {
    return r_.opt_string(t_, key, p_);
  }
  std::vector<std::pair<double, double>> pairs(std::string_view key, const std::string& what_array,
                                               const std::string& what_pair) override {
    const toml::node* n = t_.get(key);
    const toml::array* arr = n ? n->as_array() : nullptr;
    if (!arr || arr->empty()) fail(key, what_array);
    std::vector<std::pair<double, double>> out;
    for (const toml::node& pt : *arr) {
      const toml::array* pair = pt.as_array();
      if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number())
        r_.fail(&pt, dotted(p_, key), what_pair);
      out.emplace_back((*pair)[0].value<double>().value(), (*pair)[1].value<double>().value());
    }
    return out;
  }
  void record(std::string_view key, double value) override { out_.insert_or_assign(key, value); }
  void record(std::string_view key, const std::string& value) override {
    out_.insert_or_assign(key, value);
  }
  void record(std::string_view key, const std::vector<std::pair<double, double>>& v) override {
    toml::array a;
    for (const auto& [x, y] : v) a.push_back(toml::array{x, y});
    out_.insert_or_assign(key, std::move(a));
  }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const override {
    const toml::node* n = t_.get(key);
    r_.fail(n ? n : &t_, dotted(p_, key), message);
  }
  [[noreturn]] void fail_entry(const std::string& message) const override {
    r_.fail(&t_, p_, message);
  }
  std::string did_you_mean(std::string_view word,
                           const std::vector<std::string>& candidates) const override {
    return femdem::did_you_mean(word, candidates);
  }

 private:
  const Reader& r_;
  const toml::table& t_;
  const std::string& p_;
  toml::table& out_;
};

// The model comes first (it decides which keys are allowed), then the common constants, then
// the model's own keys, read by the model (materials/material_registry.hpp).
void Reader::read_materials(const toml::table& root, ModelSpec& spec, toml::array& out) const {
  const std::vector<std::string> models = material_model_names();
  std::set<std::string> names;
  for (const auto& [tp, p] : entries(root, "materials")) {
    const toml::table& t = *tp;
    const std::string model = string(t, "model", p, &t);
    const int index = material_model_index(model);
    if (index < 0)
      fail(t.get("model"), dotted(p, "model"),
           "unknown material model '" + model + "'" + did_you_mean(model, models) +
               "; available: " + join(models));
    std::vector<std::string> keys = {"name", "model", "density", "youngs_modulus", "poisson_ratio"};
    with_material_model(static_cast<std::size_t>(index), [&](auto m) {
      for (std::string& k : decltype(m)::keys()) keys.push_back(std::move(k));
    });
    check_keys(t, p, keys, "for model '" + model + "'");
    MaterialParams m;
    m.name = entry_name(t, p, names, "material");
    m.density = positive(t, "density", p, std::nullopt, &t);
    m.youngs_modulus = positive(t, "youngs_modulus", p, std::nullopt, &t);
    m.poisson_ratio = number(t, "poisson_ratio", p, std::nullopt, &t);
    if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
      fail(t.get("poisson_ratio"), dotted(p, "poisson_ratio"),
           "must lie in (-1, 0.5), got " + format_number(m.poisson_ratio));
    toml::table o;
    o.insert_or_assign("name", m.name);
    o.insert_or_assign("model", model);
    o.insert_or_assign("density", m.density);
    o.insert_or_assign("youngs_modulus", m.youngs_modulus);
    o.insert_or_assign("poisson_ratio", m.poisson_ratio);
    MaterialTable keys_of_model(*this, t, p, o);
    with_material_model(static_cast<std::size_t>(index), [&](auto model_type) {
      using Model = decltype(model_type);
      m.model = Model::read(m, keys_of_model);
    });
    spec.materials.push_back(m);
    out.push_back(std::move(o));
  }
}

Tet10Mesh Reader::read_mesh(const toml::table& mesh, const std::string& bp,
                            toml::table& out) const {
  const std::string p = dotted(bp, "mesh");
  const bool has_gen = mesh.contains("generator"), has_file = mesh.contains("file");
  if (has_gen && has_file) fail(&mesh, p, "give either 'generator' or 'file', not both");
  if (!has_gen && !has_file)
    fail(&mesh, p,
         "needs 'generator' (\"box\", \"cylinder\", \"sphere\") or 'file' (a gmsh .msh file or a "
         "CAD surface)");

  if (has_gen) {
    const std::string gen = string(mesh, "generator", p, &mesh);
    const toml::node* gn = mesh.get("generator");
    std::vector<std::string> allowed = {"generator",   "element_size",  "refine_point",
                                        "refine_size", "refine_radius", "refine_growth"};
    if (gen == "box")
      allowed.push_back("size");
    else if (gen == "cylinder")
      allowed.insert(allowed.end(), {"radius", "length"});
    else if (gen == "sphere")
      allowed.push_back("radius");
    else
      fail(gn, dotted(p, "generator"),
           "unknown mesh generator '" + gen + "'" + did_you_mean(gen, kGenerators) +
               "; available: " + join(kGenerators));
    check_keys(mesh, p, allowed, "for generator '" + gen + "'");
    const double h = positive(mesh, "element_size", p, std::nullopt, &mesh);
    out.insert_or_assign("generator", gen);
    out.insert_or_assign("element_size", h);
    Vec3 size = Vec3::Zero();
    double radius = 0.0, length = 0.0;
    if (gen == "box") {
      auto s = opt_vec3(mesh, "size", p);
      if (!s) fail(&mesh, dotted(p, "size"), "required value is missing ([lx, ly, lz] in m)");
      if (!(s->minCoeff() > 0.0))
        fail(mesh.get("size"), dotted(p, "size"), "all three lengths must be positive");
      size = *s;
      out.insert_or_assign("size", toml::array{size.x(), size.y(), size.z()});
    } else {
      radius = positive(mesh, "radius", p, std::nullopt, &mesh);
      out.insert_or_assign("radius", radius);
      if (gen == "cylinder") {
        length = positive(mesh, "length", p, std::nullopt, &mesh);
        out.insert_or_assign("length", length);
      }
    }
    // Local refinement near a point (all three generators).
    std::optional<MeshRefinement> refine;
    if (mesh.contains("refine_point") || mesh.contains("refine_size") ||
        mesh.contains("refine_radius") || mesh.contains("refine_growth")) {
      MeshRefinement r;
      const auto point = opt_vec3(mesh, "refine_point", p);
      if (!point)
        fail(&mesh, dotted(p, "refine_point"),
             "required value is missing when refining ([x, y, z] in m, in the mesh's own frame)");
      r.point = *point;
      r.size = positive(mesh, "refine_size", p, std::nullopt, &mesh);
      if (r.size > h)
        fail(mesh.get("refine_size"), dotted(p, "refine_size"),
             "must not be larger than element_size (" + format_number(h) + ")");
      r.radius = number(mesh, "refine_radius", p, 0.0, &mesh);
      if (!(r.radius >= 0.0))
        fail(mesh.get("refine_radius"), dotted(p, "refine_radius"),
             "must be >= 0, got " + format_number(r.radius));
      r.growth = positive(mesh, "refine_growth", p, kDefaultRefineGrowth, &mesh);
      if (!(r.growth <= 2.0))
        fail(mesh.get("refine_growth"), dotted(p, "refine_growth"),
             "must be in (0, 2], got " + format_number(r.growth));
      out.insert_or_assign("refine_point", toml::array{r.point.x(), r.point.y(), r.point.z()});
      out.insert_or_assign("refine_size", r.size);
      out.insert_or_assign("refine_radius", r.radius);
      out.insert_or_assign("refine_growth", r.growth);
      refine = r;
    }
    try {
      if (refine) {
        // Checked (and its element count estimated) inside the generators.
        if (gen == "box") return generate_box(size, h, refine);
        if (gen == "cylinder") return generate_cylinder(radius, length, h, refine);
        return generate_sphere(radius, h, refine);
      }
      // Counted first, so that a typo in element_size fails fast instead of exhausting memory.
      if (gen == "box") {
        box_element_count(size, h);
        return generate_box(size, h);
      }
      if (gen == "cylinder") {
        cylinder_element_count(radius, length, h);
        return generate_cylinder(radius, length, h);
      }
      sphere_element_count(radius, h);
      return generate_sphere(radius, h);
    } catch (const InputError& e) {
      const std::string what = e.what();
      // Errors about the refinement name its key (refine_point, refine_size, ...).
      std::string key = "element_size";
      for (const char* k : {"refine_point", "refine_size", "refine_radius", "refine_growth"})
        if (refine && what.find(k) != std::string::npos) {
          key = k;
          break;
        }
      fail(mesh.get(key), dotted(p, key), "cannot generate the mesh: " + what);
    } catch (const std::exception& e) {
      fail(&mesh, p, "cannot generate the mesh: " + std::string(e.what()));
    }
  }

  // A mesh file.
  const std::string file = string(mesh, "file", p, &mesh);
  const toml::node* fn = mesh.get("file");
  const std::string fkey = dotted(p, "file");
  if (file.empty()) fail(fn, fkey, "must not be empty");
  const fs::path full = fs::path(file).is_absolute() ? fs::path(file) : base_dir_ / file;
  const std::string ext = lower(fs::path(file).extension().string());
  const bool is_cad = ext != ".msh" && cad_format_supported(ext);
  if (ext == ".msh")
    check_keys(mesh, p, {"file"}, "for a gmsh .msh file (it is used as meshed)");
  else if (is_cad)
    check_keys(mesh, p, {"file", "element_size", "scale"}, "for a CAD surface file");
  else
    fail(fn, fkey,
         "unsupported mesh file type '" + (ext.empty() ? std::string("(none)") : ext) +
             "': use a second-order tetrahedral gmsh volume mesh (.msh) or a closed surface in "
             "a format assimp reads (" +
             cad_extensions() + ")");
  std::error_code ec;
  if (!fs::exists(full, ec))
    fail(fn, fkey,
         "mesh file '" + full.string() + "' does not exist (relative paths are " +
             "resolved against the scene's folder)");
  if (!fs::is_regular_file(full, ec)) fail(fn, fkey, "'" + full.string() + "' is not a file");
  if (!std::ifstream(full).good()) fail(fn, fkey, "cannot read mesh file '" + full.string() + "'");
  out.insert_or_assign("file", file);
  if (is_cad) {
    CadMeshOptions options;
    options.element_size = positive(mesh, "element_size", p, std::nullopt, &mesh);
    options.scale = positive(mesh, "scale", p, 1.0, &mesh);
    out.insert_or_assign("element_size", options.element_size);
    out.insert_or_assign("scale", options.scale);
    CachedCadMesh cm;
    try {
      cm = mesh_cad_file_cached(full.string(), options);
    } catch (const InputError& e) {
      // Size problems belong to element_size; everything else to the file.
      const bool size = std::string(e.what()).find("element_size") != std::string::npos;
      const char* key = size ? "element_size" : "file";
      fail(size ? mesh.get(key) : fn, dotted(p, key), "cannot mesh the surface: " + e.describe());
    } catch (const std::exception& e) {
      fail(fn, fkey, "cannot mesh the surface '" + full.string() + "': " + e.what());
    }
    notes_.push_back(dotted(p, "file") + ": " + cm.note);
    return std::move(cm.mesh);
  }
  Tet10Mesh m;
  try {
    m = read_gmsh(full.string());
  } catch (const InputError& e) {
    fail(fn, fkey, "bad mesh: " + e.describe());
  } catch (const std::exception& e) {
    fail(fn, fkey, "cannot read mesh '" + full.string() + "': " + e.what());
  }
  // The reader checks this too; repeated here so that any mesh source is held to it.
  const MeshQuality q = mesh_quality(m);
  if (q.bad_elements > 0)
    fail(fn, fkey,
         "mesh '" + file + "' has " + std::to_string(q.bad_elements) +
             " inverted or degenerate element(s), the first is element " +
             std::to_string(q.first_bad_element + 1) + " (1-based, in file order)");
  return m;
}

void Reader::read_bodies(const toml::table& root, ModelSpec& spec, toml::array& out,
                         std::set<std::string>& names) const {
  const auto list = entries(root, "bodies");
  if (list.empty() && !root.contains("packings"))
    fail(root.get("bodies") ? root.get("bodies") : &root, "bodies",
         "the scene has no bodies: add at least one [[bodies]] or [[packings]] entry");
  for (const auto& [tp, p] : list) {
    const toml::table& t = *tp;
    check_keys(t, p,
               {"name", "material", "mesh", "position", "rotation", "velocity", "angular_velocity",
                "fixed", "fbar"});
    BodySpec b;
    b.name = entry_name(t, p, names, "body");
    const std::string mat = string(t, "material", p, &t);
    std::vector<std::string> mat_names;
    for (std::size_t i = 0; i < spec.materials.size(); ++i) {
      mat_names.push_back(spec.materials[i].name);
      if (spec.materials[i].name == mat) b.material = static_cast<int>(i);
    }
    if (b.material < 0)
      fail(t.get("material"), dotted(p, "material"),
           "unknown material '" + mat + "'" + did_you_mean(mat, mat_names) +
               (mat_names.empty() ? "; the scene defines no [[materials]]"
                                  : "; materials: " + join(mat_names)));
    const Vec3 position = opt_vec3(t, "position", p).value_or(Vec3::Zero());
    const Vec3 rotation = opt_vec3(t, "rotation", p).value_or(Vec3::Zero());
    b.velocity = opt_vec3(t, "velocity", p).value_or(Vec3::Zero());
    b.angular_velocity = opt_vec3(t, "angular_velocity", p).value_or(Vec3::Zero());
    b.fixed = boolean(t, "fixed", p, false);
    if (const toml::node* fb = t.get("fbar")) {
      if (auto flag = fb->value<bool>()) {
        b.fbar = *flag ? FbarMode::VolumeAverage : FbarMode::Off;
      } else {
        const std::string v = string(t, "fbar", p, &t);
        b.fbar = parse_fbar_mode(v);
        if (!b.fbar)
          fail(fb, dotted(p, "fbar"),
               "must be true, false, \"volume_average\", \"centroid\" or \"off\", got '" + v + "'");
      }
    }

    const toml::node* mn = t.get("mesh");
    if (!mn) fail(&t, dotted(p, "mesh"), "required value is missing");
    toml::table mesh_out;
    b.mesh = read_mesh(require_table(mn, dotted(p, "mesh")), p, mesh_out);
    if (b.mesh.elements.empty() || b.mesh.nodes.empty())
      fail(mn, dotted(p, "mesh"), "the mesh has no elements");
    place_mesh(b.mesh, rotation, position);

    toml::table o;
    o.insert_or_assign("name", b.name);
    o.insert_or_assign("material", mat);
    o.insert_or_assign("mesh", std::move(mesh_out));
    o.insert_or_assign("position", toml::array{position.x(), position.y(), position.z()});
    o.insert_or_assign("rotation", toml::array{rotation.x(), rotation.y(), rotation.z()});
    o.insert_or_assign("velocity", toml::array{b.velocity.x(), b.velocity.y(), b.velocity.z()});
    o.insert_or_assign(
        "angular_velocity",
        toml::array{b.angular_velocity.x(), b.angular_velocity.y(), b.angular_velocity.z()});
    o.insert_or_assign("fixed", b.fixed);
    o.insert_or_assign("fbar",
                       to_string(b.fbar.value_or(default_fbar_mode(spec.materials[b.material]))));
    out.push_back(std::move(o));
    spec.bodies.push_back(std::move(b));
  }
}

void Reader::read_walls(const toml::table& root, ModelSpec& spec, toml::array& out,
                        std::set<std::string>& names) const {
  int index = 0;
  for (const auto& [tp, p] : entries(root, "walls")) {
    const toml::table& t = *tp;
    ++index;
    check_keys(t, p,
               {"name", "point", "normal", "velocity", "velocity_history", "friction",
                "penalty_factor", "damping", "force_history", "mass"});
    WallSpec w;
    w.name = entry_name(t, p, names, "wall", "wall" + std::to_string(index));
    w.point = opt_vec3(t, "point", p).value_or(Vec3::Zero());
    if (auto n = opt_vec3(t, "normal", p)) {
      if (!(n->norm() > 0.0))
        fail(t.get("normal"), dotted(p, "normal"), "must not be the zero vector");
      w.normal = n->normalized();
    }
    w.velocity = opt_vec3(t, "velocity", p).value_or(Vec3::Zero());
    if (const toml::node* hn = t.get("velocity_history")) {
      const std::string hk = dotted(p, "velocity_history");
      if (t.contains("velocity"))
        fail(hn, hk,
             "give either 'velocity' (constant) or 'velocity_history' (piecewise linear), not "
             "both");
      const toml::array* rows = hn->as_array();
      if (!rows || rows->empty())
        fail(hn, hk,
             "expected a non-empty array of rows [t, vx, vy, vz], e.g. [[0, 0, 0, 0], [1e-3, 0, "
             "0, -0.1]], got " +
                 (rows ? std::string("an empty array") : type_name(*hn)));
      for (std::size_t i = 0; i < rows->size(); ++i) {
        const toml::node& rn = *rows->get(i);
        const std::string row = "row " + std::to_string(i + 1);
        const toml::array* r = rn.as_array();
        if (!r || r->size() != 4)
          fail(&rn, hk,
               row + " must be [t, vx, vy, vz] (4 numbers), got " +
                   (r ? std::to_string(r->size()) + " numbers" : type_name(rn)));
        double v[4];
        for (std::size_t j = 0; j < 4; ++j) {
          const toml::node& e = *r->get(j);
          if (!e.is_number())
            fail(&e, hk,
                 row + " must be [t, vx, vy, vz] (4 numbers), element " + std::to_string(j + 1) +
                     " is " + type_name(e));
          v[j] = e.value<double>().value();
          if (!std::isfinite(v[j])) fail(&e, hk, row + " must hold finite numbers");
        }
        if (i == 0 && v[0] != 0.0)
          fail(&rn, hk, "the first row must be at t = 0, got t = " + format_number(v[0]));
        if (i > 0 && !(v[0] > w.velocity_history.back().time))
          fail(&rn, hk,
               "times must increase strictly: " + row + " has t = " + format_number(v[0]) +
                   " after t = " + format_number(w.velocity_history.back().time));
        w.velocity_history.push_back({v[0], Vec3(v[1], v[2], v[3])});
      }
    }
    if (const toml::node* fn = t.get("force_history")) {
      const std::string fk = dotted(p, "force_history");
      if (t.contains("velocity_history"))
        fail(fn, fk,
             "give either 'velocity_history' (prescribed motion) or 'force_history' (prescribed "
             "load), not both");
      const toml::array* rows = fn->as_array();
      if (!rows || rows->empty())
        fail(fn, fk,
             "expected a non-empty array of rows [t, F] (F in N along the normal, towards the "
             "bodies), e.g. [[0, 0], [1e-3, 500]], got " +
                 (rows ? std::string("an empty array") : type_name(*fn)));
      for (std::size_t i = 0; i < rows->size(); ++i) {
        const toml::node& rn = *rows->get(i);
        const std::string row = "row " + std::to_string(i + 1);
        const toml::array* r = rn.as_array();
        if (!r || r->size() != 2 || !(*r)[0].is_number() || !(*r)[1].is_number())
          fail(&rn, fk, row + " must be [t, F] (2 numbers)");
        const double tt = (*r)[0].value<double>().value(), f = (*r)[1].value<double>().value();
        if (!std::isfinite(tt) || !std::isfinite(f))
          fail(&rn, fk, row + " must hold finite numbers");
        if (i == 0 && tt != 0.0)
          fail(&rn, fk, "the first row must be at t = 0, got t = " + format_number(tt));
        if (i > 0 && !(tt > w.force_history.back().time))
          fail(&rn, fk,
               "times must increase strictly: " + row + " has t = " + format_number(tt) +
                   " after t = " + format_number(w.force_history.back().time));
        w.force_history.push_back({tt, f});
      }
      w.mass = number(t, "mass", p, std::nullopt, &t);
      if (!(w.mass > 0.0))
        fail(t.get("mass"), dotted(p, "mass"),
             "must be positive (the punch's mass, kg), got " + format_number(w.mass));
    } else if (t.contains("mass")) {
      fail(t.get("mass"), dotted(p, "mass"),
           "only a force-driven wall has a mass: give 'force_history' too, or remove 'mass'");
    }
    w.friction = number(t, "friction", p, 0.0, &t);
    if (w.friction < 0.0)
      fail(t.get("friction"), dotted(p, "friction"),
           "must not be negative, got " + format_number(w.friction));
    w.penalty_factor = positive(t, "penalty_factor", p, 0.0, &t);
    toml::table o;
    o.insert_or_assign("name", w.name);
    o.insert_or_assign("point", toml::array{w.point.x(), w.point.y(), w.point.z()});
    o.insert_or_assign("normal", toml::array{w.normal.x(), w.normal.y(), w.normal.z()});
    if (w.velocity_history.empty()) {
      o.insert_or_assign("velocity", toml::array{w.velocity.x(), w.velocity.y(), w.velocity.z()});
    } else {
      toml::array rows;
      for (const VelocityPoint& q : w.velocity_history)
        rows.push_back(toml::array{q.time, q.velocity.x(), q.velocity.y(), q.velocity.z()});
      o.insert_or_assign("velocity_history", std::move(rows));
    }
    o.insert_or_assign("friction", w.friction);
    if (w.penalty_factor > 0.0) o.insert_or_assign("penalty_factor", w.penalty_factor);
    w.damping = number(t, "damping", p, 0.0, &t);
    if (w.damping < 0.0 || w.damping > 1.0)
      fail(t.get("damping"), dotted(p, "damping"),
           "must be a fraction of critical damping in [0, 1], got " + format_number(w.damping));
    o.insert_or_assign("damping", w.damping);
    if (!w.force_history.empty()) {
      toml::array rows;
      for (const ForcePoint& q : w.force_history) rows.push_back(toml::array{q.time, q.force});
      o.insert_or_assign("force_history", std::move(rows));
      o.insert_or_assign("mass", w.mass);
    }
    out.push_back(std::move(o));
    spec.walls.push_back(w);
  }
}

RegionSpec Reader::read_region(const toml::table& c, const std::string& cp,
                               toml::table& out) const {
  RegionSpec r;
  const std::string p = dotted(cp, "region");
  const toml::node* n = c.get("region");
  if (!n || (n->is_string() && n->as_string()->get() == "all")) {
    r.kind = RegionSpec::Kind::All;
    out.insert_or_assign("region", "all");
    return r;
  }
  if (n->is_string())
    fail(n, p,
         "unknown region '" + n->as_string()->get() +
             "': use \"all\", { box_min = [...], box_max = [...] } or { plane_point = [...], "
             "plane_normal = [...] }");
  if (!n->is_table())
    fail(n, p,
         "expected \"all\" or a table (box_min/box_max or plane_point/plane_normal), got " +
             type_name(*n));
  const toml::table& t = *n->as_table();
  const bool box = t.contains("box_min") || t.contains("box_max");
  const bool plane = t.contains("plane_point") || t.contains("plane_normal");
  if (box && plane) fail(n, p, "mixes a box (box_min/box_max) and a plane (plane_point/...)");
  if (!box && !plane) {
    check_keys(t, p, {"box_min", "box_max", "plane_point", "plane_normal", "tolerance"});
    fail(n, p, "needs box_min and box_max, or plane_point and plane_normal");
  }
  toml::table o;
  if (box) {
    check_keys(t, p, {"box_min", "box_max"}, "for a box region");
    auto lo = opt_vec3(t, "box_min", p), hi = opt_vec3(t, "box_max", p);
    if (!lo) fail(n, dotted(p, "box_min"), "required value is missing (box_max is given)");
    if (!hi) fail(n, dotted(p, "box_max"), "required value is missing (box_min is given)");
    for (int i = 0; i < 3; ++i)
      if ((*lo)[i] > (*hi)[i])
        fail(t.get("box_max"), dotted(p, "box_max"),
             std::string("is below box_min in ") + "xyz"[i]);
    r.kind = RegionSpec::Kind::Box;
    r.box_min = *lo;
    r.box_max = *hi;
    o.insert_or_assign("box_min", toml::array{lo->x(), lo->y(), lo->z()});
    o.insert_or_assign("box_max", toml::array{hi->x(), hi->y(), hi->z()});
  } else {
    check_keys(t, p, {"plane_point", "plane_normal", "tolerance"}, "for a plane region");
    auto pt = opt_vec3(t, "plane_point", p), nr = opt_vec3(t, "plane_normal", p);
    if (!pt) fail(n, dotted(p, "plane_point"), "required value is missing");
    if (!nr) fail(n, dotted(p, "plane_normal"), "required value is missing");
    if (!(nr->norm() > 0.0))
      fail(t.get("plane_normal"), dotted(p, "plane_normal"), "must not be the zero vector");
    r.kind = RegionSpec::Kind::Plane;
    r.plane_point = *pt;
    r.plane_normal = nr->normalized();
    r.tolerance = positive(t, "tolerance", p, 0.0, n);
    o.insert_or_assign("plane_point", toml::array{pt->x(), pt->y(), pt->z()});
    o.insert_or_assign("plane_normal",
                       toml::array{r.plane_normal.x(), r.plane_normal.y(), r.plane_normal.z()});
    if (r.tolerance > 0.0) o.insert_or_assign("tolerance", r.tolerance);
  }
  out.insert_or_assign("region", std::move(o));
  return r;
}

void Reader::read_constraints(const toml::table& root, ModelSpec& spec, toml::array& out) const {
  std::vector<std::string> body_names;
  for (const auto& b : spec.bodies) body_names.push_back(b.name);
  std::set<std::string> names;
  int index = 0;
  for (const auto& [tp, p] : entries(root, "constraints")) {
    const toml::table& t = *tp;
    ++index;
    check_keys(t, p, {"name", "body", "region", "fix", "velocity"});
    if (t.contains("name"))
      entry_name(t, p, names, "constraint", "constraint" + std::to_string(index));
    ConstraintSpec c;
    const std::string body = string(t, "body", p, &t);
    for (std::size_t i = 0; i < spec.bodies.size(); ++i)
      if (spec.bodies[i].name == body) c.body = static_cast<int>(i);
    if (c.body < 0)
      fail(t.get("body"), dotted(p, "body"),
           "unknown body '" + body + "'" + did_you_mean(body, body_names) +
               "; bodies: " + join(body_names));
    toml::table o;
    if (t.contains("name")) o.insert_or_assign("name", t.get("name")->as_string()->get());
    o.insert_or_assign("body", body);
    c.region = read_region(t, p, o);
    bool any_fix = false;
    if (const toml::node* f = t.get("fix")) {
      const std::string fk = dotted(p, "fix");
      const toml::array* a = f->as_array();
      if (!a) fail(f, fk, "expected an array of components, e.g. [\"x\", \"z\"]");
      toml::array fo;
      for (const auto& e : *a) {
        const std::string comp = e.is_string() ? e.as_string()->get() : std::string();
        const int axis = comp == "x" ? 0 : comp == "y" ? 1 : comp == "z" ? 2 : -1;
        if (axis < 0)
          fail(&e, fk,
               (e.is_string() ? "unknown component '" + comp + "'"
                              : "expected a component name, got " + type_name(e)) +
                   ": use any of \"x\", \"y\", \"z\"");
        if (!c.fix[axis]) fo.push_back(comp);
        c.fix[axis] = true;
        any_fix = true;
      }
      o.insert_or_assign("fix", std::move(fo));
    }
    c.velocity = opt_vec3(t, "velocity", p);
    if (!any_fix && !c.velocity)
      fail(t.contains("fix") ? t.get("fix") : &t, p,
           "does nothing: give 'fix' (a non-empty list of \"x\", \"y\", \"z\") or 'velocity'");
    if (any_fix && c.velocity)
      fail(t.get("velocity"), dotted(p, "velocity"),
           "give either 'fix' or 'velocity', not both (velocity prescribes all three "
           "components; use velocity = [0, 0, v] to hold x and y)");
    if (c.velocity)
      o.insert_or_assign("velocity",
                         toml::array{c.velocity->x(), c.velocity->y(), c.velocity->z()});
    out.push_back(std::move(o));
    spec.constraints.push_back(c);
  }
}

void Reader::read_contact(const toml::table& root, ModelSpec& spec, toml::table& out) const {
  ContactSettings& c = spec.contact;
  if (const toml::node* n = root.get("contact")) {
    const toml::table& t = require_table(n, "contact");
    check_keys(t, "contact", {"penalty_factor", "friction", "impact_damping", "pairs"});
    c.penalty_factor = positive(t, "penalty_factor", "contact", c.penalty_factor, &t);
    c.friction = number(t, "friction", "contact", c.friction, &t);
    if (c.friction < 0.0)
      fail(t.get("friction"), "contact.friction",
           "must not be negative, got " + format_number(c.friction));
    c.impact_damping = number(t, "impact_damping", "contact", c.impact_damping, &t);
    if (!(c.impact_damping >= 0.0 && c.impact_damping < 1.0))
      fail(t.get("impact_damping"), "contact.impact_damping",
           "must be a fraction of critical damping in [0, 1), got " +
               format_number(c.impact_damping));
    std::vector<std::string> body_names;
    for (const auto& b : spec.bodies) body_names.push_back(b.name);
    toml::array pairs_out;
    for (const auto& [pt, short_prefix] : entries(t, "pairs")) {
      const toml::table& pair = *pt;
      const std::string p = "contact." + short_prefix;
      check_keys(pair, p, {"bodies", "friction"});
      const toml::node* bn = pair.get("bodies");
      if (!bn) fail(&pair, dotted(p, "bodies"), "required value is missing (two body names)");
      const toml::array* ba = bn->as_array();
      if (!ba || ba->size() != 2 || !(*ba)[0].is_string() || !(*ba)[1].is_string())
        fail(bn, dotted(p, "bodies"), "expected two body names, e.g. [\"ball\", \"plate\"]");
      ContactPairSpec cp;
      int* ids[2] = {&cp.body_a, &cp.body_b};
      for (int k = 0; k < 2; ++k) {
        const std::string name = (*ba)[k].as_string()->get();
        for (std::size_t i = 0; i < spec.bodies.size(); ++i)
          if (spec.bodies[i].name == name) *ids[k] = static_cast<int>(i);
        if (*ids[k] < 0)
          fail(bn, dotted(p, "bodies"),
               "unknown body '" + name + "'" + did_you_mean(name, body_names) +
                   "; bodies: " + join(body_names));
      }
      if (cp.body_a == cp.body_b)
        fail(bn, dotted(p, "bodies"), "names the same body twice: contact is between two bodies");
      for (const ContactPairSpec& q : c.pairs)
        if ((q.body_a == cp.body_a && q.body_b == cp.body_b) ||
            (q.body_a == cp.body_b && q.body_b == cp.body_a))
          fail(bn, dotted(p, "bodies"), "this pair of bodies is already listed");
      cp.friction = number(pair, "friction", p, std::nullopt, &pair);
      if (cp.friction < 0.0)
        fail(pair.get("friction"), dotted(p, "friction"),
             "must not be negative, got " + format_number(cp.friction));
      c.pairs.push_back(cp);
      toml::table o;
      o.insert_or_assign("bodies",
                         toml::array{spec.bodies[cp.body_a].name, spec.bodies[cp.body_b].name});
      o.insert_or_assign("friction", cp.friction);
      pairs_out.push_back(std::move(o));
    }
    if (!pairs_out.empty()) out.insert_or_assign("pairs", std::move(pairs_out));
  }
  out.insert_or_assign("penalty_factor", c.penalty_factor);
  out.insert_or_assign("friction", c.friction);
  out.insert_or_assign("impact_damping", c.impact_damping);
}

void Reader::read_compaction(const toml::table& root, ModelSpec& spec, toml::table& out,
                             std::set<std::string>& names) const {
  const toml::node* n = root.get("compaction");
  if (!n) return;
  const toml::table& t = require_table(n, "compaction");
  const std::string p = "compaction";
  check_keys(t, p,
             {"punch", "bottom", "die", "die_walls", "die_area", "die_perimeter", "powder",
              "fit_min_pressure", "fit_max_pressure"});
  CompactionSpec c;
  std::vector<std::string> wall_names, body_names;
  for (const auto& w : spec.walls) wall_names.push_back(w.name);
  for (const auto& b : spec.bodies) body_names.push_back(b.name);
  auto wall_index = [&](const toml::node* node, const std::string& key, const std::string& name) {
    for (std::size_t i = 0; i < spec.walls.size(); ++i)
      if (spec.walls[i].name == name) return static_cast<int>(i);
    fail(
        node, key,
        "unknown wall '" + name + "'" + did_you_mean(name, wall_names) +
            (wall_names.empty() ? "; the scene has no [[walls]]" : "; walls: " + join(wall_names)));
  };
  const std::string punch = string(t, "punch", p, &t), bottom = string(t, "bottom", p, &t);
  c.punch = wall_index(t.get("punch"), dotted(p, "punch"), punch);
  c.bottom = wall_index(t.get("bottom"), dotted(p, "bottom"), bottom);
  if (c.punch == c.bottom)
    fail(t.get("bottom"), dotted(p, "bottom"), "the punch and the bottom must be two walls");
  const Vec3 axis = spec.walls[c.bottom].normal;  // into the powder
  if (spec.walls[c.punch].normal.dot(axis) > -0.999)
    fail(t.get("punch"), dotted(p, "punch"),
         "the punch wall '" + punch + "' must face the bottom wall '" + bottom +
             "' (opposite normals along the die axis)");
  toml::table o;
  o.insert_or_assign("punch", punch);
  o.insert_or_assign("bottom", bottom);

  const toml::node* dn = t.get("die");
  const toml::node* dwn = t.get("die_walls");
  if (dn && dwn)
    fail(dwn, dotted(p, "die_walls"),
         "give either 'die' (a polygonal die made into walls) or 'die_walls' (with die_area), "
         "not both");
  if (!dn && !dwn)
    fail(&t, p,
         "needs a die: 'die = { radius = r, sides = N }' (N plane walls around the axis) or "
         "'die_walls = [...]' naming walls, with 'die_area' (and 'die_perimeter')");
  if (dn) {
    const std::string dp = dotted(p, "die");
    const toml::table& d = require_table(dn, dp);
    check_keys(d, dp,
               {"radius", "sides", "friction", "penalty_factor", "damping", "height", "angle"});
    if (t.contains("die_area") || t.contains("die_perimeter"))
      fail(t.contains("die_area") ? t.get("die_area") : t.get("die_perimeter"), p,
           "die_area and die_perimeter follow from 'die' (give them only with 'die_walls')");
    const double r = positive(d, "radius", dp, std::nullopt, &d);
    const std::int64_t sides = opt_integer(d, "sides", dp).value_or(24);
    if (sides < 3 || sides > 1024)
      fail(d.get("sides"), dotted(dp, "sides"),
           "must be an integer in [3, 1024], got " + std::to_string(sides));
    const double mu = number(d, "friction", dp, 0.0, &d);
    if (mu < 0.0)
      fail(d.get("friction"), dotted(dp, "friction"),
           "must not be negative, got " + format_number(mu));
    const double pf = positive(d, "penalty_factor", dp, 0.0, &d);
    const double damping = number(d, "damping", dp, 0.0, &d);
    if (damping < 0.0 || damping > 1.0)
      fail(d.get("damping"), dotted(dp, "damping"),
           "must be a fraction of critical damping in [0, 1], got " + format_number(damping));
    const auto height = opt_number(d, "height", dp);
    if (height && !(*height > 0.0))
      fail(d.get("height"), dotted(dp, "height"),
           "must be positive, got " + format_number(*height));
    const double angle = number(d, "angle", dp, 0.0, &d);
    // Two directions across the axis: x (or y when the axis is near x) made orthogonal to it,
    // so that a 4-sided die about z has its faces normal to x and y.
    Vec3 e1 = std::fabs(axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    e1 = (e1 - e1.dot(axis) * axis).normalized();
    const Vec3 e2 = axis.cross(e1);
    const Vec3 centre = spec.walls[c.bottom].point;
    const double pi = std::acos(-1.0);
    for (std::int64_t k = 0; k < sides; ++k) {
      const double th = angle * pi / 180.0 + 2.0 * pi * static_cast<double>(k) / sides;
      const Vec3 u = std::cos(th) * e1 + std::sin(th) * e2;
      WallSpec w;
      w.name = "die_" + std::to_string(k + 1);
      if (!names.insert(w.name).second)
        fail(dn, dp,
             "makes walls named die_1 ... die_" + std::to_string(sides) + ", but '" + w.name +
                 "' is already the name of a body or wall");
      w.point = centre + r * u;  // r is the inscribed radius: each face is r from the axis
      w.normal = -u;
      w.friction = mu;
      w.penalty_factor = pf;
      w.damping = damping;
      if (height) {
        w.bounded = true;
        w.bound_axis = axis;
        w.bound_max = centre.dot(axis) + *height;
      }
      c.die_walls.push_back(static_cast<int>(spec.walls.size()));
      spec.walls.push_back(w);
    }
    const double side = 2.0 * r * std::tan(pi / static_cast<double>(sides));
    c.area = 0.5 * r * side * static_cast<double>(sides);
    c.perimeter = side * static_cast<double>(sides);
    toml::table od;
    od.insert_or_assign("radius", r);
    od.insert_or_assign("sides", sides);
    od.insert_or_assign("friction", mu);
    if (pf > 0.0) od.insert_or_assign("penalty_factor", pf);
    od.insert_or_assign("damping", damping);
    if (height) od.insert_or_assign("height", *height);
    od.insert_or_assign("angle", angle);
    o.insert_or_assign("die", std::move(od));
  } else {
    const std::string dk = dotted(p, "die_walls");
    const toml::array* a = dwn->as_array();
    if (!a || a->empty()) fail(dwn, dk, "expected a non-empty array of wall names");
    toml::array ow;
    for (const auto& e : *a) {
      if (!e.is_string()) fail(&e, dk, "expected a wall name, got " + type_name(e));
      const std::string name = e.as_string()->get();
      const int wi = wall_index(&e, dk, name);
      if (wi == c.punch || wi == c.bottom)
        fail(&e, dk, "'" + name + "' is the punch or the bottom, not a die wall");
      for (int q : c.die_walls)
        if (q == wi) fail(&e, dk, "'" + name + "' is listed twice");
      c.die_walls.push_back(wi);
      ow.push_back(name);
    }
    c.area = positive(t, "die_area", p, std::nullopt, &t);
    c.perimeter = number(t, "die_perimeter", p, 0.0, &t);
    if (c.perimeter < 0.0)
      fail(t.get("die_perimeter"), dotted(p, "die_perimeter"),
           "must not be negative, got " + format_number(c.perimeter));
    o.insert_or_assign("die_walls", std::move(ow));
    o.insert_or_assign("die_area", c.area);
    o.insert_or_assign("die_perimeter", c.perimeter);
  }

  if (const toml::node* pn = t.get("powder")) {
    const std::string pk = dotted(p, "powder");
    const toml::array* a = pn->as_array();
    if (!a || a->empty()) fail(pn, pk, "expected a non-empty array of body names");
    toml::array ob;
    for (const auto& e : *a) {
      if (!e.is_string()) fail(&e, pk, "expected a body name, got " + type_name(e));
      const std::string name = e.as_string()->get();
      int bi = -1;
      for (std::size_t i = 0; i < spec.bodies.size(); ++i)
        if (spec.bodies[i].name == name) bi = static_cast<int>(i);
      if (bi < 0)
        fail(&e, pk,
             "unknown body '" + name + "'" + did_you_mean(name, body_names) +
                 "; bodies: " + join(body_names));
      for (int q : c.powder)
        if (q == bi) fail(&e, pk, "'" + name + "' is listed twice");
      c.powder.push_back(bi);
      ob.push_back(name);
    }
    o.insert_or_assign("powder", std::move(ob));
  } else {
    bool any = false;
    for (const auto& b : spec.bodies) any = any || !b.fixed;
    if (!any) fail(&t, p, "every body is fixed: there is no powder to compact");
  }
  c.fit_min_pressure = number(t, "fit_min_pressure", p, 0.0, &t);
  c.fit_max_pressure = number(t, "fit_max_pressure", p, 0.0, &t);
  if (c.fit_min_pressure < 0.0)
    fail(t.get("fit_min_pressure"), dotted(p, "fit_min_pressure"),
         "must not be negative, got " + format_number(c.fit_min_pressure));
  if (c.fit_max_pressure < 0.0 ||
      (c.fit_max_pressure > 0.0 && c.fit_max_pressure <= c.fit_min_pressure))
    fail(t.get("fit_max_pressure"), dotted(p, "fit_max_pressure"),
         "must be 0 (the largest pressure) or above fit_min_pressure, got " +
             format_number(c.fit_max_pressure));
  o.insert_or_assign("fit_min_pressure", c.fit_min_pressure);
  o.insert_or_assign("fit_max_pressure", c.fit_max_pressure);
  out = std::move(o);
  spec.compaction = c;
}

// ---------------------------------------------------------------------------------------------
// [[packings]] (io/packing.hpp): a packing file, or generator parameters (optionally cached in
// a file), turned into one body per particle with a shared material and mesh.

PackingParams Reader::read_packing_params(const toml::table& g, const std::string& gp,
                                          toml::table& out) const {
  check_keys(g, gp,
             {"container", "size", "radius", "height", "arrangement", "count", "distribution",
              "diameter", "diameter_min", "diameter_max", "diameter_mean", "sigma", "seed", "shape",
              "orientation", "friction"});
  PackingParams p;
  p.container = opt_string(g, "container", gp).value_or(p.container);
  if (auto s = opt_vec3(g, "size", gp)) p.size = *s;
  p.radius = number(g, "radius", gp, 0.0, &g);
  p.height = number(g, "height", gp, 0.0, &g);
  p.arrangement = opt_string(g, "arrangement", gp).value_or(p.arrangement);
  p.count = opt_integer(g, "count", gp).value_or(0);
  p.distribution = opt_string(g, "distribution", gp).value_or(p.distribution);
  p.diameter = number(g, "diameter", gp, 0.0, &g);
  p.diameter_min = number(g, "diameter_min", gp, 0.0, &g);
  p.diameter_max = number(g, "diameter_max", gp, 0.0, &g);
  p.diameter_mean = number(g, "diameter_mean", gp, 0.0, &g);
  p.sigma = number(g, "sigma", gp, 0.0, &g);
  if (auto s = opt_integer(g, "seed", gp)) {
    if (*s < 0) fail(g.get("seed"), dotted(gp, "seed"), "must not be negative");
    p.seed = static_cast<std::uint64_t>(*s);
  }
  p.shape = opt_string(g, "shape", gp).value_or(p.shape);
  p.orientation = opt_string(g, "orientation", gp).value_or("");
  p.friction = number(g, "friction", gp, p.friction, &g);
  // Keys that the chosen container / arrangement / distribution does not use are errors, not
  // silently ignored values.
  const bool box = p.container == "box", mono = p.distribution == "monodisperse";
  std::vector<std::string> unused;
  if (box) unused.insert(unused.end(), {"radius", "height"});
  if (!box) unused.push_back("size");
  if (mono) unused.insert(unused.end(), {"diameter_min", "diameter_max", "diameter_mean", "sigma"});
  if (!mono) unused.push_back("diameter");
  if (p.distribution == "uniform") unused.insert(unused.end(), {"diameter_mean", "sigma"});
  if (p.arrangement != "random") unused.push_back("friction");
  if (p.container == "box" || p.container == "cylinder")
    for (const std::string& k : unused)
      if (g.contains(k))
        fail(g.get(k), dotted(gp, k),
             "is not used by this packing (container '" + p.container + "', arrangement '" +
                 p.arrangement + "', distribution '" + p.distribution + "')");
  if (auto e = check_packing_params(p))
    fail(g.contains(e->key) ? g.get(e->key) : &g, dotted(gp, e->key), e->message);
  // The resolved parameters, as the packing file's header has them.
  const toml::table canonical =
      toml::parse(packing_params_text(p), std::string_view("packing parameters"));
  for (const auto& [k, v] : canonical) out.insert_or_assign(k.str(), v);
  return p;
}

void Reader::read_packings(const toml::table& root, ModelSpec& spec, toml::array& out,
                           std::set<std::string>& names) const {
  std::set<std::string> packing_names;
  for (const auto& [tp, entry_prefix] : entries(root, "packings")) {
    const toml::table& t = *tp;
    // An unnamed packing is "p" (its bodies p0001, ...), and its keys are named so.
    const std::string p = t.contains("name") ? entry_prefix : std::string("packings.p");
    check_keys(t, p,
               {"name", "material", "mesh", "file", "generate", "cache", "position", "rotation",
                "velocity", "fbar"});
    const std::string prefix = entry_name(t, p, packing_names, "packing", std::string("p"));
    toml::table o;
    o.insert_or_assign("name", prefix);

    // Material, placement, F-bar: as for [[bodies]].
    const std::string mat = string(t, "material", p, &t);
    int material = -1;
    std::vector<std::string> mat_names;
    for (std::size_t i = 0; i < spec.materials.size(); ++i) {
      mat_names.push_back(spec.materials[i].name);
      if (spec.materials[i].name == mat) material = static_cast<int>(i);
    }
    if (material < 0)
      fail(t.get("material"), dotted(p, "material"),
           "unknown material '" + mat + "'" + did_you_mean(mat, mat_names) +
               (mat_names.empty() ? "; the scene defines no [[materials]]"
                                  : "; materials: " + join(mat_names)));
    o.insert_or_assign("material", mat);
    const Vec3 position = opt_vec3(t, "position", p).value_or(Vec3::Zero());
    // The whole packing, container and all, is turned about the container's origin: a layer
    // settled in a box lies on a slope (gravity in the generator is along the box's -z).
    const Vec3 rotation = opt_vec3(t, "rotation", p).value_or(Vec3::Zero());
    const Eigen::Matrix3d packing_rotation = rotation_from_degrees(rotation);
    const Vec3 velocity = opt_vec3(t, "velocity", p).value_or(Vec3::Zero());
    std::optional<FbarMode> fbar;
    if (const toml::node* fb = t.get("fbar")) {
      if (auto flag = fb->value<bool>()) {
        fbar = *flag ? FbarMode::VolumeAverage : FbarMode::Off;
      } else {
        const std::string v = string(t, "fbar", p, &t);
        fbar = parse_fbar_mode(v);
        if (!fbar)
          fail(fb, dotted(p, "fbar"),
               "must be true, false, \"volume_average\", \"centroid\", \"nodal\", \"subtet\" or "
               "\"off\", got '" +
                   v + "'");
      }
    }

    // The particles: a file, or generated (and cached).
    const bool has_file = t.contains("file"), has_gen = t.contains("generate");
    if (has_file == has_gen)
      fail(has_file ? t.get("generate") : &t, p,
           "give either 'file' (a packing file from `femdem pack`) or 'generate' (the packing's "
           "parameters, optionally with 'cache')");
    if (has_file && t.contains("cache"))
      fail(t.get("cache"), dotted(p, "cache"), "goes with 'generate'; 'file' is read as it is");
    auto path_of = [&](const std::string& key) {
      const std::string f = string(t, key, p, &t);
      if (f.empty()) fail(t.get(key), dotted(p, key), "must not be empty");
      o.insert_or_assign(key, f);
      return fs::path(f).is_absolute() ? fs::path(f) : base_dir_ / f;
    };
    Packing packing;
    if (has_file) {
      const fs::path full = path_of("file");
      std::error_code ec;
      if (!fs::is_regular_file(full, ec))
        fail(t.get("file"), dotted(p, "file"),
             "packing file '" + full.string() +
                 "' does not exist (relative paths are resolved against the scene's folder; "
                 "write one with `femdem pack`)");
      try {
        packing = read_packing(full.string());
      } catch (const InputError& e) {
        fail(t.get("file"), dotted(p, "file"), "bad packing file: " + e.describe());
      }
    } else {
      const std::string gp = dotted(p, "generate");
      const toml::table& g = require_table(t.get("generate"), gp);
      toml::table go;
      const PackingParams params = read_packing_params(g, gp, go);
      o.insert_or_assign("generate", std::move(go));
      const std::string wanted = packing_params_text(params);
      std::optional<fs::path> cache;
      if (t.contains("cache")) cache = path_of("cache");
      bool cached = false;
      if (cache) {
        std::error_code ec;
        if (fs::is_regular_file(*cache, ec)) {
          try {
            packing = read_packing(cache->string());
            cached = packing.params_text == wanted;  // else stale: generated again below
          } catch (const InputError&) {
            cached = false;  // a broken cache is replaced
          }
        }
      }
      if (!cached) {
        try {
          packing = generate_packing(params);
        } catch (const InputError& e) {
          fail(g.contains(e.key) ? g.get(e.key) : &g, dotted(gp, e.key), e.what());
        }
        if (cache) {
          try {
            write_packing(cache->string(), packing);
          } catch (const std::exception& e) {
            fail(t.get("cache"), dotted(p, "cache"),
                 "cannot write the packing cache: " + std::string(e.what()));
          }
        }
      }
    }

    // The mesh: the sphere generator at each particle's radius, or any other mesh source
    // (a gmsh file, a CAD file, another generator) scaled so that its bounding sphere is the
    // particle's and turned by the particle's orientation.
    const std::string mp = dotted(p, "mesh");
    const toml::node* mn = t.get("mesh");
    if (!mn) fail(&t, mp, "required value is missing");
    const toml::table& mesh = require_table(mn, mp);
    toml::table mesh_out;
    const bool sphere = mesh.contains("generator") && mesh.get("generator")->is_string() &&
                        mesh.get("generator")->as_string()->get() == "sphere";
    Tet10Mesh reference;  // unit bounding radius, centred on the origin (not the sphere case)
    double element_size = 0.0;
    if (sphere) {
      check_keys(mesh, mp, {"generator", "element_size", "cells_per_radius"},
                 "for the sphere generator in a packing (the radius is each particle's)");
      mesh_out.insert_or_assign("generator", "sphere");
      if (mesh.contains("element_size") == mesh.contains("cells_per_radius"))
        fail(&mesh, mp,
             "give either 'element_size' (m, the same for every particle) or "
             "'cells_per_radius' (the same mesh for every particle, scaled)");
      if (mesh.contains("element_size")) {
        element_size = positive(mesh, "element_size", mp, std::nullopt, &mesh);
        mesh_out.insert_or_assign("element_size", element_size);
        double total = 0.0;
        try {
          for (const PackedParticle& q : packing.particles)
            total += static_cast<double>(sphere_element_count(q.radius, element_size));
        } catch (const InputError& e) {
          fail(mesh.get("element_size"), dotted(mp, "element_size"), e.what());
        }
        if (total > kMaxGeneratedElements)
          fail(mesh.get("element_size"), dotted(mp, "element_size"),
               "the particles would have " + format_number(total) + " elements in all (at most " +
                   format_number(kMaxGeneratedElements) + ")");
      } else {
        const auto n = opt_integer(mesh, "cells_per_radius", mp);
        if (*n < 1 || *n > 100)
          fail(mesh.get("cells_per_radius"), dotted(mp, "cells_per_radius"),
               "must lie in [1, 100], got " + std::to_string(*n));
        mesh_out.insert_or_assign("cells_per_radius", *n);
        reference = generate_sphere(1.0, 1.0 / static_cast<double>(*n));
        if (static_cast<double>(reference.elements.size()) *
                static_cast<double>(packing.particles.size()) >
            kMaxGeneratedElements)
          fail(mesh.get("cells_per_radius"), dotted(mp, "cells_per_radius"),
               "the particles would have more than " + format_number(kMaxGeneratedElements) +
                   " elements in all");
      }
    } else {
      reference = read_mesh(mesh, p, mesh_out);
      if (reference.elements.empty() || reference.nodes.empty())
        fail(mn, mp, "the mesh has no elements");
      Vec3 c;
      const double rb = bounding_radius(reference, &c);
      for (Vec3& x : reference.nodes) x = (x - c) / rb;
    }
    o.insert_or_assign("mesh", std::move(mesh_out));

    // One body per particle, named <name>0001, <name>0002, ... (bottom layers first).
    const std::size_t n = packing.particles.size();
    const std::size_t width = std::max<std::size_t>(4, std::to_string(n).size());
    std::map<double, Tet10Mesh> by_radius;  // element_size spheres, one per distinct radius
    for (std::size_t i = 0; i < n; ++i) {
      const PackedParticle& q = packing.particles[i];
      std::string index = std::to_string(i + 1);
      index.insert(0, width - index.size(), '0');
      BodySpec b;
      b.name = prefix + index;
      if (!names.insert(b.name).second)
        fail(t.contains("name") ? t.get("name") : &t, dotted(p, "name"),
             "the packing's body '" + b.name +
                 "' has the name of another body or wall (bodies and walls share one set of "
                 "names): choose another 'name' for the packing");
      b.material = material;
      b.velocity = velocity;
      b.fbar = fbar;
      const Eigen::Matrix3d rot = packing_rotation * q.orientation.toRotationMatrix();
      const Vec3 centre = packing_rotation * q.centre + position;
      if (element_size > 0.0) {
        auto it = by_radius.find(q.radius);
        if (it == by_radius.end())
          it = by_radius.emplace(q.radius, generate_sphere(q.radius, element_size)).first;
        b.mesh = it->second;
        for (Vec3& x : b.mesh.nodes) x = rot * x + centre;
      } else {
        b.mesh = reference;
        for (Vec3& x : b.mesh.nodes) x = rot * (q.radius * x) + centre;
      }
      spec.bodies.push_back(std::move(b));
    }
    o.insert_or_assign("position", toml::array{position.x(), position.y(), position.z()});
    o.insert_or_assign("rotation", toml::array{rotation.x(), rotation.y(), rotation.z()});
    o.insert_or_assign("velocity", toml::array{velocity.x(), velocity.y(), velocity.z()});
    o.insert_or_assign("fbar",
                       to_string(fbar.value_or(default_fbar_mode(spec.materials[material]))));
    out.push_back(std::move(o));
  }
}

ModelSpec Reader::read(const toml::table& root, const std::string& stem, toml::table& resolved) {
  check_keys(root, "",
             {"title", "simulation", "materials", "bodies", "packings", "walls", "constraints",
              "contact", "compaction"});
  ModelSpec spec;
  spec.title = opt_string(root, "title", "").value_or(stem);
  resolved.insert_or_assign("title", spec.title);

  toml::table sim;
  read_simulation(root, spec, sim);
  toml::array materials, bodies, walls, constraints;
  read_materials(root, spec, materials);
  std::set<std::string> names;  // bodies and walls share one namespace (history.csv columns)
  read_bodies(root, spec, bodies, names);
  toml::array packings;
  read_packings(root, spec, packings, names);
  read_walls(root, spec, walls, names);
  read_constraints(root, spec, constraints);
  toml::table contact;
  read_contact(root, spec, contact);
  toml::table compaction;
  read_compaction(root, spec, compaction, names);

  resolved.insert_or_assign("simulation", std::move(sim));
  resolved.insert_or_assign("materials", std::move(materials));
  resolved.insert_or_assign("bodies", std::move(bodies));
  if (!packings.empty()) resolved.insert_or_assign("packings", std::move(packings));
  if (!walls.empty()) resolved.insert_or_assign("walls", std::move(walls));
  if (!constraints.empty()) resolved.insert_or_assign("constraints", std::move(constraints));
  resolved.insert_or_assign("contact", std::move(contact));
  if (spec.compaction) resolved.insert_or_assign("compaction", std::move(compaction));
  return spec;
}

}  // namespace

SceneFile load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  SceneFile scene;
  scene.path = path;
  const fs::path p(path);
  scene.stem = p.stem().string();
  scene.directory = p.parent_path().empty() ? std::string(".") : p.parent_path().string();

  std::error_code ec;
  if (!fs::exists(p, ec)) throw InputError("scene file does not exist", path);
  if (fs::is_directory(p, ec)) throw InputError("is a folder, not a scene file", path);
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError("cannot read the scene file", path);
  std::ostringstream text;
  text << in.rdbuf();

  toml::table root;
  try {
    root = toml::parse(text.str(), path);
  } catch (const toml::parse_error& e) {
    throw InputError("TOML syntax error: " + std::string(e.description()), path,
                     static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column));
  }

  Reader reader(path, fs::path(scene.directory));
  for (const auto& o : overrides) reader.apply_override(root, o);

  toml::table resolved;
  scene.model = reader.read(root, scene.stem, resolved);
  scene.resolved_toml = resolved_scene_text(resolved);
  scene.notes = std::move(reader.notes_);
  return scene;
}

}  // namespace femdem
