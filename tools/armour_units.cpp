// SPDX-License-Identifier: GPL-3.0-or-later
// armour_units: writes closed triangle surfaces (binary STL, OBJ or OFF) of concrete armour units
// from their published proportions, for the CAD-import path of femdem scenes.
//
//   armour_units tetrapod -o tetrapod.stl [--size H | --mass KG] [--scale F] [shape options]
//
// Shapes and the proportions used (see scenes/meshes/README.md and docs/SCENES.md):
//  - tetrapod (Danel, Sogreah, 1950s). Size = unit height H, resting on three legs. Proportions
//    from the tetrapod specification drawing of the Shore Protection Manual (CERC 1984, vol. II,
//    ch. 7) and Hudson (1974, WES MP H-74-2): leg tip diameter A = 0.302 H, leg length from the
//    centre to the tip face F = 0.644 H, the leg diameter D = 0.470 H at C = 0.477 H from the tip,
//    the truncated cone continued to the centre; volume 0.280 H^3 (how this reading of the drawing
//    was checked: scenes/meshes/README.md). We take A, D and C as given and derive F from H so
//    that the height is exactly H: F = 3/4 (H - A sqrt(2)/3) = 0.643 H.
//  - dolos (Merrifield, East London, 1963). Size = overall length C (the unit fits a C x C x C
//    box). A straight shank of regular octagonal section, across-flats r C (waist ratio r,
//    0.32-0.34 as published), with a fluke of length C at each end, at right angles to the shank
//    and to each other. The flukes are octagonal too, of width r C where they meet the shank,
//    tapering linearly from the shank's faces to a tip width t C. t is not fixed by r alone; the
//    default t = 0.18 is chosen so that r = 0.32 gives the published volume of about 0.16 C^3
//    (SPM 1984).
//  - cube (plain concrete cube). Size = edge length.
//  - vcross (the idealised cruciform "V-Cross" of Xiang et al. 2009 and the thesis, section 6.3.1).
//    Two square-section bars (arm width a = 1.26 m) crossing at mid-length in one plane, one bar
//    vertical (the "main body", the impact leg at the bottom), one horizontal. Size = span S (the
//    length of each bar). The notes give only a and the mass (~30 t at 2340 kg/m3, so 12.82 m3);
//    V = 2 a^2 S - a^3 then gives S = (V + a^3) / (2 a^2) = 4.67 m.
//
// The tetrapod and the dolos are unions of convex pieces (frustums with N facets, octagonal
// prisms). Each piece is built as an exact convex hull and the pieces are united with CGAL's
// corefinement in the exact-constructions kernel, so the union itself is exact; edges shorter
// than --min-edge are then collapsed. The cube and the V-Cross are written directly. The result
// is rounded to the single-precision coordinates that STL stores, put in a canonical order and
// checked in that rounded form: closed, every edge shared by exactly two faces in opposite
// directions, manifold vertices, one component, no degenerate face, no self-intersection,
// positive volume. A surface that fails is not written (exit 1).
//
// Placement: z is up; the unit rests with its lowest point on z = 0 and its vertical axis on
// x = y = 0 (tetrapod: one leg up, three down, one lower leg towards +x; dolos: shank along x,
// fluke at x < 0 along y, fluke at x > 0 along z; vcross: main body along z, cross bar along x).
//
// Exit codes: 0 written, 2 bad option, 1 geometry check or write failed.

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/convex_hull_3.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<Exact::Point_3>;
using InexactMesh = CGAL::Surface_mesh<Inexact::Point_3>;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

// Thrown for a bad combination of options (exit 2), as opposed to a geometry failure (exit 1).
struct BadOption : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Vec {
  double x = 0, y = 0, z = 0;
};
Vec operator+(Vec a, Vec b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec operator-(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec operator*(double s, Vec a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec unit(Vec a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}

// A convex piece is given by its corner points; the exact hull makes a closed, outward-oriented
// triangle mesh of it whatever the rounding of the points (a cap whose points are not exactly
// coplanar just gets a slightly folded, still convex, triangulation).
ExactMesh convex_piece(const std::vector<Vec>& pts) {
  std::vector<Exact::Point_3> exact;
  exact.reserve(pts.size());
  for (const Vec& p : pts) exact.emplace_back(p.x, p.y, p.z);
  ExactMesh mesh;
  CGAL::convex_hull_3(exact.begin(), exact.end(), mesh);
  return mesh;
}

ExactMesh unite(std::vector<ExactMesh> pieces) {
  ExactMesh acc = std::move(pieces.front());
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    if (!PMP::corefine_and_compute_union(acc, pieces[i], acc))
      throw std::runtime_error("corefinement union of piece " + std::to_string(i) +
                               " is not manifold");
  }
  return acc;
}

// Regular polygon of n corners, circumradius rc, centred at c in the plane spanned by the unit
// vectors e1, e2; the first corner lies at angle phase from e1.
void add_polygon(std::vector<Vec>& pts, Vec c, Vec e1, Vec e2, double rc, int n, double phase) {
  for (int k = 0; k < n; ++k) {
    const double a = phase + 2.0 * std::numbers::pi * k / n;
    pts.push_back(c + rc * std::cos(a) * e1 + rc * std::sin(a) * e2);
  }
}

// Regular octagon with across-flats width w, flats facing +-e1, +-e2 and the diagonals. The
// corners are written as (+-a, +-b) and (+-b, +-a) rather than through sin/cos, so that opposite
// and axis-facing flats are exactly planar and symmetric: the corners of a flat are then exactly
// coplanar with the matching flat of a neighbouring piece, instead of a last-bit fold that the
// exact union would turn into slivers far below the float resolution of the file.
void add_octagon(std::vector<Vec>& pts, Vec c, Vec e1, Vec e2, double w) {
  const double a = 0.5 * w, b = a * (std::numbers::sqrt2 - 1.0);  // tan(22.5 deg) = sqrt2 - 1
  const double uv[8][2] = {{a, b}, {b, a}, {-b, a}, {-a, b}, {-a, -b}, {-b, -a}, {b, -a}, {a, -b}};
  for (const auto& q : uv) pts.push_back(c + q[0] * e1 + q[1] * e2);
}

// ---- shapes, built at unit size (the size option scales them afterwards) ----

struct TetrapodParams {
  double tip_diameter = 0.302;                     // A / H
  double mid_diameter = 0.470;                     // D / H, at mid_from_tip from the tip face
  double mid_from_tip = 0.477;                     // C / H
  int facets = 48;                                 // sides of each truncated cone
  std::vector<double> phases{0.5, 0.1, 0.2, 0.3};  // turn of each leg's facets, in facets
};

double tetrapod_leg_length(const TetrapodParams& p) {
  // Height = top tip face (F above the centre) down to the lowest point of a lower tip face:
  // lower legs point 1/3 below the horizontal plane through the centre (cos 109.47 deg = -1/3)
  // and their tip disc reaches a further (A/2) sin(70.53 deg) = A sqrt(2)/3 down.
  return 0.75 * (1.0 - p.tip_diameter * std::numbers::sqrt2 / 3.0);
}

ExactMesh tetrapod(const TetrapodParams& p) {
  const double F = tetrapod_leg_length(p);
  const double r_tip = 0.5 * p.tip_diameter;
  const double taper = 0.5 * (p.mid_diameter - p.tip_diameter) / p.mid_from_tip;
  const double r_centre = r_tip + taper * F;
  if (F <= 0 || r_centre <= 0) throw BadOption("tetrapod proportions give no legs");
  const Vec centre{0, 0, F / 3.0 + p.tip_diameter * std::numbers::sqrt2 / 3.0};
  const double s = 2.0 * std::numbers::sqrt2 / 3.0;  // sin of the lower legs' angle to vertical
  std::vector<Vec> dirs{{0, 0, 1}};
  for (int k = 0; k < 3; ++k) {
    const double psi = 2.0 * std::numbers::pi * k / 3.0;
    dirs.push_back({s * std::cos(psi), s * std::sin(psi), -1.0 / 3.0});
  }
  // The facets of the four legs are turned by different fractions of a facet. With identical
  // phases each pair of legs would be exact mirror images, their facet edges would cross the
  // (planar) intersection curve in coincident pairs, and the exact union would put vertices a
  // rounding error apart. Pairwise sums of the lower legs' fractions stay away from whole numbers
  // for the same reason. The unit is rescaled to its exact height afterwards (round_to_float),
  // so the phases do not change H.
  std::vector<ExactMesh> legs;
  for (int k = 0; k < 4; ++k) {
    const Vec d = dirs[k];
    const Vec e1 = d.z > 0.5 ? Vec{1, 0, 0} : unit(Vec{0, 0, -1} - (-d.z) * d);  // down the leg
    const Vec e2 = cross(d, e1);
    const double a0 = 2.0 * std::numbers::pi / p.facets * p.phases.at(k);
    std::vector<Vec> pts;
    add_polygon(pts, centre, e1, e2, r_centre, p.facets, a0);
    add_polygon(pts, centre + F * d, e1, e2, r_tip, p.facets, a0);
    legs.push_back(convex_piece(pts));
  }
  return unite(std::move(legs));
}

struct DolosParams {
  double waist = 0.32;      // r: shank across-flats / C
  double fluke_tip = 0.18;  // fluke tip across-flats / C
};

ExactMesh dolos(const DolosParams& p) {
  const double B = p.waist, T = p.fluke_tip;
  const double L = 0.5 - 0.5 * B;  // fluke axes at x = +-L, so the flukes' outer faces are at +-1/2
  const Vec ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  const Vec o{0, 0, 0.5};  // centre of the C x C x C box, so the unit rests on z = 0
  std::vector<Vec> shank;
  add_octagon(shank, o + Vec{-L, 0, 0}, ey, ez, B);
  add_octagon(shank, o + Vec{L, 0, 0}, ey, ez, B);
  // Each fluke is one convex piece: full width B where the shank meets it (|s| <= B/2, so the
  // shank's flats run flush into the fluke's), tapering linearly to width T at the tips.
  std::vector<Vec> fluke_y, fluke_z;
  for (double sgn : {-1.0, 1.0}) {
    add_octagon(fluke_y, o + Vec{-L, 0.5 * sgn, 0}, ez, ex, T);
    add_octagon(fluke_z, o + Vec{L, 0, 0.5 * sgn}, ex, ey, T);
    add_octagon(fluke_y, o + Vec{-L, 0.5 * B * sgn, 0}, ez, ex, B);
    add_octagon(fluke_z, o + Vec{L, 0, 0.5 * B * sgn}, ex, ey, B);
  }
  std::vector<ExactMesh> pieces;
  pieces.push_back(convex_piece(shank));
  pieces.push_back(convex_piece(fluke_y));
  pieces.push_back(convex_piece(fluke_z));
  return unite(std::move(pieces));
}

std::vector<Vec> box(Vec lo, Vec hi) {
  std::vector<Vec> pts;
  for (int i = 0; i < 8; ++i)
    pts.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  return pts;
}

ExactMesh cube() {
  return convex_piece(box({-0.5, -0.5, 0}, {0.5, 0.5, 1}));
}

// The V-Cross is built directly rather than as a union of two boxes: the boxes share two planes
// and their triangulations cross on the intersection lines in coincident points, which CGAL's
// corefinement (5.5) returns as duplicated vertices. The cross profile in the x-z plane is
// extruded along y; each cap is split into five rectangles (four arms and the centre square)
// whose corners are all profile corners, so the caps are conforming.
ExactMesh vcross(double arm) {  // arm = a / S
  const double h = 0.5 * arm;
  const double prof[12][2] = {{-h, 0},        {h, 0},          {h, 0.5 - h},    {0.5, 0.5 - h},
                              {0.5, 0.5 + h}, {h, 0.5 + h},    {h, 1},          {-h, 1},
                              {-h, 0.5 + h},  {-0.5, 0.5 + h}, {-0.5, 0.5 - h}, {-h, 0.5 - h}};
  std::vector<Exact::Point_3> pts;
  for (double y : {-h, h})
    for (const auto& q : prof) pts.emplace_back(q[0], y, q[1]);
  // Rectangles listed counter-clockwise in (x, z), i.e. facing -y: the y = -h cap as is.
  const int rects[5][4] = {
      {0, 1, 2, 11}, {2, 3, 4, 5}, {5, 6, 7, 8}, {8, 9, 10, 11}, {11, 2, 5, 8}};
  std::vector<std::vector<std::size_t>> tris;
  for (const auto& r : rects) {
    tris.push_back({std::size_t(r[0]), std::size_t(r[1]), std::size_t(r[2])});
    tris.push_back({std::size_t(r[0]), std::size_t(r[2]), std::size_t(r[3])});
    tris.push_back({std::size_t(r[2] + 12), std::size_t(r[1] + 12), std::size_t(r[0] + 12)});
    tris.push_back({std::size_t(r[3] + 12), std::size_t(r[2] + 12), std::size_t(r[0] + 12)});
  }
  for (std::size_t i = 0; i < 12; ++i) {  // sides: profile edge i -> i+1 reversed
    const std::size_t j = (i + 1) % 12;
    tris.push_back({j, i, i + 12});
    tris.push_back({j, i + 12, j + 12});
  }
  ExactMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(pts, tris, mesh);
  return mesh;
}

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
InexactMesh to_inexact_without_short_edges(const ExactMesh& exact, double min_edge) {
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
Surface round_to_float(const InexactMesh& mesh, double height) {
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
void canonicalize(Surface& s) {
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

double signed_volume(const Surface& s) {
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
void check_solid(const Surface& s) {
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

std::array<float, 3> normal_of(const Surface& s, const std::array<std::size_t, 3>& t) {
  const auto &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
  const Vec u{double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
  const Vec w{double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
  const Vec n = unit(cross(u, w));
  return {float(n.x), float(n.y), float(n.z)};
}

void write_stl(const Surface& s, const std::string& path, const std::string& title) {
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

void write_obj_or_off(const Surface& s, const std::string& path, bool off,
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

struct Defaults {
  double size;  // m
  const char* size_meaning;
};

const std::map<std::string, Defaults> kShapes{
    {"tetrapod", {2.0, "unit height H"}},
    {"dolos", {2.5, "overall length C"}},
    {"cube", {1.4, "edge length"}},
    {"vcross", {4.67, "span S of each bar"}},
};

}  // namespace

int main(int argc, char** argv) {
  // CGAL's default random generator is seeded from the clock and the hull construction draws
  // from it; a fixed seed makes the output the same file on every run (the shipped meshes are
  // compared against fresh output in the tests).
  CGAL::get_default_random() = CGAL::Random(0);
  CLI::App app{
      "Write a closed triangle surface of a concrete armour unit (tetrapod, dolos, cube, vcross)\n"
      "from its published proportions. Lengths in metres; z up, resting on z = 0."};
  std::string shape, output;
  double size = 0, mass = 0, density = 2340, scale = 1, arm = 1.26, min_edge = 0.005;
  TetrapodParams tp;
  DolosParams dp;
  std::map<std::string, std::vector<CLI::Option*>> shape_options;  // options of one shape only
  app.add_option("shape", shape, "tetrapod | dolos | cube | vcross")->required();
  app.add_option("-o,--output", output, "output file: .stl (binary), .obj or .off")->required();
  auto* size_opt = app.add_option(
      "--size", size,
      "characteristic size in m: tetrapod height H (default 2.0), dolos length C (2.5), cube edge "
      "(1.4), vcross span S (4.67)");
  auto* mass_opt = app.add_option("--mass", mass, "size the unit to this mass in kg instead");
  mass_opt->excludes(size_opt);
  app.add_option("--density", density, "density in kg/m3 for --mass and the report")
      ->capture_default_str();
  app.add_option("--scale", scale, "multiply every length by this (e.g. a model scale)")
      ->capture_default_str();
  shape_options["tetrapod"].push_back(
      app.add_option("--tip-diameter", tp.tip_diameter, "tetrapod leg tip diameter A / H")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--mid-diameter", tp.mid_diameter,
                     "tetrapod leg diameter D / H at --mid-from-tip")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--mid-from-tip", tp.mid_from_tip, "tetrapod distance C / H of D from the tip")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option(
             "--leg-phases", tp.phases,
             "tetrapod: turn of each leg's facets (top, then the three lower legs), in facets")
          ->expected(4)
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--facets", tp.facets, "tetrapod: sides of each leg's cone")
          ->capture_default_str());
  shape_options["dolos"].push_back(
      app.add_option("--waist", dp.waist, "dolos waist ratio r (shank width / C)")
          ->capture_default_str());
  shape_options["dolos"].push_back(
      app.add_option("--fluke-tip", dp.fluke_tip, "dolos fluke tip width / C")
          ->capture_default_str());
  app.add_option("--min-edge", min_edge,
                 "collapse edges shorter than this fraction of the size (0: keep the exact union)")
      ->capture_default_str();
  shape_options["vcross"].push_back(
      app.add_option("--arm", arm, "vcross arm width a in m at the default span (scales with size)")
          ->capture_default_str());
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << e.what() << "\nRun with --help for the options.\n";
    return kExitBadInput;
  }

  try {
    const auto it = kShapes.find(shape);
    if (it == kShapes.end())
      throw BadOption("unknown shape '" + shape + "' (tetrapod, dolos, cube, vcross)");
    for (const auto& [owner, options] : shape_options)
      for (const CLI::Option* o : options)
        if (owner != shape && !o->empty())
          throw BadOption(o->get_name() + " applies to " + owner + " only, not to " + shape);
    auto positive = [](double v, const char* what) {
      if (!(std::isfinite(v) && v > 0)) throw BadOption(std::string(what) + " must be > 0");
    };
    positive(density, "--density");
    positive(scale, "--scale");
    if (!size_opt->empty()) positive(size, "--size");
    if (!mass_opt->empty()) positive(mass, "--mass");
    const std::string ext = std::filesystem::path(output).extension().string();
    if (ext != ".stl" && ext != ".obj" && ext != ".off")
      throw BadOption("output '" + output + "' must end in .stl, .obj or .off");

    ExactMesh mesh;
    std::string params;
    const double default_size = it->second.size;
    if (shape == "tetrapod") {
      if (!(tp.tip_diameter > 0 && tp.tip_diameter < tp.mid_diameter && tp.mid_diameter < 1 &&
            tp.mid_from_tip > 0 && tp.mid_from_tip < 1))
        throw BadOption(
            "tetrapod needs 0 < --tip-diameter < --mid-diameter < 1, 0 < --mid-from-tip < 1");
      if (tp.facets < 8 || tp.facets > 256 || tp.facets % 2 != 0)
        throw BadOption("--facets must be an even number from 8 to 256");
      if (tetrapod_leg_length(tp) <= tp.mid_from_tip)
        throw BadOption("tetrapod --mid-from-tip must be shorter than the leg");
      mesh = tetrapod(tp);
      params = "A/H=" + std::to_string(tp.tip_diameter) +
               " D/H=" + std::to_string(tp.mid_diameter) +
               " C/H=" + std::to_string(tp.mid_from_tip) + " N=" + std::to_string(tp.facets);
    } else if (shape == "dolos") {
      if (!(dp.waist >= 0.2 && dp.waist <= 0.5))
        throw BadOption("--waist must be in [0.2, 0.5] (published dolosse: 0.32 to 0.42)");
      if (!(dp.fluke_tip > 0 && dp.fluke_tip <= dp.waist))
        throw BadOption("--fluke-tip must be in (0, --waist]");
      mesh = dolos(dp);
      params = "r=" + std::to_string(dp.waist) + " t=" + std::to_string(dp.fluke_tip);
    } else if (shape == "cube") {
      mesh = cube();
    } else {
      positive(arm, "--arm");
      if (!(arm < 0.5 * default_size))
        throw BadOption("--arm must be less than half the default span (4.67 m)");
      mesh = vcross(arm / default_size);
      params = "a/S=" + std::to_string(arm / default_size);
    }

    if (!(min_edge >= 0 && min_edge <= 0.05)) throw BadOption("--min-edge must be in [0, 0.05]");
    const InexactMesh clean = to_inexact_without_short_edges(mesh, min_edge);

    // Size: given, or from the mass through the unit-size volume (the shape is exact up to
    // scaling, so the volume scales with the cube of the size).
    double length = size_opt->empty() ? default_size : size;
    if (!mass_opt->empty()) {
      const double unit_volume = signed_volume(round_to_float(clean, 1.0));
      length = std::cbrt(mass / density / unit_volume);
    }
    length *= scale;
    Surface surface = round_to_float(clean, length);
    canonicalize(surface);
    check_solid(surface);

    const std::string title = shape + " size=" + std::to_string(length) + "m " + params;
    if (ext == ".stl")
      write_stl(surface, output, title);
    else
      write_obj_or_off(surface, output, ext == ".off", title);

    std::array<float, 3> lo = surface.points.front(), hi = lo;
    for (const auto& p : surface.points)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const double volume = signed_volume(surface);
    std::printf("shape      %s (%s %.6g m) %s\n", shape.c_str(), it->second.size_meaning, length,
                params.c_str());
    std::printf("file       %s\n", output.c_str());
    std::printf("triangles  %zu\nvertices   %zu\n", surface.triangles.size(),
                surface.points.size());
    std::printf("volume     %.6g m3 (%.6g size^3)\n", volume, volume / std::pow(length, 3));
    std::printf("mass       %.6g kg at %g kg/m3\n", volume * density, density);
    double min_edge = HUGE_VAL;
    for (const auto& t : surface.triangles)
      for (int k = 0; k < 3; ++k) {
        const auto &a = surface.points[t[k]], &b = surface.points[t[(k + 1) % 3]];
        min_edge = std::min(
            min_edge, std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]));
      }
    std::printf("min edge   %.3g m\n", min_edge);
    std::printf("bbox       [%.6g, %.6g] x [%.6g, %.6g] x [%.6g, %.6g] m\n", lo[0], hi[0], lo[1],
                hi[1], lo[2], hi[2]);
    std::printf("checks     closed, oriented, manifold, one component, no self-intersection\n");
    return kExitOk;
  } catch (const BadOption& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
}
