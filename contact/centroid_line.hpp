// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The separation of two tetrahedra along the line through their centroids: a separating-axis
// test that costs 8 dot products. The pair kernel rejects a pair on it before any inverse
// (contact/tet_potential_integral.hpp); body contact keeps a candidate only while it is within
// the Verlet buffer (engine/body_contact.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "contact/point3.hpp"

namespace femdem::contact {

// (lowest corner of b - highest corner of a) projected on axis = 4 (centroid_b - centroid_a),
// times |axis|: positive when the line separates them. axis_length is |axis|.
inline double centroid_line_separation(const std::array<P3, 4>& a, const std::array<P3, 4>& b,
                                       double* axis_length = nullptr) {
  P3 axis = {0.0, 0.0, 0.0};
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) axis[d] += b[k][d] - a[k][d];
  double a_top = -HUGE_VAL, b_bottom = HUGE_VAL;
  for (int k = 0; k < 4; ++k) {
    a_top = std::max(a_top, dot(axis, a[k]));
    b_bottom = std::min(b_bottom, dot(axis, b[k]));
  }
  if (axis_length) *axis_length = std::sqrt(dot(axis, axis));
  return b_bottom - a_top;
}

}  // namespace femdem::contact
