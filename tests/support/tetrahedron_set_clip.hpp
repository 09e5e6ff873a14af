// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A tetrahedron clipped by half-spaces as a set of tetrahedra, and the set's volume and first
// moment: a clipper of positions for tet_potential_contact_with<Clip>
// (contact/tet_potential_integral.hpp), checked against the polyhedron clipper of the tests
// (tests/support/convex_polyhedron.hpp). Each plane splits each piece into a tetrahedron or a
// triangular prism of three, so 4 planes give up to 81 pieces. It was the kernel's clipper
// (faster than the polyhedron one) until contact/tet_regions_clip.hpp, the same algorithm in
// barycentric coordinates on the four regions at once, which runs about twice as fast.
#include <array>

#include <cmath>
#include "contact/point3.hpp"

namespace femdem::contact {

class TetrahedronSetClip {
 public:
  static constexpr int kMaxPlanes = 4;

  void set_tetrahedron(const std::array<P3, 4>& p) {
    for (int k = 0; k < 4; ++k) buf_[0][0].v[k] = p[k];
    n_ = 1;
    cur_ = 0;
  }
  bool empty() const { return n_ == 0; }

  void clip(double c, const P3& g) {
    int m = 0;
    for (int k = 0; k < n_; ++k) m += clip_piece(buf_[cur_][k], c, g, buf_[1 - cur_] + m);
    cur_ = 1 - cur_;
    n_ = m;
  }

  void moments(double& volume, P3& moment) const {
    volume = 0.0;
    moment = {0.0, 0.0, 0.0};
    for (int k = 0; k < n_; ++k) {
      const P3* v = buf_[cur_][k].v;
      const double vol =
          std::abs(dot(sub(v[1], v[0]), cross(sub(v[2], v[0]), sub(v[3], v[0])))) / 6.0;
      const double w = vol * 0.25;
      volume += vol;
      for (int d = 0; d < 3; ++d) moment[d] += w * (v[0][d] + v[1][d] + v[2][d] + v[3][d]);
    }
  }

 private:
  struct Tet {
    P3 v[4];
  };
  static constexpr int kMaxPieces = 81;

  static P3 cut(const P3& p, double sp, const P3& q, double sq) {
    const double t = sp / (sp - sq);  // sp >= 0 > sq
    return {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
  }
  // Triangular prism with ends (a0, a1, a2) and (b0, b1, b2), a_k joined to b_k: three
  // tetrahedra whose diagonals meet consistently on the three side quadrilaterals.
  static int prism(const P3& a0, const P3& a1, const P3& a2, const P3& b0, const P3& b1,
                   const P3& b2, Tet* out) {
    out[0] = {{a0, a1, a2, b0}};
    out[1] = {{a1, a2, b0, b1}};
    out[2] = {{a2, b0, b1, b2}};
    return 3;
  }
  static int clip_piece(const Tet& in, double c, const P3& g, Tet* out) {
    double s[4];
    int inside[4], outside[4], ni = 0, no = 0;
    for (int k = 0; k < 4; ++k) {
      s[k] = c + dot(g, in.v[k]);
      if (s[k] >= 0.0)
        inside[ni++] = k;
      else
        outside[no++] = k;
    }
    const P3* v = in.v;
    switch (ni) {
      case 4:
        out[0] = in;
        return 1;
      case 0:
        return 0;
      case 1: {
        const int a = inside[0];
        out[0] = {{v[a], cut(v[a], s[a], v[outside[0]], s[outside[0]]),
                   cut(v[a], s[a], v[outside[1]], s[outside[1]]),
                   cut(v[a], s[a], v[outside[2]], s[outside[2]])}};
        return 1;
      }
      case 2: {
        const int a = inside[0], b = inside[1], c2 = outside[0], d = outside[1];
        return prism(v[a], cut(v[a], s[a], v[c2], s[c2]), cut(v[a], s[a], v[d], s[d]), v[b],
                     cut(v[b], s[b], v[c2], s[c2]), cut(v[b], s[b], v[d], s[d]), out);
      }
      default: {
        const int a = inside[0], b = inside[1], c3 = inside[2], d = outside[0];
        return prism(v[a], v[b], v[c3], cut(v[a], s[a], v[d], s[d]), cut(v[b], s[b], v[d], s[d]),
                     cut(v[c3], s[c3], v[d], s[d]), out);
      }
    }
  }

  Tet buf_[2][kMaxPieces];
  int n_ = 0, cur_ = 0;
};

}  // namespace femdem::contact
