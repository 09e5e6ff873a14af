// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/resolved_scene.hpp"

#include <cstdio>
#include <ostream>
#include <sstream>
#include <vector>

#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

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

namespace {

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

}  // namespace

std::string resolved_scene_text(const toml::table& root) {
  std::ostringstream os;
  for (const auto& [k, v] : root)
    if (!v.is_table() && !v.is_array()) {
      os << k.str() << " = ";
      write_toml_value(os, v);
      os << "\n";
    }
  for (const char* section : {"simulation", "materials", "bodies", "packings", "walls", "tubes",
                              "constraints", "contact", "compaction", "output"}) {
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

}  // namespace femdem::scene
