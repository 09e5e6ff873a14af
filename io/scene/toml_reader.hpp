// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The scene reader's internals (io/scene/*.cpp only; the public interface is scene_reader.hpp).
// Reader walks the TOML tree of a scene after the --set overrides are applied, checks it and
// fills the ModelSpec and the resolved scene. Its generic helpers (toml_reader.cpp) look values
// up by key and throw InputError naming the file, line, column and dotted key; every section has
// its reader in its own file (read_simulation.cpp, read_materials.cpp, read_bodies.cpp,
// read_walls.cpp, read_tubes.cpp, read_packings.cpp, read_compaction.cpp), the overrides are in
// overrides.cpp, and Reader::read (scene_reader.cpp) calls the sections in order.
#include <toml++/toml.h>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/model_spec.hpp"
#include "io/packing/packing.hpp"

namespace femdem::scene {

// ---------------------------------------------------------------------------------------------
// Small helpers

// " (did you mean 'xxx'?)" for the closest candidate within a few edits, else "".
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);
std::string join(const std::vector<std::string>& items, std::string_view sep = ", ");
std::string trim(std::string_view s);
std::string lower(std::string s);
// "a table", "an array", "a string", ... for messages.
std::string type_name(const toml::node& n);
// Shortest round-trip form.
std::string format_number(double v);
// A velocity history as the resolved scene writes it: rows [t, vx, vy, vz].
toml::array velocity_history_rows(const std::vector<VelocityPoint>& history);

// ---------------------------------------------------------------------------------------------
// The reader: walks the (overridden) TOML tree, checks it, fills the ModelSpec and the resolved
// scene.

class Reader {
 public:
  Reader(std::string scene_path, std::filesystem::path base_dir)
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
  // `penalty_factor`: a positive number, or "auto" (returned as 0: the automatic stiffness of
  // engine/contact_stiffness.hpp); nullopt when absent.
  std::optional<double> opt_penalty_factor(const toml::table& t, const std::string& prefix) const;
  std::string string(const toml::table& t, std::string_view k, const std::string& prefix,
                     const toml::node* owner) const;
  std::optional<Vec3> opt_vec3(const toml::table& t, std::string_view k,
                               const std::string& prefix) const;
  bool boolean(const toml::table& t, std::string_view k, const std::string& prefix, bool def) const;
  class MaterialTable;  // a [[materials]] entry as materials/material_keys.hpp sees it
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
  // A body's named node sets (gmsh physical points, curves, surfaces): (name, node indices).
  using NodeSets = std::vector<std::pair<std::string, std::vector<std::int32_t>>>;
  Tet10Mesh read_mesh(const toml::table& mesh, const std::string& prefix, toml::table& out,
                      NodeSets* node_sets = nullptr) const;
  void read_walls(const toml::table& root, ModelSpec& spec, toml::array& out,
                  std::set<std::string>& names) const;
  // t.velocity_history (empty when absent): rows [t, vx, vy, vz], the first at t = 0, times
  // increasing; an error when t also has a constant `velocity`.
  std::vector<VelocityPoint> read_velocity_history(const toml::table& t,
                                                   const std::string& prefix) const;
  // What a generated set of walls shares (a die's, a tube's): friction (>= 0), penalty factor
  // (> 0 its own, 0 the [contact] one, < 0 "auto") and damping (in [0, 1]), read from t and
  // written back to the resolved table by `write`.
  struct WallSurface {
    double friction = 0.0, penalty_factor = 0.0, damping = 0.0;
    void write(toml::table& out) const;
  };
  WallSurface read_wall_surface(const toml::table& t, const std::string& prefix) const;
  // t.sides of a polygonal die or tube: an integer in [3, 1024], 24 when absent.
  int read_polygon_sides(const toml::table& t, const std::string& prefix) const;
  // [[tubes]]: each a polygonal tube of bounded walls, moving as a whole (lifted off a column).
  void read_tubes(const toml::table& root, ModelSpec& spec, toml::array& out,
                  std::set<std::string>& names) const;
  void read_constraints(const toml::table& root, ModelSpec& spec, toml::array& out) const;
  RegionSpec read_region(const toml::table& c, const std::string& prefix, toml::table& out) const;
  void read_contact(const toml::table& root, ModelSpec& spec, toml::table& out) const;
  void read_output(const toml::table& root, ModelSpec& spec, toml::table& out) const;
  // A law's name at t[key] (or `fallback`), checked against the registered `laws`.
  std::string law_name(const toml::table& t, std::string_view key, std::string_view fallback,
                       const std::vector<std::string>& laws) const;
  void read_compaction(const toml::table& root, ModelSpec& spec, toml::table& out,
                       std::set<std::string>& names) const;
  // [[packings]]: one body per particle of a packing file or generated packing.
  void read_packings(const toml::table& root, ModelSpec& spec, toml::array& out,
                     std::set<std::string>& names) const;
  PackingParams read_packing_params(const toml::table& g, const std::string& prefix,
                                    toml::table& out) const;

  std::string scene_path_;
  std::filesystem::path base_dir_;
  std::map<const toml::node*, std::string> override_nodes_;  // nodes created by --set
  mutable std::map<std::string, NodeSets> body_node_sets_;   // by body name (read_bodies)

 public:
  // What happened while reading that the user should see in the log (CAD meshing, cache).
  mutable std::vector<std::string> notes_;
  // SceneReadLimits::max_mesh_elements (0: none beyond the mesh sources' own)
  std::int64_t max_mesh_elements_ = 0;
  // SceneReadLimits::max_total_elements (0: none)
  std::int64_t max_total_elements_ = 0;
  // Counts `elements` more into the scene's total (the bodies read so far); past
  // max_total_elements_ an input error at `where` (key `key`) before anything more is meshed.
  void count_elements(double elements, const toml::node* where, const std::string& key) const;

 private:
  mutable double elements_read_ = 0.0;
};

}  // namespace femdem::scene
