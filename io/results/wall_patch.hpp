// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The rectangle the results show for a rigid wall (walls.xdmf, /walls/patch in results.h5): a
// wall is an unbounded plane, so it is drawn over the part of its plane that faces the bodies:
// the bodies' reference bounding box, grown by a tenth of its diagonal, projected on the plane
// at t = 0, and for a wall of finite axial extent (a die's side) only along that extent.
#include <array>

#include "engine/model.hpp"

namespace femdem {

// Corners in order around the rectangle (counter-clockwise seen from the bodies' side), at the
// wall's position at t = 0; the patch moves with the wall. `lo`/`hi`: the bodies' bounding box.
std::array<Vec3, 4> wall_patch(const Wall& wall, const Vec3& lo, const Vec3& hi);

}  // namespace femdem
