// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Checks of a TET10 mesh shared by the mesh tests (generators, refinement): conformity, its
// boundary and interior faces, and its volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "elements/tet_geometry.hpp"

namespace femdem::test {

struct Faces {
  std::vector<std::array<int, 6>> boundary;          // faces of one element (6 nodes)
  std::vector<std::array<std::size_t, 2>> interior;  // the two elements sharing a face
};

// Conformity: every element right-handed with a valid quadratic map; every node used; one
// mid-edge node per edge, shared by every element on that edge and never a corner; every face
// in one element (boundary) or two (interior) with opposite orientations; the boundary a
// closed genus-0 surface. No hanging node can pass: a hanging corner splits a neighbour's face
// into faces that appear only once, which would open the boundary surface.
inline Faces check_conforming(const Tet10Mesh& m) {
  Faces out;
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    const Tet10& t = m.elements[e];
    EXPECT_GT(tet_signed_volume(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]), 0.0)
        << "element " << e;
    EXPECT_GT(tet10_min_scaled_jacobian(m, e), 0.0) << "element " << e;
  }
  std::vector<char> used(m.nodes.size(), 0);
  std::map<std::pair<int, int>, int> edge_mid;
  std::set<int> corners, mids;
  for (const Tet10& t : m.elements) {
    for (int n : t) {
      EXPECT_GE(n, 0);
      EXPECT_LT(n, static_cast<int>(m.nodes.size()));
      used[n] = 1;
    }
    for (int k = 0; k < 6; ++k) {
      int a = t[kTet10Edges[k][0]], b = t[kTet10Edges[k][1]];
      if (a > b) std::swap(a, b);
      const auto [it, added] = edge_mid.emplace(std::make_pair(a, b), t[4 + k]);
      if (!added) {
        EXPECT_EQ(it->second, t[4 + k]) << "edge " << a << "-" << b;
      }
      corners.insert(a);
      corners.insert(b);
      mids.insert(t[4 + k]);
    }
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<long>(m.nodes.size()));
  EXPECT_EQ(mids.size(), edge_mid.size()) << "a mid-edge node serves two edges";
  for (int c : corners) EXPECT_EQ(mids.count(c), 0u) << "node " << c << " is corner and mid";
  std::vector<std::array<double, 3>> pos;
  for (const Vec3& x : m.nodes) pos.push_back({x[0], x[1], x[2]});
  std::sort(pos.begin(), pos.end());
  EXPECT_EQ(std::adjacent_find(pos.begin(), pos.end()), pos.end()) << "duplicate node";

  struct FaceUse {
    std::array<int, 6> nodes;
    std::size_t element;
  };
  std::map<std::array<int, 3>, std::vector<FaceUse>> faces;
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    for (const auto& f : kTet10Faces) {
      FaceUse u{{}, e};
      for (int i = 0; i < 6; ++i) u.nodes[i] = m.elements[e][f[i]];
      std::array<int, 3> key{u.nodes[0], u.nodes[1], u.nodes[2]};
      std::sort(key.begin(), key.end());
      faces[key].push_back(u);
    }
  for (const auto& [key, list] : faces) {
    EXPECT_LE(list.size(), 2u);
    if (list.size() == 1) out.boundary.push_back(list[0].nodes);
    if (list.size() == 2) {
      out.interior.push_back({list[0].element, list[1].element});
      const auto& p = list[0].nodes;
      const auto& q = list[1].nodes;
      int i = 0;
      while (i < 3 && q[i] != p[0]) ++i;
      EXPECT_EQ(q[(i + 2) % 3], p[1]) << "faces not oppositely oriented";
    }
  }
  std::map<std::pair<int, int>, int> bedges;
  std::set<int> bverts;
  for (const auto& f : out.boundary)
    for (int i = 0; i < 3; ++i) {
      int a = f[i], b = f[(i + 1) % 3];
      bverts.insert(a);
      if (a > b) std::swap(a, b);
      ++bedges[{a, b}];
    }
  for (const auto& [e, n] : bedges) EXPECT_EQ(n, 2) << "boundary edge in " << n << " faces";
  EXPECT_EQ(static_cast<long>(bverts.size()) - static_cast<long>(bedges.size()) +
                static_cast<long>(out.boundary.size()),
            2);
  return out;
}

inline double mesh_volume(const Tet10Mesh& m) {
  double v = 0.0;
  for (std::size_t e = 0; e < m.elements.size(); ++e) v += tet10_volume(m, e);
  return v;
}

}  // namespace femdem::test
