// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Penalty-potential contact between two linear tetrahedra (Munjiza & Andrews 2000; thesis
// eq. 2.66, L1805-1865, and the penalty of eq. 2.123-2.124, L3713-3760).
//
// Each tetrahedron T carries the potential phi_T(x) = 4 min_i lambda_i^T(x) (lambda_i the
// barycentric coordinates, so 4 lambda_i = 4 V_i / V of the thesis): 0 on the surface, 1 at the
// centroid. The pair's energy is
//     E = p * integral over A n B of (phi_A + phi_B) dV,
// and the nodal forces are exactly -dE/dx (24 numbers). The resultant force on B is the thesis'
// p * integral (grad phi_B - grad phi_A) dV; the nodal distribution differs from spreading that
// force density with the shape functions by a self-equilibrated term (docs/ARCHITECTURE.md,
// "Tet-tet potential contact"), which is what makes the forces conservative.
//
// Everything is computed exactly (up to round-off) by clipping: phi_T is linear on each of the
// four sub-tetrahedra (centroid + one face) where one lambda_i is the smallest, so the integrals
// reduce to volumes and first moments of those sub-tetrahedra clipped by the other tetrahedron
// (contact/tet_potential_integral.hpp, contact/tet_regions_clip.hpp). No heap allocation;
// early exits on disjoint boxes and on a separating face plane.
#include <array>

namespace femdem::contact {

// Corner coordinates of a linear tetrahedron, any orientation.
using TetCorners = std::array<std::array<double, 3>, 4>;

// Plain data (no initializers: the kernel writes every field when the pair touches, and a
// rejected pair, the common case, costs no clearing); TetPairContact c{} is all zeros.
struct TetPairContact {
  double energy;                           // E (J when p is in Pa and lengths in m)
  TetCorners force_a;                      // -dE/dx at the corners of A (N)
  TetCorners force_b;                      // -dE/dx at the corners of B; sums to minus A's
  double overlap_volume;                   // volume of A n B
  std::array<double, 3> overlap_centroid;  // centroid of A n B (where friction acts)
};

// Fills `out` for the pair (a, b) with penalty p (Pa). Returns false, leaving `out` as it was,
// when the tetrahedra do not overlap (or either one is degenerate).
bool tet_potential_contact(const TetCorners& a, const TetCorners& b, double penalty,
                           TetPairContact& out);

}  // namespace femdem::contact
