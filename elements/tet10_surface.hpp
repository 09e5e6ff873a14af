// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Boundary faces of a TET10 mesh: faces that belong to exactly one element.
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

struct BoundaryFace {
  std::int32_t element = 0;
  std::int8_t face = 0;  // index into kTet10Faces; its normal points out of the mesh
};

// Deterministic: faces come out in element order, then face order.
std::vector<BoundaryFace> boundary_faces(const std::vector<Tet10>& elements);

}  // namespace femdem
