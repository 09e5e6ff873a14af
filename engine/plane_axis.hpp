// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// An in-plane direction for a plane of unit normal n, the same for the same n wherever it is
// asked for: the coordinate axis least aligned with n (the first of equals), projected into the
// plane and normalised (x for a floor). A studded wall lays its lattice along it and the walls'
// output draws their patches along it, so the drawing and the relief share axes.
#include <cmath>

#include "elements/tet10_mesh.hpp"

namespace femdem {

inline Vec3 in_plane_axis(const Vec3& n) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  return (Vec3::Unit(k) - n[k] * n).normalized();
}

}  // namespace femdem
