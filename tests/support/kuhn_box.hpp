// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A small structured TET10 box for element-level tests, independent of io/ (so element tests do
// not depend on the production mesh generators they may be used to check). Each hex cell is cut
// into the 6 Kuhn tetrahedra around its main diagonal, which conform across cells.
#include <map>
#include <random>

#include "elements/tet10_mesh.hpp"

namespace femdem::test {

inline Tet10Mesh kuhn_box(int nx, int ny, int nz, Vec3 size, double jitter = 0.0,
                          unsigned seed = 1) {
  Tet10Mesh m;
  auto corner_id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 h(size[0] / nx, size[1] / ny, size[2] / nz);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        Vec3 p(i * h[0], j * h[1], k * h[2]);
        const bool interior = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
        if (interior && jitter > 0.0) p += jitter * h.cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
        m.nodes.push_back(p);
      }
  // Kuhn: paths from corner 0 to corner 7 of the cell through the 6 permutations of axes
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::map<std::pair<int, int>, int> mid;
  auto midnode = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    m.nodes.push_back(0.5 * (m.nodes[a] + m.nodes[b]));
    const int id = static_cast<int>(m.nodes.size()) - 1;
    mid[key] = id;
    return id;
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          int v[4];
          v[0] = corner_id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            v[s + 1] = corner_id(c[0], c[1], c[2]);
          }
          const Vec3 d1 = m.nodes[v[1]] - m.nodes[v[0]], d2 = m.nodes[v[2]] - m.nodes[v[0]],
                     d3 = m.nodes[v[3]] - m.nodes[v[0]];
          if (d1.dot(d2.cross(d3)) < 0) std::swap(v[1], v[2]);
          Tet10 t;
          for (int a = 0; a < 4; ++a) t[a] = v[a];
          for (int e = 0; e < 6; ++e) t[4 + e] = midnode(v[kTet10Edges[e][0]], v[kTet10Edges[e][1]]);
          m.elements.push_back(t);
        }
  return m;
}

}  // namespace femdem::test
