// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Geometry and quality measures of tetrahedra, and a quality summary of a whole TET10 mesh.
//
// Conventions:
//  - A tetrahedron is given by its 4 corners a, b, c, d in the local order of tet10_mesh.hpp;
//    its signed volume (b - a) x (c - a) . (d - a) / 6 is positive when right-handed.
//  - Face i is the face opposite corner i.
//  - Angles are in degrees.
//  - Aspect ratio: (longest edge) / (smallest altitude) * sqrt(2/3). It is 1 for the regular
//    tetrahedron and grows without bound for slivers, needles, wedges and caps alike.
//  - Scaled Jacobian of a TET10: det J of the quadratic map at the 4 Gauss points (a =
//    0.5854101966249685, b = 0.1381966011250105) and at the 4 corners, divided by det J of the
//    straight corner tetrahedron (6 V). It is 1 for straight-sided elements with mid-edge nodes
//    at the edge midpoints; <= 0 means the element is folded.
#include <array>
#include <cstdint>
#include <string>

#include "elements/tet10_mesh.hpp"

namespace femdem {

double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Areas of the faces opposite corners 0..3.
std::array<double, 4> tet_face_areas(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Smallest altitude = 3 |V| / (largest face area); 0 for a degenerate tetrahedron.
double tet_min_altitude(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The six interior dihedral angles (degrees), at edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3 (the
// order of kTet10Edges). 0 (or 180) for a degenerate tetrahedron.
std::array<double, 6> tet_dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d);

// (longest edge) / (smallest altitude) * sqrt(2/3): 1 for the regular tetrahedron, infinity
// for a degenerate one.
double tet_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Minimum over the 4 Gauss points and 4 corners of det J / (6 V_corner) for element e.
// Returns -infinity if the corner tetrahedron has zero volume.
double tet10_min_scaled_jacobian(const Tet10Mesh& mesh, std::size_t e);

// Volume of element e with its quadratic (possibly curved) geometry: det J integrated with a
// rule exact for cubics, so exact for any TET10.
double tet10_volume(const Tet10Mesh& mesh, std::size_t e);

struct MeshQuality {
  std::int64_t elements = 0;
  std::int64_t nodes = 0;
  double min_dihedral_deg = 0.0;  // over all elements' corner tetrahedra
  double max_dihedral_deg = 0.0;
  double max_aspect_ratio = 0.0;  // worst (largest) aspect ratio, see above
  // The tails that matter more than the single worst element in a generated mesh: 5 % of the
  // elements have their smallest dihedral angle below p05_min_dihedral_deg, and 5 % an aspect
  // ratio above p95_aspect_ratio (nearest-rank percentiles over elements).
  double p05_min_dihedral_deg = 0.0;
  double p95_aspect_ratio = 0.0;
  double mean_edge = 0.0;   // mean corner-to-corner edge length over the elements' 6 edges
  double min_volume = 0.0;  // signed volume of the corner tetrahedron
  double max_volume = 0.0;
  double total_volume = 0.0;  // sum of tet10_volume (curved geometry)
  double min_scaled_jacobian = 0.0;
  double min_edge = 0.0;  // shortest and longest corner-to-corner edge
  double max_edge = 0.0;
  // Elements whose corner volume is <= 1e-12 * (mean |volume|) or whose scaled Jacobian is
  // <= 0 anywhere it is sampled.
  std::int64_t bad_elements = 0;
  std::int64_t first_bad_element = -1;  // index into mesh.elements, -1 if none
};

MeshQuality mesh_quality(const Tet10Mesh& mesh);

// A few human-readable lines, e.g. for `femdem check`.
std::string format_mesh_quality(const MeshQuality& q);

}  // namespace femdem
