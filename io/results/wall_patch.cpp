// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/results/wall_patch.hpp"

#include <algorithm>
#include <cmath>

#include "engine/plane_axis.hpp"

namespace femdem {

std::array<Vec3, 4> wall_patch(const Wall& wall, const Vec3& lo, const Vec3& hi) {
  const Vec3 n = wall.normal.normalized();
  // in-plane axes: a bounded wall's axis (projected on the plane) first, else the one a studded
  // wall lays its lattice along
  const Vec3 t1 = wall.bounded ? Vec3((wall.bound_axis - wall.bound_axis.dot(n) * n).normalized())
                               : in_plane_axis(n);
  const Vec3 t2 = n.cross(t1);
  const double grow = 0.1 * (hi - lo).norm();
  const Vec3 g = Vec3::Constant(grow);
  const Vec3 blo = lo - g, bhi = hi + g;
  // the box's extent along t1 and t2, measured from the wall's point
  double a0 = HUGE_VAL, a1 = -HUGE_VAL, b0 = HUGE_VAL, b1 = -HUGE_VAL;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p((c & 1) ? bhi.x() : blo.x(), (c & 2) ? bhi.y() : blo.y(),
                 (c & 4) ? bhi.z() : blo.z());
    const Vec3 d = p - wall.point0;
    a0 = std::min(a0, d.dot(t1));
    a1 = std::max(a1, d.dot(t1));
    b0 = std::min(b0, d.dot(t2));
    b1 = std::max(b1, d.dot(t2));
  }
  if (wall.bounded && wall.bound_axis.dot(t1) > 0.0) {
    // the axial extent is in absolute coordinates along bound_axis
    const double cos_axis = wall.bound_axis.normalized().dot(t1);
    const double s0 = wall.point0.dot(wall.bound_axis.normalized());
    const double scale = wall.bound_axis.norm();
    if (std::isfinite(wall.bound_min)) a0 = std::max(a0, (wall.bound_min / scale - s0) / cos_axis);
    if (std::isfinite(wall.bound_max)) a1 = std::min(a1, (wall.bound_max / scale - s0) / cos_axis);
    if (a1 < a0) a1 = a0;
  }
  const Vec3& p = wall.point0;
  return {p + a0 * t1 + b0 * t2, p + a1 * t1 + b0 * t2, p + a1 * t1 + b1 * t2,
          p + a0 * t1 + b1 * t2};
}

}  // namespace femdem
