// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Built-in structured TET10 mesh generators (scene key `mesh = { generator = ... }`).
//
// All three build a structured grid of hexahedral cells in a parameter space, split every cell
// into 6 tetrahedra around one of its diagonals (the Kuhn / Freudenthal split), and map the
// corner AND mid-edge nodes through a smooth map to physical space. The nodes are exactly the
// points of the grid refined twice (corners, edge midpoints, face centres, cell centres), so no
// edge search is needed and the result is conforming, deterministic and fast.
//
//  - box: cells per axis n_i = max(1, round(l_i / h)); spans [0, lx] x [0, ly] x [0, lz].
//    All tetrahedra are straight; dihedral angles of a cubic cell's tets are 45, 60, 90 deg.
//  - cylinder: axis z from 0 to length. The cross-section is an "O-grid": a square of
//    2n x 2n cells, n = max(1, round(radius / h)), mapped onto the disc by concentric squares ->
//    concentric circles with equal angles along each square side (equiangular map); the map
//    is linear along rays, so radial spacing is radius / n and the circumferential spacing is
//    (pi / 4) radius / n at the rim. Along z, n_z = max(1, round(length / h)) cells.
//  - sphere: centred on the origin. A cube of 2n x 2n x 2n cells, n = max(1, round(radius /
//    h)), mapped onto the ball by concentric cubes -> concentric spheres with the equiangular
//    cubed-sphere map on each face (six blocks meeting at the centre); radial spacing radius / n.
//
// In the cylinder and sphere the diagonal of every cell runs away from the axis / centre, so
// every tetrahedron lies within one smooth patch of the map (the map has kinks on the planes
// |x| = |y| etc.); mid-edge nodes are the mapped edge midpoints, hence mid-edge nodes of
// boundary edges lie exactly on the true cylinder / sphere, and interior edges are very slightly
// curved (consistently with the map). The volume converges at the rate of quadratic geometry.
//
// Bad arguments (non-positive or non-finite sizes, more than kMaxGeneratedElements elements)
// throw InputError without a file; the message names the generator and the parameter.
#include <cstdint>

#include "elements/tet10_mesh.hpp"

namespace femdem {

inline constexpr double kMaxGeneratedElements = 2e7;

Tet10Mesh generate_box(Vec3 size, double h);
Tet10Mesh generate_cylinder(double radius, double length, double h);
Tet10Mesh generate_sphere(double radius, double h);

// Number of elements the generators would produce (no allocation; throws like them).
std::int64_t box_element_count(Vec3 size, double h);
std::int64_t cylinder_element_count(double radius, double length, double h);
std::int64_t sphere_element_count(double radius, double h);

}  // namespace femdem
