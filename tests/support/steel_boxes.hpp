// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A scene of elastic steel unit cubes (Kuhn-box meshes of n^3 cells) side by side along x, one
// body each, 2 m apart: what engine tests that need a few plain bodies build.
#include <string>

#include "engine/model_spec.hpp"
#include "support/elastic_material.hpp"
#include "support/kuhn_box.hpp"

namespace femdem::test {

inline ModelSpec steel_boxes(int bodies, int cells) {
  ModelSpec s;
  s.materials.push_back(elastic_material("steel", 7800.0, 200e9, 0.3));
  for (int i = 0; i < bodies; ++i) {
    BodySpec b;
    b.name = "box" + std::to_string(i);
    b.material = 0;
    b.mesh = kuhn_box(cells, cells, cells, Vec3(1.0, 1.0, 1.0));
    for (Vec3& p : b.mesh.nodes) p.x() += 2.0 * i;
    s.bodies.push_back(b);
  }
  s.simulation.end_time = 1.0;
  return s;
}

}  // namespace femdem::test
