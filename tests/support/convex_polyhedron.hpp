// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A convex polyhedron clipped by half-spaces, and its volume and first moment: a second clipper
// for the tet-tet potential integral (contact/tet_potential_integral.hpp), independent of the
// tetrahedron sets of the kernel (contact/tet_regions_clip.hpp) and of the tests'
// tests/support/tetrahedron_set_clip.hpp, so that the tests can check the kernel against a
// different algorithm. (Measured as the kernel's clipper it was slower:
// 2.36 against 1.69 us per shallow pair, docs/PERFORMANCE.md, "Tet-tet contact pair kernel".)
//
// The polyhedron is stored as its vertices and, per vertex, its three neighbours in one fixed
// rotational order (a simple polyhedron: every vertex has degree 3). A tetrahedron is one, and
// clipping keeps it one: a cut edge gets a new vertex joined to the kept end and to the two
// next new vertices around the cut face. The topology therefore never depends on a tolerance;
// a vertex exactly on a plane counts as kept, and the cut next to it gives a vertex on top of
// it (a zero-length edge, which adds nothing to the moments). Each clip adds at most one face
// (the cut), and a simple polyhedron of F faces has 2F - 4 vertices, so a tetrahedron clipped
// by up to kMaxPlanes planes fits the fixed storage: no allocation.
#include <array>

#include <cassert>
#include <cstdint>
#include "contact/point3.hpp"

namespace femdem::test {

using contact::cross;
using contact::dot;
using contact::sub;

class ConvexPolyhedron {
 public:
  using P3 = contact::P3;
  static constexpr int kMaxPlanes = 6;
  // 2F - 4 vertices before a clip (F <= 4 + kMaxPlanes - 1) plus one per cut edge (3V/2).
  static constexpr int kMaxVertices = (2 * (3 + kMaxPlanes) - 4) * 5 / 2;

  // The tetrahedron with corners p (either orientation; a flat one gives zero moments).
  void set_tetrahedron(const std::array<P3, 4>& p) {
    const P3 e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]), e3 = sub(p[3], p[0]);
    const bool positive = dot(e1, cross(e2, e3)) >= 0.0;
    // Neighbours in the order of the traversal rule in moments(): for a positively oriented
    // tetrahedron (0, 1, 2, 3) these are the even permutations of (0: 1 3 2); the other
    // orientation reverses each.
    static constexpr std::int8_t kPositive[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
    static constexpr std::int8_t kNegative[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    const auto& order = positive ? kPositive : kNegative;
    count_ = 4;
    for (int v = 0; v < 4; ++v) {
      pos_[v] = p[v];
      for (int k = 0; k < 3; ++k) next_[v][k] = order[v][k];
    }
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) {
        const int u = next_[v][k];
        back_[v][k] = static_cast<std::int8_t>(next_[u][0] == v ? 0 : next_[u][1] == v ? 1 : 2);
      }
  }

  int vertex_count() const { return count_; }
  const P3& vertex(int v) const { return pos_[v]; }
  bool empty() const { return count_ == 0; }

  // Keeps the part where c + g . x >= 0. Planes that keep everything change nothing; a plane
  // that keeps nothing empties the polyhedron.
  void clip(double c, const P3& g) {
    if (count_ == 0) return;
    double s[kMaxVertices];
    int kept = 0;
    for (int v = 0; v < count_; ++v) {
      s[v] = c + dot(g, pos_[v]);
      kept += s[v] >= 0.0;
    }
    if (kept == count_) return;
    if (kept == 0) {
      count_ = 0;
      return;
    }
    // a new vertex on every edge from a kept vertex v to a removed one u; its first neighbour
    // is v, which points to it instead of u
    const int old_count = count_;
    for (int v = 0; v < old_count; ++v) {
      if (s[v] < 0.0) continue;
      for (int k = 0; k < 3; ++k) {
        const int u = next_[v][k];
        if (s[u] >= 0.0) continue;
        assert(count_ < kMaxVertices);
        const int w = count_++;
        const double t = s[v] / (s[v] - s[u]);  // s[v] >= 0 > s[u]: t in [0, 1)
        for (int d = 0; d < 3; ++d) pos_[w][d] = pos_[v][d] + t * (pos_[u][d] - pos_[v][d]);
        s[w] = 0.0;
        next_[w][0] = static_cast<std::int8_t>(v);
        back_[w][0] = static_cast<std::int8_t>(k);
        next_[v][k] = static_cast<std::int8_t>(w);
        back_[v][k] = 0;
      }
    }
    // Join the new vertices around the cut: from w, walk the face to the left of (w, v) (the
    // traversal rule of moments()) through kept vertices to the next new vertex w2; that face
    // closes with the edge w2 -> w, which puts w2 in w's third slot and w in w2's second.
    for (int w = old_count; w < count_; ++w) {
      int cur = next_[w][0], slot = kAfter[back_[w][0]];
      while (cur < old_count) {
        const int nx = next_[cur][slot];
        slot = kAfter[back_[cur][slot]];
        cur = nx;
      }
      next_[w][2] = static_cast<std::int8_t>(cur);
      back_[w][2] = 1;
      next_[cur][1] = static_cast<std::int8_t>(w);
      back_[cur][1] = 2;
    }
    // drop the removed vertices, renumbering the rest
    std::int8_t index[kMaxVertices];
    int n = 0;
    for (int v = 0; v < count_; ++v) {
      if (s[v] < 0.0) {
        index[v] = -1;
        continue;
      }
      index[v] = static_cast<std::int8_t>(n);
      if (n != v) {
        pos_[n] = pos_[v];
        for (int k = 0; k < 3; ++k) {
          next_[n][k] = next_[v][k];
          back_[n][k] = back_[v][k];
        }
      }
      ++n;
    }
    count_ = n;
    for (int v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) next_[v][k] = index[next_[v][k]];
  }

  // Volume and first moment (volume times centroid), summed over the fans of the faces from
  // the first vertex (so faces through it add nothing and the sums keep their digits).
  void moments(double& volume, P3& moment) const {
    volume = 0.0;
    moment = {0.0, 0.0, 0.0};
    if (count_ < 4) return;
    const P3& o = pos_[0];
    bool done[kMaxVertices][3] = {};
    double six_v = 0.0;
    P3 m4 = {0.0, 0.0, 0.0};  // 24 x first moment about o
    for (int v0 = 1; v0 < count_; ++v0) {
      for (int k0 = 0; k0 < 3; ++k0) {
        if (done[v0][k0]) continue;
        // the face whose boundary runs v0 -> next_[v0][k0] -> ...
        done[v0][k0] = true;
        const P3 a = sub(pos_[v0], o);
        int cur = next_[v0][k0], k = kAfter[back_[v0][k0]];
        bool through_o = cur == 0;
        P3 b = sub(pos_[cur], o);
        double f6 = 0.0;
        P3 fm = {0.0, 0.0, 0.0};
        for (;;) {
          done[cur][k] = true;
          const int nx = next_[cur][k];
          if (nx == v0) break;
          through_o |= nx == 0;
          const P3 c = sub(pos_[nx], o);
          const double d = dot(a, cross(b, c));
          f6 += d;
          for (int i = 0; i < 3; ++i) fm[i] += d * (a[i] + b[i] + c[i]);
          k = kAfter[back_[cur][k]];
          cur = nx;
          b = c;
        }
        if (through_o) continue;  // a face through o spans no volume with it
        six_v += f6;
        for (int i = 0; i < 3; ++i) m4[i] += fm[i];
      }
    }
    // The traversal rule runs each face clockwise seen from outside, so the fans' signed
    // volumes are negative.
    volume = -six_v / 6.0;
    for (int i = 0; i < 3; ++i) moment[i] = volume * o[i] - m4[i] / 24.0;
  }

 private:
  // The traversal rule: arriving at a vertex through its slot j (back_ of the edge taken), a
  // face goes on through slot kAfter[j], the neighbour after the one it came from.
  static constexpr std::int8_t kAfter[3] = {1, 2, 0};

  int count_ = 0;
  P3 pos_[kMaxVertices];
  std::int8_t next_[kMaxVertices][3];  // neighbours, in rotational order
  std::int8_t back_[kMaxVertices][3];  // back_[v][k]: the slot of v at next_[v][k]
};

}  // namespace femdem::test
