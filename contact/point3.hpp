// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A point of the contact kernels as three doubles, and the three operations they need: kept
// as plain arrays (not Eigen) so that the kernels' fixed stack buffers stay trivially copyable.
#include <array>

namespace femdem::contact {

using P3 = std::array<double, 3>;

inline double dot(const P3& a, const P3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline P3 sub(const P3& a, const P3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

}  // namespace femdem::contact
