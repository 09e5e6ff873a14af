// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A ten-node tetrahedral mesh: the exchange format between mesh sources (generators, gmsh files,
// CAD meshing) and the engine.
//
// Local node order (the same as VTK_QUADRATIC_TETRA and XDMF "Tetrahedron_10", so frames are
// written without permutation):
//   0..3  corners, right-handed: (x1 - x0) x (x2 - x0) . (x3 - x0) > 0
//   4: edge 0-1   5: edge 1-2   6: edge 2-0   7: edge 0-3   8: edge 1-3   9: edge 2-3
// gmsh's order differs only in the last two (its 8 is edge 2-3, its 9 is edge 1-3).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace femdem {

using Vec3 = Eigen::Vector3d;
using Tet10 = std::array<std::int32_t, 10>;

// The two corners of each mid-edge node 4..9, in local numbering.
inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges = {
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

// The four faces as six-node triangles (3 corners then 3 mid-edge nodes: edge c0-c1, c1-c2,
// c2-c0), each ordered so that its normal (c1 - c0) x (c2 - c0) points out of the element.
inline constexpr std::array<std::array<int, 6>, 4> kTet10Faces = {{
    {0, 2, 1, 6, 5, 4},  // opposite corner 3
    {0, 1, 3, 4, 8, 7},  // opposite corner 2
    {1, 2, 3, 5, 9, 8},  // opposite corner 0
    {0, 3, 2, 7, 9, 6},  // opposite corner 1
}};

struct Tet10Mesh {
  std::vector<Vec3> nodes;
  std::vector<Tet10> elements;
};

// TET4 -> TET10 promotion, shared by every mesh source that produces linear tetrahedra (gmsh
// TET4 files, CAD meshing). Elements whose node 4 is -1 are taken as TET4 (corners 0..3 set,
// 4..9 unset): each gets one node at the midpoint of every edge, shared by all the elements
// around that edge, and reused from any complete TET10 element on the same edge. New nodes are
// appended in element order, edge order kTet10Edges, so the result is deterministic.
void add_mid_edge_nodes(Tet10Mesh& mesh);

}  // namespace femdem
