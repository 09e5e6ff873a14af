// SPDX-License-Identifier: GPL-3.0-or-later
// Distributed runs on 2 and 3 ranks (run by ctest under mpirun; docs/ARCHITECTURE.md,
// "Distributed runs"): exact sums added across ranks, ghost nodes receiving their owners'
// values, a vibrating bar stepped on the ranks with the same bits as in one process, and what
// distributed runs cannot do yet refused alike on every rank.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/distributed/communicator.hpp"
#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "support/steel_bar.hpp"

using namespace femdem;

namespace {

// A 12 x 3 x 3-cell steel bar, bent and stretched by its initial velocity (every node moves
// differently), no supports: elastic, nothing but the elements.
ModelSpec vibrating_bar(SimulationSettings::StableStep estimate) {
  ModelSpec s = test::steel_bar();
  s.simulation.stable_step = estimate;
  return s;
}

Model with_velocity(Model m) {
  for (std::int32_t n = 0; n < m.node_count; ++n) {
    const double x = m.X[3 * n], y = m.X[3 * n + 1];
    m.v[3 * n] = 2.0 * std::sin(7.9 * x);
    m.v[3 * n + 1] = 1.0 * std::cos(3.0 * x) + 0.5 * y;
    m.v[3 * n + 2] = 3.0 * std::sin(15.7 * x);
  }
  return m;
}

}  // namespace

TEST(Distributed, ExactSumsAddAcrossRanks) {
  const Communicator& c = Communicator::world();
  ASSERT_GE(c.size(), 2) << "run under mpirun with 2 or more ranks";
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ExactSum all, mine[2];
  for (int k = 0; k < 10000; ++k) {
    const double t = std::ldexp(u(rng), k % 200 - 100);
    all.add(t);
    if (k % c.size() == c.rank()) mine[0].add(t), mine[1].add(-2.0 * t);
  }
  c.sum(mine);
  EXPECT_EQ(mine[0].value(), all.value());
  EXPECT_EQ(mine[1].value(), -2.0 * all.value());
}

TEST(Distributed, GhostsReceiveTheirOwnersValues) {
  const Communicator& c = Communicator::world();
  const Model m = build_model(vibrating_bar(SimulationSettings::StableStep::element));
  const Partition p = partition_model(m, c.size());
  const LocalPart part = local_part(m, p, c.rank(), ghost_layers(m));
  std::vector<double> values(2 * part.nodes.size(), std::nan(""));
  for (std::size_t k = 0; k < part.nodes.size(); ++k)
    if (part.node_owned[k]) values[2 * k] = part.nodes[k], values[2 * k + 1] = -part.nodes[k];
  c.exchange(part, values.data(), 2);
  for (std::size_t k = 0; k < part.nodes.size(); ++k) {
    EXPECT_EQ(values[2 * k], part.nodes[k]);
    EXPECT_EQ(values[2 * k + 1], -part.nodes[k]);
  }
}

namespace {

// 200 steps of the bar on every rank's part against one process on each rank, with the SIMD
// element update (whose pairs of elements the renumbering regroups) and the scalar one.
void expect_same_bits_as_one_process(ElementKernelChoice kernel,
                                     SimulationSettings::StableStep estimate) {
  const Communicator& c = Communicator::world();
  const Model global = with_velocity(build_model(vibrating_bar(estimate)));
  Simulation whole(global);
  const Partition p = partition_model(global, c.size());
  const LocalPart part = local_part(global, p, c.rank(), ghost_layers(global));
  Simulation mine(local_model(global, part), Distribution{part, &c});
  whole.choose_element_kernel(kernel);
  mine.choose_element_kernel(kernel);
  auto differing = [&] {
    int n = 0;
    for (std::size_t k = 0; k < part.nodes.size(); ++k) {
      if (!part.node_owned[k]) continue;
      for (int d = 0; d < 3; ++d) {
        n += mine.model().x[3 * k + d] != whole.model().x[3 * part.nodes[k] + d];
        n += mine.model().v[3 * k + d] != whole.model().v[3 * part.nodes[k] + d];
      }
    }
    return n;
  };
  for (int step = 0; step < 200; ++step) {
    ASSERT_EQ(mine.dt(), whole.dt()) << "step " << step;
    whole.step();
    mine.step();
    ASSERT_EQ(differing(), 0) << "step " << step;  // (every rank stops at the same step)
  }
  EXPECT_EQ(mine.time(), whole.time());
  const Energies a = mine.energies(), b = whole.energies();
  EXPECT_EQ(a.kinetic, b.kinetic);
  EXPECT_EQ(a.internal, b.internal);
  EXPECT_EQ(a.external_work, b.external_work);
  EXPECT_GT(a.internal, 0.0);
  // the bar, cut among the ranks: a history row's figures (exact sums) have one process's
  // bits; the per-step motions (the ranks' plain sums added) agree to round-off
  std::vector<BodyState> sampled, whole_sampled, moving;
  std::vector<double> tension, whole_tension;
  mine.body_samples(sampled, tension);
  whole.body_samples(whole_sampled, whole_tension);
  mine.body_motions(moving);
  if (c.rank() != 0) return;
  const BodyState& s = sampled[0];
  const BodyState& w = whole_sampled[0];
  const BodyState plain = whole.body_motion(0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(s.com[k], w.com[k]);
    EXPECT_EQ(s.vcom[k], w.vcom[k]);
    EXPECT_NEAR(moving[0].com[k], plain.com[k], 1e-12 * plain.com.norm());
    EXPECT_NEAR(moving[0].vcom[k], plain.vcom[k], 1e-12 * plain.vcom.norm());
  }
  EXPECT_EQ(s.kinetic_energy, w.kinetic_energy);
  EXPECT_EQ(tension[0], whole_tension[0]);
  EXPECT_GT(tension[0], 0.0);
  EXPECT_NEAR(moving[0].kinetic_energy, plain.kinetic_energy, 1e-12 * plain.kinetic_energy);
}

}  // namespace

TEST(Distributed, BarStepsWithTheSameBitsAsOneProcess) {
  expect_same_bits_as_one_process(ElementKernelChoice::simd,
                                  SimulationSettings::StableStep::element);
}

TEST(Distributed, BarStepsWithTheSameBitsAsOneProcessScalarKernel) {
  expect_same_bits_as_one_process(ElementKernelChoice::scalar,
                                  SimulationSettings::StableStep::element);
}

// The default stable step: Lanczos iterations over the whole model, its vectors' ghosts
// exchanged and its dot products summed over the ranks.
TEST(Distributed, BarStepsWithTheSameBitsAsOneProcessAssembledStep) {
  expect_same_bits_as_one_process(ElementKernelChoice::simd,
                                  SimulationSettings::StableStep::assembled);
}

// What distributed runs cannot do yet is refused on every rank alike, before any exchange (so
// that no rank waits for another), naming what to change.
TEST(Distributed, WhatIsNotYetDistributedIsAnInputErrorOnEveryRank) {
  const Communicator& c = Communicator::world();
  ModelSpec s = vibrating_bar(SimulationSettings::StableStep::element);
  s.simulation.deformation_damping = 0.1;
  const Model global = build_model(s);
  const LocalPart part = local_part(global, partition_model(global, c.size()), c.rank(), 1);
  try {
    Simulation mine(local_model(global, part), Distribution{part, &c});
    FAIL() << "a scene with deformation damping ran distributed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "distributed runs cannot yet do this scene: simulation.deformation_damping"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(c.all(true));  // every rank got here
}
