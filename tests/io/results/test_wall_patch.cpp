// SPDX-License-Identifier: GPL-3.0-or-later
// wall_patch: the rectangle drawn for a wall lies in the wall's plane, faces the bodies (its
// corners go counter-clockwise about the normal), covers the bodies' bounding box seen along the
// normal with a margin, and for a bounded wall spans only its axial extent.
#include <gtest/gtest.h>

#include "io/results/wall_patch.hpp"

namespace {

using femdem::Vec3;
using femdem::Wall;

void expect_in_plane_and_facing(const Wall& w, const std::array<Vec3, 4>& c) {
  for (const Vec3& p : c) EXPECT_NEAR((p - w.point0).dot(w.normal), 0.0, 1e-12);
  const Vec3 n = (c[1] - c[0]).cross(c[2] - c[1]);
  EXPECT_GT(n.dot(w.normal), 0.0);
  EXPECT_NEAR((c[2] - c[1]).dot(c[1] - c[0]), 0.0, 1e-12);  // a rectangle
}

TEST(WallPatch, CoversTheBodiesSeenAlongTheNormal) {
  const Vec3 lo(0, 0, 0), hi(1, 2, 3);
  const double margin = 0.1 * (hi - lo).norm();
  for (const Vec3& normal :
       {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(1, 1, 1).normalized()}) {
    SCOPED_TRACE(normal.transpose());
    Wall w;
    w.normal = normal;
    w.point0 = Vec3(0.5, 1.0, -1.0);
    const auto c = femdem::wall_patch(w, lo, hi);
    expect_in_plane_and_facing(w, c);
    // every box corner (grown by the margin), projected on the plane, is inside the rectangle
    const Vec3 u = (c[1] - c[0]).normalized(), v = (c[3] - c[0]).normalized();
    const double lu = (c[1] - c[0]).norm(), lv = (c[3] - c[0]).norm();
    for (int k = 0; k < 8; ++k) {
      const Vec3 p((k & 1) ? hi.x() + margin : lo.x() - margin,
                   (k & 2) ? hi.y() + margin : lo.y() - margin,
                   (k & 4) ? hi.z() + margin : lo.z() - margin);
      const double a = (p - c[0]).dot(u), b = (p - c[0]).dot(v);
      EXPECT_GE(a, -1e-12);
      EXPECT_LE(a, lu + 1e-12);
      EXPECT_GE(b, -1e-12);
      EXPECT_LE(b, lv + 1e-12);
    }
  }
}

TEST(WallPatch, BoundedWallSpansItsAxialExtent) {
  Wall w;  // a die side x = 1 acting for 0.2 <= z <= 0.7
  w.normal = Vec3(-1, 0, 0);
  w.point0 = Vec3(1, 0, 0);
  w.bounded = true;
  w.bound_axis = Vec3(0, 0, 1);
  w.bound_min = 0.2;
  w.bound_max = 0.7;
  const auto c = femdem::wall_patch(w, Vec3(0, 0, 0), Vec3(1, 1, 1));
  expect_in_plane_and_facing(w, c);
  double zmin = 1e9, zmax = -1e9;
  for (const Vec3& p : c) {
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  EXPECT_NEAR(zmin, 0.2, 1e-12);
  EXPECT_NEAR(zmax, 0.7, 1e-12);
}

}  // namespace
