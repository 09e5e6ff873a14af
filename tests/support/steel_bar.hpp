// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// An elastic steel bar of 0.4 x 0.1 x 0.1 m, 12 x 3 x 3 Kuhn cells (648 TET10) with its inner
// corners jittered by up to 20 % of a cell: the one body the distributed-run tests cut among
// ranks (engine/distributed).
#include <optional>

#include "engine/model_spec.hpp"
#include "support/elastic_material.hpp"
#include "support/kuhn_box.hpp"

namespace femdem::test {

inline ModelSpec steel_bar(std::optional<FbarMode> fbar = std::nullopt) {
  ModelSpec s;
  s.materials.push_back(elastic_material("steel", 7800.0, 200e9, 0.3));
  BodySpec b;
  b.name = "bar";
  b.material = 0;
  b.fbar = fbar;
  b.mesh = kuhn_box(12, 3, 3, Vec3(0.4, 0.1, 0.1), 0.2);
  s.bodies.push_back(b);
  return s;
}

}  // namespace femdem::test
