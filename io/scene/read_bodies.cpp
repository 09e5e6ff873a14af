// SPDX-License-Identifier: GPL-3.0-or-later
#include <filesystem>
#include <fstream>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/cad_mesh.hpp"
#include "io/mesh/gmsh_io.hpp"
#include "io/mesh/mesh_cache.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/scene/scene_reader.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kGenerators = {"box", "cylinder", "sphere"};

}  // namespace

Tet10Mesh Reader::read_mesh(const toml::table& mesh, const std::string& bp, toml::table& out,
                            NodeSets* node_sets) const {
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
    if (max_mesh_elements_ > 0) {
      // the reading's own cap: counted at the finest size the mesh can have
      const double finest = refine ? refine->size : h;
      std::int64_t count = 0;
      try {
        count = gen == "box"        ? box_element_count(size, finest)
                : gen == "cylinder" ? cylinder_element_count(radius, length, finest)
                                    : sphere_element_count(radius, finest);
      } catch (const InputError&) {
        count = max_mesh_elements_ + 1;  // past the generators' own limit
      }
      if (count > max_mesh_elements_)
        fail(mesh.get("element_size"), dotted(p, "element_size"),
             "the mesh would have up to " + std::to_string(count) +
                 " elements, more than this reading allows (" + std::to_string(max_mesh_elements_) +
                 ")");
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
    check_keys(mesh, p, {"file", "physical"}, "for a gmsh .msh file (it is used as meshed)");
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
    if (max_mesh_elements_ > 0)
      options.max_elements = std::min(options.max_elements, max_mesh_elements_);
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
  GmshReadInfo info;
  try {
    m = read_gmsh(full.string(), &info);
  } catch (const InputError& e) {
    fail(fn, fkey, "bad mesh: " + e.describe());
  } catch (const std::exception& e) {
    fail(fn, fkey, "cannot read mesh '" + full.string() + "': " + e.what());
  }
  // Physical volumes: one is the body; several need `physical` to say which.
  std::vector<std::string> volumes;
  for (const GmshPhysicalGroup& g : info.groups)
    if (g.dim == 3 && !g.elements.empty()) volumes.push_back(g.label());
  std::string volume;
  if (const toml::node* pn = mesh.get("physical")) {
    volume = string(mesh, "physical", p, &mesh);
    if (std::find(volumes.begin(), volumes.end(), volume) == volumes.end())
      fail(pn, dotted(p, "physical"),
           "'" + file + "' has no physical volume '" + volume + "'" +
               did_you_mean(volume, volumes) +
               (volumes.empty() ? "; it defines no physical volumes"
                                : "; its physical volumes: " + join(volumes)));
    out.insert_or_assign("physical", volume);
  } else if (volumes.size() > 1) {
    fail(fn, fkey,
         "'" + file + "' holds " + std::to_string(volumes.size()) + " physical volumes (" +
             join(volumes) +
             "): choose the body's with physical = \"NAME\" (one [[bodies]] entry per volume)");
  }
  GmshBody body = gmsh_body(std::move(m), info, volume);
  m = std::move(body.mesh);
  if (node_sets) *node_sets = std::move(body.node_sets);
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
    NodeSets node_sets;
    b.mesh = read_mesh(require_table(mn, dotted(p, "mesh")), p, mesh_out, &node_sets);
    body_node_sets_[b.name] = std::move(node_sets);
    if (b.mesh.elements.empty() || b.mesh.nodes.empty())
      fail(mn, dotted(p, "mesh"), "the mesh has no elements");
    count_elements(static_cast<double>(b.mesh.elements.size()), mn, dotted(p, "mesh"));
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

}  // namespace femdem::scene
