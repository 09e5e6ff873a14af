// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/errors.hpp"
#include "io/scene/resolved_scene.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

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

}  // namespace femdem::scene
