// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The armour-unit shapes at unit size, as exact CGAL surfaces: small vector helpers, convex
// pieces (exact hulls) and their exact union, and the tetrapod, dolos, cube and V-Cross
// (proportions and sources: main.cpp). Included by main.cpp only (one translation unit: CGAL's
// headers are slow to compile).
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

namespace armour_units {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace PMP = CGAL::Polygon_mesh_processing;
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<Exact::Point_3>;
using InexactMesh = CGAL::Surface_mesh<Inexact::Point_3>;

// Thrown for a bad combination of options (exit 2), as opposed to a geometry failure (exit 1).
struct BadOption : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Vec {
  double x = 0, y = 0, z = 0;
};
inline Vec operator+(Vec a, Vec b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec operator-(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec operator*(double s, Vec a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec unit(Vec a) {
  return (1.0 / std::sqrt(dot(a, a))) * a;
}

// A convex piece is given by its corner points; the exact hull makes a closed, outward-oriented
// triangle mesh of it whatever the rounding of the points (a cap whose points are not exactly
// coplanar just gets a slightly folded, still convex, triangulation).
inline ExactMesh convex_piece(const std::vector<Vec>& pts) {
  std::vector<Exact::Point_3> exact;
  exact.reserve(pts.size());
  for (const Vec& p : pts) exact.emplace_back(p.x, p.y, p.z);
  ExactMesh mesh;
  CGAL::convex_hull_3(exact.begin(), exact.end(), mesh);
  return mesh;
}

inline ExactMesh unite(std::vector<ExactMesh> pieces) {
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
inline void add_polygon(std::vector<Vec>& pts, Vec c, Vec e1, Vec e2, double rc, int n,
                        double phase) {
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
inline void add_octagon(std::vector<Vec>& pts, Vec c, Vec e1, Vec e2, double w) {
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

inline double tetrapod_leg_length(const TetrapodParams& p) {
  // Height = top tip face (F above the centre) down to the lowest point of a lower tip face:
  // lower legs point 1/3 below the horizontal plane through the centre (cos 109.47 deg = -1/3)
  // and their tip disc reaches a further (A/2) sin(70.53 deg) = A sqrt(2)/3 down.
  return 0.75 * (1.0 - p.tip_diameter * std::numbers::sqrt2 / 3.0);
}

inline ExactMesh tetrapod(const TetrapodParams& p) {
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

inline ExactMesh dolos(const DolosParams& p) {
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

inline std::vector<Vec> box(Vec lo, Vec hi) {
  std::vector<Vec> pts;
  for (int i = 0; i < 8; ++i)
    pts.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  return pts;
}

inline ExactMesh cube() {
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

}  // namespace armour_units
