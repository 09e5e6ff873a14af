// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The SIMD element update: internal forces, stresses, energies and the Gauss-point history of
// TET10 elements two at a time (their 8 Gauss points as the lanes of one pack), for the
// instruction set of the machine it runs on (Google Highway's dynamic dispatch: AVX-512, AVX2,
// or portable scalar code, chosen once at run time). The same physics as the scalar kernel
// of engine/element_kernel.hpp, which stays the reference its tests compare with (to 1e-12):
// the same F-bar forms, the same return mappings (materials/lanes/), the eigen-solver of
// materials/symmetric_eigen3.hpp without branches.
//
// Gradients. A straight-sided element (all GCC/CAD/generated meshes: mid-edge nodes at the
// midpoints) has a constant reference Jacobian J0, so dN_a/dX = dN_a/dxi J0^-1 with the natural
// derivatives dN_a/dxi at the Gauss points the same for every element: the update reads J0^-1
// (9 numbers) instead of the 120-number table (960 B less to move per element and step). A
// curved element reads the table (in the lane layout: dNdX_lanes).
//
// Which instruction set: results agree across them to about 1e-15 relative (fused multiply-add
// where there is one, the order of the 4-lane sums, the vector log and exp), not bit for bit;
// on one machine they are the same bits with any number of threads.
#include <cstdint>
#include <string>
#include <vector>

#include "elements/fbar_mode.hpp"
#include "elements/tet10_mesh.hpp"
#include "engine/element_update/element_states.hpp"
#include "materials/material_registry.hpp"

namespace femdem {

struct ElementResult;

// Two elements updated together (second == first: one element alone, its copy discarded).
struct ElementPair {
  std::int32_t first = 0, second = 0;
};

// The model's arrays the update reads and writes, indexed by element (and node).
struct ElementUpdateArrays {
  const double* x = nullptr;                 // current node positions, 3 per node
  const double* X = nullptr;                 // reference node positions (F = I + grad(x - X))
  const Tet10* conn = nullptr;               // connectivity
  const double* inverse_jacobian = nullptr;  // straight-sided: J0^-1, 9 per element, row-major
  const double* dNdX_lanes = nullptr;        // curved: dN_a/dX_j at the 4 points, [e][3a+j][g]
  const double* gauss_weight = nullptr;      // w_g det J0, 4 per element
  const double* subtet_volume0 = nullptr;    // SubTet F-bar: the 8 sub-tets' reference volume
  const double* node_J = nullptr;            // Nodal F-bar: each node's averaged volume ratio
  double* pressure_weight = nullptr;         // Nodal F-bar, out: 4 per element (element_kernel)
  double* volume_gradient = nullptr;         // Nodal F-bar, out: d(volume)/dx, 30 per element
  ElementStates* state = nullptr;            // history (not touched for elastic materials)
  double* stress = nullptr;                  // out: Cauchy stress, [e][6][4] (xx yy zz xy yz xz)
  double* force = nullptr;                   // out: internal nodal forces, 30 per element
  ElementResult* result = nullptr;  // out: energy, dissipation, min det F, max eps_p, altitude
};

// True when the SIMD update has the material's model and the F-bar mode (the rest go through
// the scalar kernel).
bool element_update_supports(const MaterialKernel& material, FbarMode fbar);

// Updates `count` pairs whose elements all have this material and F-bar mode, and all
// straight-sided (`straight`) or all curved. dt: the step (rate-dependent models).
void update_element_pairs(const MaterialKernel& material, FbarMode fbar, bool straight,
                          const ElementUpdateArrays& arrays, const ElementPair* pairs,
                          std::size_t count, double dt);

// Each element's current volume (sum_g w_g det F_g) for `count` pairs, all straight-sided or all
// curved: the nodal F-bar's input, computed before the update. Reads x, X, conn, the gradients
// and the weights of `arrays`.
void element_pair_volumes(bool straight, const ElementUpdateArrays& arrays,
                          const ElementPair* pairs, std::size_t count, double* volume);

// The instruction sets this binary has code for and this machine runs, best first ("AVX3",
// "AVX2", "SCALAR"), and the one in use.
std::vector<std::string> element_update_targets();
std::string element_update_target();
// Restricts the update to one of element_update_targets() (tests and benchmarks compare them);
// "" goes back to the best. Affects the whole process. Returns false for an unknown name.
bool use_element_update_target(const std::string& name);

}  // namespace femdem
