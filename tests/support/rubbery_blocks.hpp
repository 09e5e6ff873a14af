// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Small elastic blocks for the contact and damping tests: a soft material, a Kuhn-box block
// placed at an origin, and the total momentum of a model.
#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

namespace femdem::test {

inline MaterialParams rubbery() {
  MaterialParams mat;
  mat.name = "rubbery";
  mat.density = 1000.0;
  mat.youngs_modulus = 1e8;
  mat.poisson_ratio = 0.3;
  return mat;
}

inline Tet10Mesh box_at(Vec3 size, Vec3 origin, int n = 2) {
  Tet10Mesh m = kuhn_box(n, n, n, size);
  for (Vec3& p : m.nodes) p += origin;
  return m;
}

inline Vec3 momentum(const Model& m) {
  Vec3 p = Vec3::Zero();
  for (std::int32_t n = 0; n < m.node_count; ++n)
    p += m.mass[n] * Vec3(m.v[3 * n], m.v[3 * n + 1], m.v[3 * n + 2]);
  return p;
}

}  // namespace femdem::test
