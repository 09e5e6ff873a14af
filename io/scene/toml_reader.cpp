// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/toml_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "engine/errors.hpp"

namespace femdem::scene {

// ---------------------------------------------------------------------------------------------
// Small helpers

namespace {

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

}  // namespace

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

std::string join(const std::vector<std::string>& items, std::string_view sep) {
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

void Reader::count_elements(double elements, const toml::node* where,
                            const std::string& key) const {
  elements_read_ += elements;
  if (max_total_elements_ > 0 && elements_read_ > static_cast<double>(max_total_elements_))
    fail(where, key,
         "the scene would have " + format_number(elements_read_) +
             " elements in all with this one, more than this reading allows (" +
             std::to_string(max_total_elements_) + ")");
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

std::optional<double> Reader::opt_penalty_factor(const toml::table& t,
                                                 const std::string& prefix) const {
  const toml::node* n = t.get("penalty_factor");
  if (!n) return std::nullopt;
  if (const auto* s = n->as_string()) {
    if (s->get() == "auto") return 0.0;
    fail(n, dotted(prefix, "penalty_factor"),
         "expected a positive number or \"auto\", got \"" + s->get() + "\"");
  }
  if (!n->is_number())
    fail(n, dotted(prefix, "penalty_factor"),
         "expected a positive number or \"auto\", got " + type_name(*n));
  return positive(t, "penalty_factor", prefix, std::nullopt, &t);
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

}  // namespace femdem::scene
