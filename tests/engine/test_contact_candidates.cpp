// SPDX-License-Identifier: GPL-3.0-or-later
// The candidate pipeline of contact between bodies (engine/body_contact.hpp: the NBS broadphase
// on buffered boxes, the Verlet rule, the centroid-line gap filter, the per-step box test) must
// never lose a touching pair. Ten blocks, some rotated, drift into a cluster and jostle (random
// rigid motions and node jitter, many buffer lengths in all); at every step the touching pairs
// and the contact energy equal those of every pair of contact sub-tetrahedra of different
// bodies put through the kernel directly. Two fixed blocks stand pressed together in the ring's
// middle, where the others close in on them: pairs of a fixed and a moving block are found, the
// pair of the two fixed ones never is (body boxes first: engine/body_contact.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "contact/tet_potential_contact.hpp"
#include "engine/body_contact.hpp"
#include "engine/contact_stiffness.hpp"
#include "engine/simulation.hpp"
#include "support/elastic_material.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

TEST(ContactCandidates, EveryTouchingPairOfARandomClusterIsFound) {
  ModelSpec s;
  s.materials.push_back(test::elastic_material("steel", 7800.0, 2e11, 0.3));
  const int bodies = 10;
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int b = 0; b < bodies; ++b) {
    BodySpec spec;
    spec.name = "block" + std::to_string(b);
    spec.material = 0;
    spec.mesh = test::kuhn_box(1, 1, 1, Vec3(0.01, 0.01, 0.01), 0.1, 3 + b);
    s.bodies.push_back(spec);
  }
  // the fixed pair: 6 mm cubes overlapping by 0.2 mm across x = 0, listed after the ring
  for (int k = 0; k < 2; ++k) {
    BodySpec spec;
    spec.name = "fixed" + std::to_string(k);
    spec.material = 0;
    spec.fixed = true;
    spec.mesh = test::kuhn_box(1, 1, 1, Vec3(0.006, 0.006, 0.006));
    for (Vec3& x : spec.mesh.nodes) x += Vec3(k == 0 ? -0.0059 : -0.0001, -0.003, -0.003);
    s.bodies.push_back(spec);
  }
  Model m = build_model(s);
  // each block's rest shape, its start centre on a ring of radius 12 mm and a rotation
  std::vector<Vec3> rest(m.node_count), centre(bodies), drift(bodies);
  std::vector<Eigen::Matrix3d> rotation(bodies);
  for (std::int32_t n = 0; n < m.node_count; ++n)
    rest[n] = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]) - Vec3(0.005, 0.005, 0.005);
  const std::vector<double> fixed_x = m.x;
  for (int b = 0; b < bodies; ++b) {
    const double a = 2.0 * M_PI * b / bodies;
    centre[b] = Vec3(0.022 * std::cos(a), 0.022 * std::sin(a), 0.002 * u(rng));
    drift[b] = -0.35 * centre[b] / 200.0;  // in to a radius of 14 mm over 200 of 300 steps
    rotation[b] = Eigen::AngleAxisd(u(rng) * M_PI, Vec3(u(rng), u(rng), u(rng)).normalized())
                      .toRotationMatrix();
  }
  const std::vector<std::int32_t>& body_of = m.node_body;
  BodyContact contact(m);
  ASSERT_TRUE(contact.active());
  std::normal_distribution<double> jitter(0.0, 3e-6);
  int most_touching = 0, most_touching_fixed = 0;
  for (int step = 0; step < 300; ++step) {
    const double t = std::min(step, 200) + 0.0;
    for (std::int32_t n = 0; n < m.node_count; ++n) {
      const int b = body_of[n];
      if (b >= bodies) continue;  // the fixed blocks stay where they are
      // the cluster closes, then jostles: a slow wobble of each block's position and turn
      const Vec3 wobble = 4e-4 * Vec3(std::sin(0.1 * step + b), std::cos(0.14 * step + 2 * b),
                                      std::sin(0.06 * step + 3 * b));
      const Eigen::Matrix3d turn =
          Eigen::AngleAxisd(0.002 * step * (b % 3 - 1), Vec3::UnitZ()).toRotationMatrix();
      const Vec3 x = centre[b] + t * drift[b] + wobble + turn * rotation[b] * rest[n];
      for (int c = 0; c < 3; ++c) m.x[3 * n + c] = x[c] + jitter(rng);
    }
    std::vector<double> f(m.x.size(), 0.0);
    contact.compute(m, 1e-7, f);
    // every pair of contact sub-tets of different bodies, through the kernel
    int touching = 0, touching_fixed = 0;
    double energy = 0.0;
    const std::size_t nt = m.contact_tets.size();
    std::vector<contact::TetCorners> corners(nt);
    std::vector<Vec3> lo(nt, Vec3::Constant(HUGE_VAL)), hi(nt, Vec3::Constant(-HUGE_VAL));
    for (std::size_t i = 0; i < nt; ++i)
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) {
          corners[i][k][c] = m.x[3 * m.contact_tets[i][k] + c];
          lo[i][c] = std::min(lo[i][c], corners[i][k][c]);
          hi[i][c] = std::max(hi[i][c], corners[i][k][c]);
        }
    for (std::size_t i = 0; i < nt; ++i)
      for (std::size_t j = i + 1; j < nt; ++j) {
        const int bi = m.contact_tet_body[i], bj = m.contact_tet_body[j];
        if (bi == bj || (m.bodies[bi].fixed && m.bodies[bj].fixed)) continue;
        // (overlapping tetrahedra have overlapping boxes: this only saves time)
        if ((hi[i].array() < lo[j].array()).any() || (hi[j].array() < lo[i].array()).any())
          continue;
        contact::TetPairContact c{};
        if (!contact::tet_potential_contact(corners[i], corners[j], pair_penalty(m, bi, bj), c) ||
            !(c.energy > 0.0))
          continue;
        ++touching;
        touching_fixed += m.bodies[bi].fixed || m.bodies[bj].fixed;
        energy += c.energy;
      }
    ASSERT_EQ(static_cast<int>(contact.touching_pairs()), touching) << "step " << step;
    ASSERT_NEAR(contact.energy(), energy, 1e-12 * energy + 1e-300) << "step " << step;
    most_touching = std::max(most_touching, touching);
    most_touching_fixed = std::max(most_touching_fixed, touching_fixed);
  }
  for (std::size_t i = 3 * static_cast<std::size_t>(m.bodies[bodies].first_node); i < m.x.size();
       ++i)
    ASSERT_EQ(m.x[i], fixed_x[i]);
  std::printf("most touching pairs %d (%d with a fixed block), broadphase runs %lld\n",
              most_touching, most_touching_fixed,
              static_cast<long long>(contact.broadphase_runs()));
  EXPECT_GT(most_touching, 20);              // the cluster did close
  EXPECT_GT(most_touching_fixed, 4);         // on the fixed blocks too
  EXPECT_GT(contact.broadphase_runs(), 10);  // and moved the list through many rebuilds
}
