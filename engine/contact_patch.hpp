// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What two bodies (or a body and a wall) in contact exert on each other this step, summed over
// the touching pairs (or nodes) between them: the input of the impact damping
// (engine/impact_damping.hpp).
#include <cstdint>

#include "engine/model_spec.hpp"

namespace femdem {

struct ContactPatch {
  std::int32_t body_a = -1;
  // the other side: a body (>= 0), or a wall: -1 - (its index)
  std::int32_t body_b = -1;
  Vec3 force_on_a = Vec3::Zero();      // the penalty (normal) forces on a, summed
  Vec3 weighted_point = Vec3::Zero();  // sum of |force| x point of application
  double weight = 0.0;                 // sum of |force|
  double stiffness = 0.0;              // sum of the normal (secant) stiffnesses, N/m

  Vec3 point() const { return weighted_point / weight; }
  static std::int32_t wall_side(std::size_t wall) { return -1 - static_cast<std::int32_t>(wall); }
};

}  // namespace femdem
