// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The written surface of an armour unit: the exact union turned into an inexact mesh without
// short edges, rounded to the single-precision coordinates STL stores, put in canonical order,
// checked as a closed solid in that rounded form, and written as binary STL, OBJ or OFF.
// Included by main.cpp only.
#include "tools/armour_units/unit_shapes.hpp"

namespace armour_units {

// ---- the written surface and its checks ----

struct Surface {
  std::vector<std::array<float, 3>> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

// The exact union has edges far shorter than anything the unit needs: where the facet edges of
// one leg cross the intersection curve with another leg a fraction of a millimetre from those of
// the other leg (H/10^5 on the tetrapod). A volume mesher that protects the sharp intersection
// curves would put tiny elements there, and a tiny element sets the explicit time step. So edges
// shorter than min_edge (a fraction of the unit's size) are collapsed to their midpoints, never
// flipping a face normal; this moves the surface by at most min_edge / 2. The checks after
// rounding still apply to the result.
inline InexactMesh to_inexact_without_short_edges(const ExactMesh& exact, double min_edge) {
  InexactMesh mesh;
  std::map<ExactMesh::Vertex_index, InexactMesh::Vertex_index> index;
  for (auto v : exact.vertices()) {
    const auto& q = exact.point(v);
    index[v] = mesh.add_vertex(
        Inexact::Point_3(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())));
  }
  for (auto f : exact.faces()) {
    std::vector<InexactMesh::Vertex_index> vs;
    for (auto v : CGAL::vertices_around_face(exact.halfedge(f), exact)) vs.push_back(index.at(v));
    if (mesh.add_face(vs) == InexactMesh::null_face())
      throw std::runtime_error("the exact surface is not a manifold polygon mesh");
  }
  if (min_edge > 0) {
    namespace SMS = CGAL::Surface_mesh_simplification;
    SMS::Edge_length_stop_predicate<double> stop(min_edge);
    SMS::Bounded_normal_change_placement<SMS::Midpoint_placement<InexactMesh>> placement;
    SMS::edge_collapse(
        mesh, stop,
        CGAL::parameters::get_cost(SMS::Edge_length_cost<InexactMesh>()).get_placement(placement));
    mesh.collect_garbage();
  }
  return mesh;
}

// Rounds the surface to the float coordinates of the files: moved so that its lowest point is at
// z = 0 and scaled so that its height is exactly `height` (every size option is the unit's
// height: tetrapod H, dolos C, cube edge, V-Cross span).
inline Surface round_to_float(const InexactMesh& mesh, double height) {
  double zlo = HUGE_VAL, zhi = -HUGE_VAL;
  for (auto v : mesh.vertices()) {
    const double z = mesh.point(v).z();
    zlo = std::min(zlo, z), zhi = std::max(zhi, z);
  }
  const double factor = height / (zhi - zlo);
  Surface out;
  std::map<InexactMesh::Vertex_index, std::size_t> index;
  for (auto v : mesh.vertices()) {
    const auto& q = mesh.point(v);
    index[v] = out.points.size();
    out.points.push_back({static_cast<float>(factor * q.x()), static_cast<float>(factor * q.y()),
                          static_cast<float>(factor * (q.z() - zlo))});
  }
  for (auto f : mesh.faces()) {
    std::array<std::size_t, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) throw std::runtime_error("union produced a face that is not a triangle");
      t[k++] = index.at(v);
    }
    if (k != 3) throw std::runtime_error("union produced a face that is not a triangle");
    out.triangles.push_back(t);
  }
  return out;
}

// CGAL hands the union's vertices and faces back in an order that depends on heap addresses
// (the same geometry comes out in a different order when, say, the output path is longer), so
// the surface is put into a canonical order: vertices sorted by coordinates, each triangle
// starting at its lowest vertex, triangles sorted. The same geometry then gives the same file.
inline void canonicalize(Surface& s) {
  std::vector<std::size_t> order(s.points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return s.points[a] < s.points[b]; });
  std::vector<std::size_t> rank(order.size());
  std::vector<std::array<float, 3>> points(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) rank[order[i]] = i, points[i] = s.points[order[i]];
  s.points = std::move(points);
  for (auto& t : s.triangles) {
    for (auto& v : t) v = rank[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(s.triangles.begin(), s.triangles.end());
}

inline double signed_volume(const Surface& s) {
  double v = 0;
  for (const auto& t : s.triangles) {
    const auto &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    v += (double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
          double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
          double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0])) /
         6.0;
  }
  return v;
}

// Everything a solid mesher downstream relies on, checked on the rounded coordinates actually
// written. Throws with the first problem found.
inline void check_solid(const Surface& s) {
  // Distinct vertices must stay distinct after rounding, or the file's topology changes.
  std::vector<std::array<float, 3>> sorted = s.points;
  std::sort(sorted.begin(), sorted.end());
  if (auto d = std::adjacent_find(sorted.begin(), sorted.end()); d != sorted.end())
    throw std::runtime_error("two vertices coincide after rounding to float, at (" +
                             std::to_string((*d)[0]) + ", " + std::to_string((*d)[1]) + ", " +
                             std::to_string((*d)[2]) + ")");
  // Closed and consistently oriented: each directed edge once, and its reverse once.
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    if (n != 1) throw std::runtime_error("an edge is used twice in the same direction");
    if (!directed.count({e.second, e.first}))
      throw std::runtime_error("an edge has no opposite half-edge (surface not closed)");
  }
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : s.triangles) polygons.push_back({t[0], t[1], t[2]});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw std::runtime_error("the surface has a non-manifold vertex");
  std::vector<Inexact::Point_3> pts;
  for (const auto& p : s.points) pts.emplace_back(p[0], p[1], p[2]);
  InexactMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(pts, polygons, mesh);
  for (auto f : mesh.faces())
    if (PMP::is_degenerate_triangle_face(f, mesh))
      throw std::runtime_error("a triangle is degenerate after rounding to float");
  auto fcc = mesh.add_property_map<InexactMesh::Face_index, std::size_t>("f:cc", 0).first;
  if (PMP::connected_components(mesh, fcc) != 1)
    throw std::runtime_error("the surface has more than one connected component");
  if (PMP::does_self_intersect(mesh)) throw std::runtime_error("the surface self-intersects");
  if (!(signed_volume(s) > 0))
    throw std::runtime_error("the enclosed volume is not positive (inward orientation)");
}

inline std::array<float, 3> normal_of(const Surface& s, const std::array<std::size_t, 3>& t) {
  const auto &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
  const Vec u{double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
  const Vec w{double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
  const Vec n = unit(cross(u, w));
  return {float(n.x), float(n.y), float(n.z)};
}

inline void write_stl(const Surface& s, const std::string& path, const std::string& title) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot open " + path + " for writing");
  // Fixed header (no date or version), so identical geometry gives identical bytes.
  char header[80] = {};
  std::snprintf(header, sizeof header, "femdem armour_units %s", title.c_str());
  out.write(header, 80);
  const auto n = static_cast<std::uint32_t>(s.triangles.size());
  static_assert(std::endian::native == std::endian::little, "binary STL is little-endian");
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : s.triangles) {
    const auto normal = normal_of(s, t);
    out.write(reinterpret_cast<const char*>(normal.data()), 12);
    for (int k = 0; k < 3; ++k) out.write(reinterpret_cast<const char*>(s.points[t[k]].data()), 12);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

inline void write_obj_or_off(const Surface& s, const std::string& path, bool off,
                             const std::string& title) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open " + path + " for writing");
  char buf[128];
  if (off) {
    out << "OFF\n# femdem armour_units " << title << "\n"
        << s.points.size() << " " << s.triangles.size() << " 0\n";
  } else {
    out << "# femdem armour_units " << title << "\n";
  }
  for (const auto& p : s.points) {
    // %.9g round-trips a float exactly, so OBJ/OFF carry the same coordinates as the STL.
    std::snprintf(buf, sizeof buf, "%s%.9g %.9g %.9g\n", off ? "" : "v ", p[0], p[1], p[2]);
    out << buf;
  }
  for (const auto& t : s.triangles) {
    if (off)
      out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    else
      out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  }
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace armour_units
