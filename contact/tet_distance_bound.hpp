// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A lower bound of the distance between two tetrahedra: the largest gap between their
// projections on the separating axes of two convex polyhedra (the 8 face normals of either
// tetrahedron and the 36 cross products of an edge of each) and on the line through their
// centroids. A projection on a unit axis shortens every distance, so each gap is a lower bound;
// by the separating-axis theorem one of them is positive whenever the two are apart, and for
// two tetrahedra facing each other across a gap (the flat contact about to close) a face normal
// gives the gap itself. The edge axes are tried only when no face axis separates the two. Used
// by body contact to decide which pairs may touch within a step (engine/body_contact.cpp,
// omega_squared_bound).
#include <algorithm>
#include <array>
#include <cmath>

#include "contact/centroid_line.hpp"
#include "contact/point3.hpp"

namespace femdem::contact {

namespace detail {
// Each face of a tetrahedron (3 corners) and the corner opposite it.
inline constexpr int kFaces[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};
// The six edges of a tetrahedron.
inline constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// The gap of b beyond the plane of face (i, j, k) of a, on the face's outward unit normal (the
// side away from a's fourth corner l); -HUGE_VAL for a degenerate face.
inline double face_gap(const std::array<P3, 4>& a, int i, int j, int k, int l,
                       const std::array<P3, 4>& b) {
  P3 n = cross(sub(a[j], a[i]), sub(a[k], a[i]));
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0.0)) return -HUGE_VAL;
  if (dot(n, sub(a[l], a[i])) > 0.0) n = {-n[0], -n[1], -n[2]};
  double lowest = HUGE_VAL;
  for (const P3& p : b) lowest = std::min(lowest, dot(n, sub(p, a[i])));
  return lowest / len;  // (a lies on the other side of the plane: its own gap is 0)
}

// The gap between the projections of a and b on the unit axis along n (-HUGE_VAL when n is 0).
inline double axis_gap(const std::array<P3, 4>& a, const std::array<P3, 4>& b, const P3& n) {
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0.0)) return -HUGE_VAL;
  double a_lo = HUGE_VAL, a_hi = -HUGE_VAL, b_lo = HUGE_VAL, b_hi = -HUGE_VAL;
  for (int k = 0; k < 4; ++k) {
    const double pa = dot(n, a[k]), pb = dot(n, b[k]);
    a_lo = std::min(a_lo, pa), a_hi = std::max(a_hi, pa);
    b_lo = std::min(b_lo, pb), b_hi = std::max(b_hi, pb);
  }
  return std::max(b_lo - a_hi, a_lo - b_hi) / len;
}
}  // namespace detail

// True when a face of one tetrahedron separates it from the other and at least 3 corners of the
// other lie within `reach` of that face's plane: a face of each, nearly parallel, facing each
// other across less than reach, which is how a flat contact closes. (A corner or an edge meets a
// face or an edge first otherwise: its overlap, and so its penalty stiffness, grows from zero.)
inline bool faces_flush_within(const std::array<P3, 4>& a, const std::array<P3, 4>& b,
                               double reach) {
  for (int side = 0; side < 2; ++side) {
    const std::array<P3, 4>& s = side == 0 ? a : b;
    const std::array<P3, 4>& o = side == 0 ? b : a;
    for (const auto& f : detail::kFaces) {
      P3 n = cross(sub(s[f[1]], s[f[0]]), sub(s[f[2]], s[f[0]]));
      const double len = std::sqrt(dot(n, n));
      if (!(len > 0.0)) continue;
      if (dot(n, sub(s[f[3]], s[f[0]])) > 0.0) n = {-n[0], -n[1], -n[2]};
      int close = 0;
      bool separates = true;
      for (const P3& p : o) {
        const double d = dot(n, sub(p, s[f[0]])) / len;
        separates = separates && d > 0.0;
        close += d <= reach;
      }
      if (separates && close >= 3) return true;
    }
  }
  return false;
}

inline double tet_distance_lower_bound(const std::array<P3, 4>& a, const std::array<P3, 4>& b) {
  double length = 0.0;
  const double along = centroid_line_separation(a, b, &length);
  double gap = length > 0.0 ? along / length : -HUGE_VAL;
  for (const auto& f : detail::kFaces) {
    gap = std::max(gap, detail::face_gap(a, f[0], f[1], f[2], f[3], b));
    gap = std::max(gap, detail::face_gap(b, f[0], f[1], f[2], f[3], a));
  }
  if (gap > 0.0) return gap;
  for (const auto& ea : detail::kEdges) {
    const P3 da = sub(a[ea[1]], a[ea[0]]);
    for (const auto& eb : detail::kEdges)
      gap = std::max(gap, detail::axis_gap(a, b, cross(da, sub(b[eb[1]], b[eb[0]]))));
  }
  return gap;
}

// The decision body contact's stable step takes for a pair not touching (engine/body_contact.cpp,
// omega_squared_bound): whether the two may close with faces flush within `reach`,
//   g <= reach && (g <= 0 || faces_flush_within(a, b, reach)),  g = tet_distance_lower_bound(a, b),
// with the same arithmetic, in one pass over the faces, and stopping at the first axis that
// settles it: most candidate pairs of a packing lie further apart than their reach, which the
// centroid line or the first faces show, where the bound and the flush test above each take
// every face (and the flush test again).
inline bool may_close_flush_within(const std::array<P3, 4>& a, const std::array<P3, 4>& b,
                                   double reach) {
  double length = 0.0;
  const double along = centroid_line_separation(a, b, &length);
  bool separated = false;
  if (length > 0.0) {
    const double gap = along / length;
    if (gap > reach) return false;
    separated = gap > 0.0;
  }
  bool flush = false;
  for (int side = 0; side < 2; ++side) {
    const std::array<P3, 4>& s = side == 0 ? a : b;
    const std::array<P3, 4>& o = side == 0 ? b : a;
    for (const auto& f : detail::kFaces) {
      P3 n = cross(sub(s[f[1]], s[f[0]]), sub(s[f[2]], s[f[0]]));
      const double len = std::sqrt(dot(n, n));
      if (!(len > 0.0)) continue;
      if (dot(n, sub(s[f[3]], s[f[0]])) > 0.0) n = {-n[0], -n[1], -n[2]};
      // (the lowest of the quotients is the quotient of the lowest: division by len > 0 keeps
      // the order, so this is detail::face_gap to the bit)
      double lowest = HUGE_VAL;
      int close = 0;
      for (const P3& p : o) {
        const double d = dot(n, sub(p, s[f[0]])) / len;
        lowest = std::min(lowest, d);
        close += d <= reach;
      }
      if (lowest > reach) return false;
      if (lowest > 0.0) {
        separated = true;
        flush = flush || close >= 3;
      }
    }
  }
  if (separated) return flush;
  // No face and not the centroid line separate them: an edge-edge axis that does leaves them
  // apart without a face flush (false), none leaves them touching (true).
  for (const auto& ea : detail::kEdges) {
    const P3 da = sub(a[ea[1]], a[ea[0]]);
    for (const auto& eb : detail::kEdges)
      if (detail::axis_gap(a, b, cross(da, sub(b[eb[1]], b[eb[0]]))) > 0.0) return false;
  }
  return true;
}

}  // namespace femdem::contact
