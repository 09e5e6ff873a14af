// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a run of a model will hold in memory, from its node and element counts before anything
// is built: measured as the peak resident size of `femdem run` (2 threads; the model, the
// simulation's arrays, the stable-step estimate's vectors, the output buffers, HDF5). Curved
// elements keep their own shape-function gradients and cost more than straight ones; the
// estimate takes every element as curved, so it is an upper bound: measured within 2 % for
// curved meshes (spheres of 1e5 and 7.5e5 elements) and 20-26 % above for straight ones (boxes
// of 1e4 to 1e6), docs/PERFORMANCE.md "Memory".
#include <cstdint>

#include "engine/model_spec.hpp"

namespace femdem {

struct MemoryEstimate {
  std::int64_t nodes = 0, elements = 0;
  double bytes = 0.0;
};

inline constexpr double kMemoryBase = 30e6;          // bytes: the program and its libraries
inline constexpr double kMemoryPerElement = 3700.0;  // bytes per TET10 element (curved)
inline constexpr double kMemoryPerNode = 500.0;      // bytes per node

inline MemoryEstimate estimate_memory(const ModelSpec& spec) {
  MemoryEstimate e;
  for (const BodySpec& b : spec.bodies) {
    e.nodes += static_cast<std::int64_t>(b.mesh.nodes.size());
    e.elements += static_cast<std::int64_t>(b.mesh.elements.size());
  }
  e.bytes = kMemoryBase + kMemoryPerElement * static_cast<double>(e.elements) +
            kMemoryPerNode * static_cast<double>(e.nodes);
  return e;
}

}  // namespace femdem
