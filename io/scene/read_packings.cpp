// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <map>

#include "engine/errors.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/packing/packing.hpp"
#include "io/scene/scene_reader.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// [[packings]] (io/packing/packing.hpp): a packing file, or generator parameters (optionally cached
// in a file), turned into one body per particle with a shared material and mesh.

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
    {
      double total = 0.0;
      if (element_size > 0.0)
        for (const PackedParticle& q : packing.particles)
          total += static_cast<double>(sphere_element_count(q.radius, element_size));
      else
        total = static_cast<double>(reference.elements.size()) *
                static_cast<double>(packing.particles.size());
      count_elements(total, mn, mp);
    }

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

}  // namespace femdem::scene
