// SPDX-License-Identifier: GPL-3.0-or-later
// Wall contact visits only the (node, wall) pairs within reach (engine/wall_contact.hpp): the
// list must never miss a pair that touches. A block's nodes jitter and drift and two walls move
// towards and away from it, by many buffer lengths in all, with the forces compared at every
// step with the sum over every (boundary node, wall) pair, k d n for each node behind a wall.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/contact_stiffness.hpp"
#include "engine/simulation.hpp"
#include "engine/wall_contact.hpp"
#include "support/elastic_material.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

TEST(WallReach, ForcesEqualTheSumOverEveryNodeAndWall) {
  ModelSpec s;
  s.materials.push_back(test::elastic_material("steel", 7800.0, 2e11, 0.3));
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = test::kuhn_box(3, 3, 3, Vec3(0.01, 0.01, 0.01));
  s.bodies.push_back(b);
  WallSpec floor, punch;
  floor.name = "floor";
  floor.point = Vec3(0, 0, 0);
  floor.normal = Vec3(0, 0, 1);
  punch.name = "punch";
  punch.point = Vec3(0, 0, 0.01);
  punch.normal = Vec3(0, 0, -1);
  s.walls = {floor, punch};
  Model m = build_model(s);
  WallContact walls(m, false);
  const std::vector<double> x0 = m.x;

  std::mt19937 rng(17);
  std::normal_distribution<double> jitter(0.0, 2e-5);
  int touching_steps = 0, list_sizes_changed = 0;
  std::size_t last_size = 0;
  for (int step = 0; step < 2000; ++step) {
    // the block drifts up and down by +-1.5 mm (its elements are 3.3 mm), its nodes jitter
    // by 20 um, the punch comes down to press it and goes back
    const double t = step / 2000.0;
    const double drift = 1.5e-3 * std::sin(6.0 * M_PI * t);
    for (std::size_t i = 0; i < m.x.size(); ++i)
      m.x[i] = x0[i] + jitter(rng) + (i % 3 == 2 ? drift : 0.0);
    m.walls[1].point.z() = 0.01 + 2e-3 * std::cos(4.0 * M_PI * t);
    std::vector<double> f(m.x.size(), 0.0), expected(m.x.size(), 0.0);
    ContactSums sums;
    walls.compute(m, 1e-7, f, sums);
    bool touching = false;
    for (const SurfaceNode& sn : m.surface)
      for (const Wall& w : m.walls) {
        const Vec3 p(m.x[3 * sn.node], m.x[3 * sn.node + 1], m.x[3 * sn.node + 2]);
        const double d = (w.point - p).dot(w.normal);
        if (d <= 0.0) continue;
        touching = true;
        const double k = wall_modulus(m, w, sn.body) * sn.area / sn.depth;
        for (int c = 0; c < 3; ++c) expected[3 * sn.node + c] += k * d * w.normal[c];
      }
    touching_steps += touching;
    for (std::size_t i = 0; i < f.size(); ++i)
      ASSERT_NEAR(f[i], expected[i], 1e-9 * (std::fabs(expected[i]) + 1.0))
          << "step " << step << " dof " << i;
    list_sizes_changed += walls.near_pairs() != last_size;
    last_size = walls.near_pairs();
  }
  // the test moved things far enough to rebuild the list many times, with contact often
  EXPECT_GT(walls.near_list_builds(), 10);
  EXPECT_GT(list_sizes_changed, 10);
  EXPECT_GT(touching_steps, 500);
  // and the list is shorter than every pair (what it is for)
  EXPECT_LT(walls.near_pairs(), m.surface.size() * m.walls.size());
}
