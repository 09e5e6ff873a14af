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

// Two such 0.1 m blocks, "a" at the origin and "b" at b_origin, closing along z at
// closing_speed (a up, b down, half each).
inline ModelSpec two_blocks_closing(Vec3 b_origin, double closing_speed) {
  ModelSpec s;
  s.materials.push_back(rubbery());
  BodySpec a, b;
  // (moved in, not assigned from a literal: GCC 12 warns falsely about the literal's copy,
  // -Wrestrict, bug 105329)
  a.name = std::string(1, 'a');
  a.material = 0;
  a.mesh = box_at(Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 0));
  a.velocity = Vec3(0, 0, 0.5 * closing_speed);
  b.name = std::string(1, 'b');
  b.material = 0;
  b.mesh = box_at(Vec3(0.1, 0.1, 0.1), b_origin);
  b.velocity = Vec3(0, 0, -0.5 * closing_speed);
  s.bodies = {a, b};
  return s;
}

inline Vec3 momentum(const Model& m) {
  Vec3 p = Vec3::Zero();
  for (std::int32_t n = 0; n < m.node_count; ++n)
    p += m.mass[n] * Vec3(m.v[3 * n], m.v[3 * n + 1], m.v[3 * n + 2]);
  return p;
}

}  // namespace femdem::test
