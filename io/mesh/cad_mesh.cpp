// SPDX-License-Identifier: GPL-3.0-or-later
// Surface checks and repair (CGAL Polygon_mesh_processing) and volume meshing (CGAL Mesh_3):
// see io/mesh/cad_mesh.hpp. This is the only translation unit that includes CGAL, because CGAL
// headers take minutes to compile; keep it that way.
#include "io/mesh/cad_mesh.hpp"

// GCC 12 warns about boost::graph edge descriptors (inside CGAL's feature detection) that "may
// be used uninitialized"; a false positive in library code this file cannot change.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unordered_map>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"

namespace femdem {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<K, SurfaceMesh>;
// Sequential: the parallel mesher's result depends on thread timing.
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string fmt_point(const Vec3& x) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", x[0], x[1], x[2]);
  return buf;
}

std::string fmt_num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// The surface as an indexed soup, each triangle remembering its index in the file.
struct Soup {
  std::vector<Vec3> points;
  std::vector<std::array<std::int32_t, 3>> tris;
  std::vector<std::int64_t> input_index;
};

// Drops triangles whose corners coincide after the vertex merge, and repeated triangles (the
// same three vertices, in either orientation: a doubled wall, which no solid has).
void drop_collapsed_and_duplicates(Soup& s, const CadMeshOptions& o, const std::string& path,
                                   CadMeshReport& rep) {
  std::int64_t collapsed = 0, duplicate = 0, first_collapsed = -1, first_duplicate = -1;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> seen;  // by smallest two corners
  Soup out;
  out.points = std::move(s.points);
  for (std::size_t i = 0; i < s.tris.size(); ++i) {
    auto t = s.tris[i];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      if (collapsed++ == 0) first_collapsed = s.input_index[i];
      continue;
    }
    std::array<std::int32_t, 3> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    auto& bucket = seen[edge_key(sorted[0], sorted[1])];
    bool dup = false;
    for (std::size_t j : bucket) {
      std::array<std::int32_t, 3> other = out.tris[j];
      std::sort(other.begin(), other.end());
      if (other == sorted) dup = true;
    }
    if (dup) {
      if (duplicate++ == 0) first_duplicate = s.input_index[i];
      continue;
    }
    bucket.push_back(out.tris.size());
    out.tris.push_back(t);
    out.input_index.push_back(s.input_index[i]);
  }
  if (collapsed > 0) {
    const std::string what = std::to_string(collapsed) +
                             " triangle(s) with coincident corners (first: input triangle " +
                             std::to_string(first_collapsed) + ")";
    if (!o.repair) throw InputError("degenerate: " + what, path);
    rep.repairs.push_back("removed " + what);
  }
  if (duplicate > 0) {
    const std::string what = std::to_string(duplicate) +
                             " repeated triangle(s) (first: input triangle " +
                             std::to_string(first_duplicate) + ")";
    if (!o.repair) throw InputError("not manifold: " + what, path);
    rep.repairs.push_back("removed " + what);
  }
  s = std::move(out);
  if (s.tris.empty())
    throw InputError("empty: no triangles left after removing " +
                         std::to_string(collapsed + duplicate) + " degenerate or repeated ones",
                     path);
}

// Border edges (one triangle: the surface is open), edges of more than two triangles (not
// manifold) and edges whose two triangles run the same way (inconsistent orientation).
struct EdgeCheck {
  std::int64_t border = 0, non_manifold = 0, inconsistent = 0;
  Vec3 first_border, first_non_manifold, first_inconsistent;
};

EdgeCheck check_edges(const Soup& s) {
  struct Use {
    int count = 0;
    int forward = 0;  // triangles running from the smaller to the larger index
  };
  std::unordered_map<std::uint64_t, Use> uses;
  uses.reserve(s.tris.size() * 2);
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      Use& u = uses[edge_key(a, b)];
      ++u.count;
      if (a < b) ++u.forward;
    }
  EdgeCheck c;
  // Walk the triangles (not the hash map) so that "first" is well defined.
  std::unordered_map<std::uint64_t, bool> reported;
  for (const auto& t : s.tris)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      const std::uint64_t key = edge_key(a, b);
      if (!reported.emplace(key, true).second) continue;
      const Use& u = uses[key];
      const Vec3 mid = 0.5 * (s.points[a] + s.points[b]);
      if (u.count == 1) {
        if (c.border++ == 0) c.first_border = mid;
      } else if (u.count > 2) {
        if (c.non_manifold++ == 0) c.first_non_manifold = mid;
      } else if (u.forward != 1) {
        if (c.inconsistent++ == 0) c.first_inconsistent = mid;
      }
    }
  return c;
}

Vec3 to_vec(const Point& p) {
  return Vec3(p.x(), p.y(), p.z());
}

Vec3 face_centroid(const SurfaceMesh& m, SurfaceMesh::Face_index f) {
  Vec3 c = Vec3::Zero();
  for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) c += to_vec(m.point(v));
  return c / 3.0;
}

// Counts the edges whose faces' normals differ by more than `angle` degrees (what
// detect_features will protect), for the report.
std::int64_t count_sharp_edges(const SurfaceMesh& m, double angle) {
  const double cos_bound = std::cos(angle * 3.14159265358979323846 / 180.0);
  std::int64_t n = 0;
  for (auto e : m.edges()) {
    const auto h = m.halfedge(e);
    if (m.is_border(e)) continue;
    const auto n1 = PMP::compute_face_normal(m.face(h), m);
    const auto n2 = PMP::compute_face_normal(m.face(m.opposite(h)), m);
    if (CGAL::to_double(n1 * n2) < cos_bound) ++n;
  }
  return n;
}

// The surface, checked and repaired, as a closed, manifold, outward-oriented CGAL mesh without
// self-intersections.
SurfaceMesh checked_surface(TriangleSurface surface, const CadMeshOptions& o,
                            const std::string& path, CadMeshReport& rep) {
  Soup s;
  s.points = std::move(surface.points);
  s.tris = std::move(surface.triangles);
  s.input_index.resize(s.tris.size());
  for (std::size_t i = 0; i < s.tris.size(); ++i) s.input_index[i] = static_cast<std::int64_t>(i);
  if (s.tris.empty()) throw InputError("empty: no triangles", path);

  drop_collapsed_and_duplicates(s, o, path, rep);

  // Topology, before anything is handed to CGAL (whose soup-to-mesh conversion needs it).
  const EdgeCheck ec = check_edges(s);
  if (ec.border > 0 || ec.non_manifold > 0) {
    std::string msg;
    if (ec.border > 0)
      msg = "surface is open: " + std::to_string(ec.border) + " border edge(s), first near " +
            fmt_point(ec.first_border) +
            " (every edge must be shared by exactly two triangles; vertices closer than " +
            fmt_num(o.merge_tolerance) + " of the bounding-box diagonal are merged)";
    if (ec.non_manifold > 0)
      msg += std::string(msg.empty() ? "" : "; ") +
             "not manifold: " + std::to_string(ec.non_manifold) +
             " edge(s) shared by more than two triangles, first near " +
             fmt_point(ec.first_non_manifold);
    throw InputError(msg, path);
  }
  if (ec.inconsistent > 0 && !o.repair)
    throw InputError("orientation is inconsistent: " + std::to_string(ec.inconsistent) +
                         " edge(s) where neighbouring triangles face opposite ways, first near " +
                         fmt_point(ec.first_inconsistent),
                     path);

  // Orientation, and vertices where separate sheets touch (orient_polygon_soup duplicates them,
  // which says the surface is not manifold there).
  std::vector<Point> pts;
  pts.reserve(s.points.size());
  for (const Vec3& x : s.points) pts.emplace_back(x[0], x[1], x[2]);
  std::vector<std::vector<std::size_t>> polys(s.tris.size());
  for (std::size_t i = 0; i < s.tris.size(); ++i)
    polys[i] = {static_cast<std::size_t>(s.tris[i][0]), static_cast<std::size_t>(s.tris[i][1]),
                static_cast<std::size_t>(s.tris[i][2])};
  const std::size_t npoints = pts.size();
  const bool manifold = PMP::orient_polygon_soup(pts, polys);
  if (!manifold || pts.size() != npoints) {
    const Vec3 where = pts.size() > npoints ? to_vec(pts[npoints]) : Vec3::Zero();
    throw InputError("not manifold: " + std::to_string(pts.size() - npoints) +
                         " vertex(es) where separate parts of the surface touch, first at " +
                         fmt_point(where),
                     path);
  }
  if (ec.inconsistent > 0)
    rep.repairs.push_back("made the orientation consistent (" + std::to_string(ec.inconsistent) +
                          " edge(s) had neighbouring triangles facing opposite ways)");

  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, mesh);
  if (mesh.number_of_faces() != polys.size() || !CGAL::is_closed(mesh))
    throw InputError("not manifold: the triangles do not form a closed surface", path);

  // Triangles of zero area that are not collapsed (three collinear corners): PMP removes them
  // by edge collapses and flips.
  const double diag = [&] {
    const auto bb = PMP::bbox(mesh);
    return std::sqrt(std::pow(bb.xmax() - bb.xmin(), 2) + std::pow(bb.ymax() - bb.ymin(), 2) +
                     std::pow(bb.zmax() - bb.zmin(), 2));
  }();
  bool renumbered = false;
  {
    std::int64_t flat = 0, first = -1;
    for (auto f : mesh.faces())
      if (PMP::is_degenerate_triangle_face(f, mesh)) {
        if (flat++ == 0) first = s.input_index[static_cast<std::size_t>(f)];
      }
    if (flat > 0) {
      const std::string what = std::to_string(flat) +
                               " triangle(s) of zero area (collinear corners; first: input "
                               "triangle " +
                               std::to_string(first) + ")";
      if (!o.repair) throw InputError("degenerate: " + what, path);
      if (!PMP::remove_degenerate_faces(mesh) || !CGAL::is_closed(mesh))
        throw InputError("degenerate: " + what + " that could not be removed", path);
      mesh.collect_garbage();
      renumbered = true;
      rep.repairs.push_back("removed " + what);
    }
  }

  // Self-intersections: Mesh_3 needs a surface that bounds a volume unambiguously.
  if (PMP::does_self_intersect(mesh)) {
    std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
    PMP::self_intersections(mesh, std::back_inserter(pairs));
    auto first = pairs.front();
    for (const auto& p : pairs)  // the smallest pair, so the message does not depend on order
      if (std::minmax(p.first, p.second) < std::minmax(first.first, first.second)) first = p;
    const auto [fa, fb] = std::minmax(first.first, first.second);
    std::string which;
    if (renumbered)
      which = "faces " + std::to_string(static_cast<std::size_t>(fa)) + " and " +
              std::to_string(static_cast<std::size_t>(fb)) + " of the repaired surface";
    else
      which = "input triangles " + std::to_string(s.input_index[static_cast<std::size_t>(fa)]) +
              " and " + std::to_string(s.input_index[static_cast<std::size_t>(fb)]);
    throw InputError(std::to_string(pairs.size()) + " pair(s) of self-intersecting faces, first " +
                         which + " near " + fmt_point(face_centroid(mesh, fa)),
                     path);
  }

  // Outward. With several shells (a hollow part) each must face away from the material, which
  // orient_to_bound_a_volume sorts out by nesting depth; one volume sign could not. (Mesh_3
  // itself decides inside by ray parity, but the reported volume and any later use of the
  // surface need the orientation right.)
  const double volume_before = PMP::volume(mesh);
  {
    auto fcc = mesh.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:cc").first;
    rep.components = static_cast<std::int64_t>(PMP::connected_components(mesh, fcc));
    mesh.remove_property_map(fcc);
  }
  if (rep.components > 1) {
    SurfaceMesh oriented = mesh;
    PMP::orient_to_bound_a_volume(oriented);
    std::int64_t flipped = 0;
    for (auto f : mesh.faces())
      flipped += mesh.target(mesh.halfedge(f)) != oriented.target(oriented.halfedge(f)) ||
                 mesh.source(mesh.halfedge(f)) != oriented.source(oriented.halfedge(f));
    if (flipped > 0) {
      if (!o.repair)
        throw InputError("orientation: " + std::to_string(flipped) +
                             " triangle(s) of nested shells face into the material",
                         path);
      mesh = std::move(oriented);
      rep.repairs.push_back("reversed " + std::to_string(flipped) +
                            " triangle(s) of nested shells to face away from the material");
    }
  } else if (volume_before < 0.0) {
    if (!o.repair)
      throw InputError("inside out: the surface's triangles face inwards (enclosed volume " +
                           fmt_num(volume_before) + ")",
                       path);
    PMP::reverse_face_orientations(mesh);
    rep.repairs.push_back("reversed the orientation: the surface was inside out");
  }
  rep.surface_volume = PMP::volume(mesh);
  rep.surface_area = PMP::area(mesh);
  rep.surface_triangles = static_cast<std::int64_t>(mesh.number_of_faces());
  if (!(rep.surface_volume > 1e-12 * diag * diag * diag))
    throw InputError(
        "degenerate: the surface encloses no volume (" + fmt_num(rep.surface_volume) + ")", path);
  return mesh;
}

}  // namespace

std::string cad_options_key(const CadMeshOptions& o) {
  std::ostringstream k;
  k.precision(17);
  k << "femdem-cad-mesher " << kCadMesherVersion << " (CGAL " << CGAL_VERSION_STR << ")"
    << "; element_size " << o.element_size << "; scale " << o.scale << "; merge_tolerance "
    << o.merge_tolerance << "; feature_angle " << o.feature_angle << "; facet_angle "
    << o.facet_angle << "; facet_distance " << o.facet_distance << "; cell_radius_edge_ratio "
    << o.cell_radius_edge_ratio << "; odt " << o.odt << "; lloyd " << o.lloyd << "; perturb "
    << o.perturb << " " << o.perturb_sliver_bound << "; exude " << o.exude << "; seed " << o.seed
    << "; repair " << o.repair;
  return k.str();
}

Tet10Mesh mesh_surface(TriangleSurface surface, const CadMeshOptions& o, const std::string& path,
                       CadMeshReport* report_out) {
  CadMeshReport rep;
  if (report_out) rep.import = report_out->import;
  if (!(o.element_size > 0.0) || !std::isfinite(o.element_size))
    throw InputError("element_size must be a positive number", path);
  const double h = o.element_size;

  auto t0 = Clock::now();
  SurfaceMesh surf = checked_surface(std::move(surface), o, path, rep);
  rep.check_seconds = seconds_since(t0);

  // A regular tetrahedron of edge h has volume h^3 / (6 sqrt 2); Delaunay meshes come out
  // about that dense.
  const double estimate = rep.surface_volume / (h * h * h / (6.0 * std::sqrt(2.0)));
  if (estimate > static_cast<double>(o.max_elements))
    throw InputError("element_size " + fmt_num(h) + " would give about " + fmt_num(estimate) +
                         " tetrahedra for a volume of " + fmt_num(rep.surface_volume) + " (limit " +
                         std::to_string(o.max_elements) + "); is element_size in m, after scale?",
                     path);
  rep.sharp_edges = count_sharp_edges(surf, o.feature_angle);

  t0 = Clock::now();
  // Everything random in Mesh_3 draws from these two generators; seeding both makes the mesh
  // a function of the input alone.
  CGAL::get_default_random() = CGAL::Random(o.seed);
  CGAL::Random rng(o.seed);
  Domain domain(surf, &rng);
  domain.detect_features(o.feature_angle);

  // Mesh_3's size bounds are radii: facet_size bounds the surface Delaunay balls (the
  // circumradius of an equilateral triangle of edge b is b / sqrt 3), cell_size the
  // circumradius of the tetrahedra (b sqrt 6 / 4 for the regular one). edge_size is the spacing
  // of the protecting balls along sharp edges, i.e. an edge length. With b = h the mean edge
  // came out at 0.82 h (sphere, cube and cylinder alike: upper bounds give shorter edges), so
  // the bounds are b = 1.2 h to make element_size the mean edge length, like the generators'.
  constexpr double kBoundPerSize = 1.2;
  const double b = kBoundPerSize * h;
  const double facet_distance = o.facet_distance > 0.0 ? o.facet_distance : h / 10.0;
  namespace P = CGAL::parameters;
  const Criteria criteria(P::edge_size = b, P::facet_angle = o.facet_angle,
                          P::facet_size = b / std::sqrt(3.0), P::facet_distance = facet_distance,
                          P::cell_radius_edge_ratio = o.cell_radius_edge_ratio,
                          P::cell_size = b * std::sqrt(6.0) / 4.0);
  // No time limits (0 = none): a time limit makes the result depend on the machine's load.
  C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(
      domain, criteria,
      o.lloyd ? P::lloyd(P::time_limit = 0, P::max_iteration_number = 10) : P::no_lloyd(),
      o.odt ? P::odt(P::time_limit = 0, P::max_iteration_number = 10) : P::no_odt(),
      o.perturb ? P::perturb(P::time_limit = 0, P::sliver_bound = o.perturb_sliver_bound)
                : P::no_perturb(),
      o.exude ? P::exude(P::time_limit = 0, P::sliver_bound = 0) : P::no_exude());

  // Tetrahedra of the complex; vertices numbered in the order the cells first use them.
  Tet10Mesh mesh;
  std::unordered_map<Tr::Vertex_handle, std::int32_t> index;
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    Tet10 el;
    for (int k = 0; k < 4; ++k) {
      const Tr::Vertex_handle v = c->vertex(k);
      auto [it, added] = index.emplace(v, static_cast<std::int32_t>(mesh.nodes.size()));
      if (added) {
        const auto& p = v->point();
        mesh.nodes.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                                CGAL::to_double(p.z()));
      }
      el[k] = it->second;
    }
    for (int k = 4; k < 10; ++k) el[k] = -1;
    if (tet_signed_volume(mesh.nodes[el[0]], mesh.nodes[el[1]], mesh.nodes[el[2]],
                          mesh.nodes[el[3]]) < 0.0)
      std::swap(el[1], el[2]);
    mesh.elements.push_back(el);
  }
  rep.tet4 = static_cast<std::int64_t>(mesh.elements.size());
  if (mesh.elements.empty())
    throw InputError("meshing gave no tetrahedra: element_size " + fmt_num(h) +
                         " is probably too large for this part (enclosed volume " +
                         fmt_num(rep.surface_volume) + ")",
                     path);
  add_mid_edge_nodes(mesh);
  rep.mesh_seconds = seconds_since(t0);

  const MeshQuality q = mesh_quality(mesh);
  if (q.bad_elements > 0)
    throw InputError("meshing gave " + std::to_string(q.bad_elements) +
                         " degenerate tetrahedra; try a smaller element_size",
                     path);
  if (report_out) *report_out = std::move(rep);
  return mesh;
}

Tet10Mesh mesh_cad_file(const std::string& path, const CadMeshOptions& o,
                        CadMeshReport* report_out) {
  CadMeshReport rep;
  const auto t0 = Clock::now();
  TriangleSurface s = import_surface(path, o.scale, o.merge_tolerance, &rep.import);
  const double import_seconds = seconds_since(t0);
  Tet10Mesh mesh = mesh_surface(std::move(s), o, path, &rep);
  rep.import_seconds = import_seconds;
  if (report_out) *report_out = std::move(rep);
  return mesh;
}

std::string format_cad_report(const CadMeshReport& r) {
  char buf[512];
  std::string s;
  std::snprintf(
      buf, sizeof buf,
      "surface: %lld triangles, %lld vertices in the file (%lld after merging), "
      "%lld shell(s), %lld sharp edge(s)\n"
      "enclosed volume %.6g, area %.6g\n",
      static_cast<long long>(r.surface_triangles), static_cast<long long>(r.import.input_vertices),
      static_cast<long long>(r.import.merged_vertices), static_cast<long long>(r.components),
      static_cast<long long>(r.sharp_edges), r.surface_volume, r.surface_area);
  s += buf;
  for (const std::string& rp : r.repairs) s += "repaired: " + rp + "\n";
  std::snprintf(buf, sizeof buf,
                "%lld tetrahedra in %.2f s (import %.2f s, checks %.2f s, meshing %.2f s)",
                static_cast<long long>(r.tet4), r.import_seconds + r.check_seconds + r.mesh_seconds,
                r.import_seconds, r.check_seconds, r.mesh_seconds);
  s += buf;
  return s;
}

}  // namespace femdem
