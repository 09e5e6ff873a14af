// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/scene_reader.hpp"

#include <toml++/toml.h>
#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "engine/errors.hpp"
#include "io/scene/resolved_scene.hpp"
#include "io/scene/toml_reader.hpp"

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

namespace scene {

ModelSpec Reader::read(const toml::table& root, const std::string& stem, toml::table& resolved) {
  check_keys(root, "",
             {"title", "simulation", "materials", "bodies", "packings", "walls", "tubes",
              "constraints", "contact", "compaction", "output"});
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
  toml::array tubes;
  read_tubes(root, spec, tubes, names);
  read_constraints(root, spec, constraints);
  toml::table contact;
  read_contact(root, spec, contact);
  toml::table compaction;
  read_compaction(root, spec, compaction, names);
  toml::table output;
  read_output(root, spec, output);

  resolved.insert_or_assign("simulation", std::move(sim));
  resolved.insert_or_assign("materials", std::move(materials));
  resolved.insert_or_assign("bodies", std::move(bodies));
  if (!packings.empty()) resolved.insert_or_assign("packings", std::move(packings));
  if (!walls.empty()) resolved.insert_or_assign("walls", std::move(walls));
  if (!tubes.empty()) resolved.insert_or_assign("tubes", std::move(tubes));
  if (!constraints.empty()) resolved.insert_or_assign("constraints", std::move(constraints));
  resolved.insert_or_assign("contact", std::move(contact));
  if (spec.compaction) resolved.insert_or_assign("compaction", std::move(compaction));
  resolved.insert_or_assign("output", std::move(output));
  return spec;
}

}  // namespace scene

using scene::Reader;
using scene::resolved_scene_text;

namespace {

// toml++'s words, except where they hide the usual cause: a string left open reads as a line
// break inside it ("unescaped control characters ...").
std::string syntax_error_text(const std::string& text, std::string_view description, int line) {
  const bool control = description.find("unescaped control characters") != std::string_view::npos;
  if (control && line > 0) {
    std::istringstream lines(text);
    std::string l;
    for (int i = 0; i < line && std::getline(lines, l);) ++i;
    if (std::count(l.begin(), l.end(), '"') % 2 == 1)
      return "unterminated string: a string opened on this line does not close on it (add the "
             "closing \", or use a multi-line string \"\"\"...\"\"\")";
  }
  return std::string(description);
}

}  // namespace

SceneFile load_scene(const std::string& path, const std::vector<std::string>& overrides,
                     SceneReadLimits limits) {
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
    const int line = static_cast<int>(e.source().begin.line);
    const int column = static_cast<int>(e.source().begin.column);
    throw InputError("TOML syntax error: " + syntax_error_text(text.str(), e.description(), line),
                     path, line, column);
  }

  Reader reader(path, fs::path(scene.directory));
  reader.max_mesh_elements_ = limits.max_mesh_elements;
  reader.max_total_elements_ = limits.max_total_elements;
  for (const auto& o : overrides) reader.apply_override(root, o);

  toml::table resolved;
  scene.model = reader.read(root, scene.stem, resolved);
  scene.resolved_toml = resolved_scene_text(resolved);
  scene.notes = std::move(reader.notes_);
  return scene;
}

}  // namespace femdem
