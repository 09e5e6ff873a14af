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

// The signed distances d[k] of o's corners from the plane of face f of s (f: 3 corners, then the
// fourth), along the face's outward unit normal (away from s's fourth corner); false for a
// degenerate face.
inline bool face_distances(const std::array<P3, 4>& s, const int (&f)[4],
                           const std::array<P3, 4>& o, double d[4]) {
  P3 n = cross(sub(s[f[1]], s[f[0]]), sub(s[f[2]], s[f[0]]));
  const double len = std::sqrt(dot(n, n));
  if (!(len > 0.0)) return false;
  if (dot(n, sub(s[f[3]], s[f[0]])) > 0.0) n = {-n[0], -n[1], -n[2]};
  for (int k = 0; k < 4; ++k) d[k] = dot(n, sub(o[k], s[f[0]])) / len;
  return true;
}

// Calls visit(d) with the distances (face_distances) of the other's corners from each
// non-degenerate face of a, then of b, until it returns true; true when it did.
template <class Visit>
bool any_face(const std::array<P3, 4>& a, const std::array<P3, 4>& b, Visit visit) {
  for (int side = 0; side < 2; ++side) {
    const std::array<P3, 4>& s = side == 0 ? a : b;
    const std::array<P3, 4>& o = side == 0 ? b : a;
    for (const auto& f : kFaces) {
      double d[4];
      if (face_distances(s, f, o, d) && visit(d)) return true;
    }
  }
  return false;
}

// The gap of b beyond the plane of face f of a (a lies on the other side of it: its own gap is
// 0); -HUGE_VAL for a degenerate face.
inline double face_gap(const std::array<P3, 4>& a, const int (&f)[4], const std::array<P3, 4>& b) {
  double d[4];
  if (!face_distances(a, f, b, d)) return -HUGE_VAL;
  return std::min(std::min(d[0], d[1]), std::min(d[2], d[3]));
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
  return detail::any_face(a, b, [reach](const double(&d)[4]) {
    int close = 0;
    bool separates = true;
    for (const double dk : d) {
      separates = separates && dk > 0.0;
      close += dk <= reach;
    }
    return separates && close >= 3;
  });
}

inline double tet_distance_lower_bound(const std::array<P3, 4>& a, const std::array<P3, 4>& b) {
  double length = 0.0;
  const double along = centroid_line_separation(a, b, &length);
  double gap = length > 0.0 ? along / length : -HUGE_VAL;
  for (const auto& f : detail::kFaces) {
    gap = std::max(gap, detail::face_gap(a, f, b));
    gap = std::max(gap, detail::face_gap(b, f, a));
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
// `bound` receives the largest gap it measured: a lower bound of the distance when positive
// (-HUGE_VAL when it measured none).
inline bool may_close_flush_within(const std::array<P3, 4>& a, const std::array<P3, 4>& b,
                                   double reach, double& bound) {
  bound = -HUGE_VAL;
  double length = 0.0;
  const double along = centroid_line_separation(a, b, &length);
  bool separated = false;
  if (length > 0.0) {
    const double gap = along / length;
    bound = gap;
    if (gap > reach) return false;
    separated = gap > 0.0;
  }
  bool flush = false;
  const bool beyond = detail::any_face(a, b, [&](const double(&d)[4]) {
    double lowest = HUGE_VAL;  // detail::face_gap
    int close = 0;
    for (const double dk : d) {
      lowest = std::min(lowest, dk);
      close += dk <= reach;
    }
    bound = std::max(bound, lowest);
    if (lowest > 0.0) {
      separated = true;
      flush = flush || close >= 3;
    }
    return lowest > reach;
  });
  if (beyond) return false;
  if (separated) return flush;
  // No face and not the centroid line separate them: an edge-edge axis that does leaves them
  // apart without a face flush (false), none leaves them touching (true).
  for (const auto& ea : detail::kEdges) {
    const P3 da = sub(a[ea[1]], a[ea[0]]);
    for (const auto& eb : detail::kEdges) {
      const double gap = detail::axis_gap(a, b, cross(da, sub(b[eb[1]], b[eb[0]])));
      bound = std::max(bound, gap);
      if (gap > 0.0) return false;
    }
  }
  return true;
}

}  // namespace femdem::contact
