// SPDX-License-Identifier: GPL-3.0-or-later
#include "elements/tet10_mesh.hpp"

#include <unordered_map>

namespace femdem {

namespace {

// Edge key of two node indices, order-independent.
std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

}  // namespace

void add_mid_edge_nodes(Tet10Mesh& mesh) {
  std::unordered_map<std::uint64_t, std::int32_t> mid_of;
  std::size_t linear = 0;
  for (const Tet10& el : mesh.elements) {
    if (el[4] < 0) {
      ++linear;
      continue;
    }
    for (int k = 0; k < 6; ++k)
      mid_of.emplace(edge_key(el[kTet10Edges[k][0]], el[kTet10Edges[k][1]]), el[4 + k]);
  }
  if (linear == 0) return;
  // A TET4 mesh has about 1.2 edges per element.
  mid_of.reserve(mid_of.size() + linear * 2);
  for (Tet10& el : mesh.elements) {
    if (el[4] >= 0) continue;
    for (int k = 0; k < 6; ++k) {
      const std::int32_t a = el[kTet10Edges[k][0]], b = el[kTet10Edges[k][1]];
      const auto [it, added] =
          mid_of.emplace(edge_key(a, b), static_cast<std::int32_t>(mesh.nodes.size()));
      if (added) mesh.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
      el[4 + k] = it->second;
    }
  }
}

}  // namespace femdem
