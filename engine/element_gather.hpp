// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The deterministic gather of per-element node forces: every node sums its element slots in the
// fixed CSR order of Model::node_elem_offset / node_elem_slot, so the result has the same bits for
// any thread count (threads never add into a shared node).
#include <cstdint>

#include "engine/model.hpp"
#include "engine/parallel_threshold.hpp"

namespace femdem {

// element_force: 30 per element (3 per local node); f: 3 per node, overwritten.
inline void gather_element_forces(const Model& m, const double* element_force, double* f) {
  const std::int32_t nn = m.node_count;
#pragma omp parallel for schedule(static) if (nn > kParallelMinNodes)
  for (std::int32_t n = 0; n < nn; ++n) {
    double s[3] = {0.0, 0.0, 0.0};
    for (std::int32_t k = m.node_elem_offset[n]; k < m.node_elem_offset[n + 1]; ++k) {
      const double* fe = element_force + 3 * static_cast<std::size_t>(m.node_elem_slot[k]);
      s[0] += fe[0], s[1] += fe[1], s[2] += fe[2];
    }
    for (int k = 0; k < 3; ++k) f[3 * n + k] = s[k];
  }
}

}  // namespace femdem
