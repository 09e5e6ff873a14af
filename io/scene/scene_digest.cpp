// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/scene_digest.hpp"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/scene/resolved_scene.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem {
namespace {

toml::table parse(const std::string& text) {
  try {
    return toml::parse(text);
  } catch (const toml::parse_error& e) {
    throw std::invalid_argument(std::string("the resolved scene is not TOML: ") +
                                std::string(e.description()));
  }
}

// "simulation.end_time" -> the table "simulation" and the key "end_time".
std::pair<std::string, std::string> split(const std::string& dotted) {
  const auto dot = dotted.find('.');
  return {dotted.substr(0, dot), dotted.substr(dot + 1)};
}

std::string value_text(const toml::node& n) {
  if (const auto* d = n.as_floating_point()) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, d->get());
    std::string s(buf, r.ptr);
    // a TOML float needs a point or an exponent (1e-3 has one; 2 would read as an integer)
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
  }
  if (const auto* i = n.as_integer()) return std::to_string(i->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  std::ostringstream os;
  if (const auto* s = n.as_string()) os << toml::value<std::string>(s->get());
  return os.str();
}

}  // namespace

// What a resumed run may change: settings that act only on the steps still to come.
// contact_time_step_safety is one (a settling run may take larger steps once its energy balance
// has been seen); time_step_safety would be too, but the digests of checkpoints already
// written include it, and leaving it out of the digest now would refuse them all.
const std::vector<std::string>& resumable_keys() {
  static const std::vector<std::string> keys = {"simulation.end_time",
                                                "simulation.output_interval",
                                                "simulation.history_interval",
                                                "simulation.checkpoint_interval",
                                                "simulation.checkpoint_wall_interval",
                                                "simulation.rest_kinetic_fraction",
                                                "simulation.rest_hold_time",
                                                "simulation.rebalance_threshold",
                                                "simulation.threads",
                                                "simulation.contact_time_step_safety"};
  return keys;
}

std::string scene_identity_text(const std::string& resolved_toml) {
  toml::table root = parse(resolved_toml);
  for (const std::string& key : resumable_keys()) {
    const auto [table, name] = split(key);
    if (toml::table* t = root[table].as_table()) t->erase(name);
  }
  return scene::resolved_scene_text(root);
}

std::string scene_digest(const std::string& resolved_toml) {
  const std::string text = scene_identity_text(resolved_toml);
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64 offset basis and prime
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<std::string> resumable_settings(const std::string& resolved_toml) {
  const toml::table root = parse(resolved_toml);
  std::vector<std::string> out;
  for (const std::string& key : resumable_keys()) {
    const auto [table, name] = split(key);
    const toml::table* t = root[table].as_table();
    const toml::node* n = t ? t->get(name) : nullptr;
    if (n) out.push_back(key + "=" + value_text(*n));
  }
  return out;
}

std::string first_differing_line(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(sa, la));
    const bool gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "";
    if (!ga) return "(none; the other has: " + lb + ")";
    if (!gb || la != lb) return la;
  }
}

}  // namespace femdem
