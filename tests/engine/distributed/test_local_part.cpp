// SPDX-License-Identifier: GPL-3.0-or-later
// What each rank of a distributed run holds (engine/distributed/local_part.hpp): every element
// and node owned exactly once, the exchange lists of two ranks naming the same nodes in the
// same order, and the point of it all: the internal force on every node a rank owns has the
// same bits as in one process, for plain elements (one layer of held elements) and for nodal
// F-bar (three layers; two are shown to be not enough).
#include <gtest/gtest.h>

#include <random>

#include "engine/distributed/local_part.hpp"
#include "engine/simulation.hpp"
#include "support/steel_bar.hpp"

using namespace femdem;

namespace {

// A 12 x 3 x 3-cell bar, its corners moved at random by up to 2 % of a cell (a deformed state
// with forces everywhere).
Model deformed_bar(FbarMode fbar) {
  const ModelSpec s = test::steel_bar(fbar);
  Model m = build_model(s);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& x : m.x) x += 0.02 * 0.033 * u(rng);
  return m;
}

std::vector<std::int32_t> global_ids(const LocalPart& p, const std::vector<std::int32_t>& local) {
  std::vector<std::int32_t> g;
  for (std::int32_t k : local) g.push_back(p.nodes[k]);
  return g;
}

}  // namespace

TEST(LocalPart, OwnsEachElementAndNodeOnceAndExchangeListsAgree) {
  const Model m = deformed_bar(FbarMode::Off);
  for (int parts : {2, 3}) {
    const Partition p = partition_model(m, parts);
    std::vector<LocalPart> lp;
    for (int r = 0; r < parts; ++r) lp.push_back(local_part(m, p, r, 1));
    std::vector<int> element_owners(m.element_count, 0), node_owners(m.node_count, 0);
    for (const LocalPart& l : lp) {
      for (std::size_t k = 0; k < l.elements.size(); ++k)
        element_owners[l.elements[k]] += l.element_owned[k];
      for (std::size_t k = 0; k < l.nodes.size(); ++k) node_owners[l.nodes[k]] += l.node_owned[k];
      // every element around an owned node is held
      std::vector<std::uint8_t> held(m.element_count, 0);
      for (std::int32_t e : l.elements) held[e] = 1;
      for (std::size_t k = 0; k < l.nodes.size(); ++k) {
        if (!l.node_owned[k]) continue;
        const std::int32_t n = l.nodes[k];
        for (std::int32_t s = m.node_elem_offset[n]; s < m.node_elem_offset[n + 1]; ++s)
          EXPECT_TRUE(held[m.node_elem_slot[s] / 10]) << "rank " << l.rank << ", node " << n;
      }
      // every held node that is not owned is received from its owner
      std::size_t received = 0;
      for (const auto& nb : l.neighbours) received += nb.receive.size();
      EXPECT_EQ(received, l.nodes.size() - std::count(l.node_owned.begin(), l.node_owned.end(), 1));
    }
    for (int c : element_owners) EXPECT_EQ(c, 1);
    for (int c : node_owners) EXPECT_EQ(c, 1);
    for (const LocalPart& a : lp)
      for (const auto& nb : a.neighbours) {
        const LocalPart& b = lp[nb.rank];
        const auto it = std::find_if(b.neighbours.begin(), b.neighbours.end(),
                                     [&](const auto& x) { return x.rank == a.rank; });
        ASSERT_NE(it, b.neighbours.end());
        EXPECT_EQ(global_ids(a, nb.receive), global_ids(b, it->send));
        EXPECT_EQ(global_ids(a, nb.send), global_ids(b, it->receive));
        EXPECT_FALSE(nb.receive.empty()) << parts << " parts: " << a.rank << " <- " << nb.rank;
      }
  }
}

// Simulation's constructor computes the internal forces at the model's positions.
void expect_owned_forces_equal(FbarMode fbar, int layers, bool equal) {
  const Model m = deformed_bar(fbar);
  const Simulation whole(m);
  for (int parts : {2, 3}) {
    const Partition p = partition_model(m, parts);
    int differing = 0, owned = 0;
    for (int r = 0; r < parts; ++r) {
      const LocalPart lp = local_part(m, p, r, layers);
      const Simulation part(local_model(m, lp));
      for (std::size_t k = 0; k < lp.nodes.size(); ++k) {
        if (!lp.node_owned[k]) continue;
        ++owned;
        for (int d = 0; d < 3; ++d) {
          const double a = part.model().f_int[3 * k + d],
                       b = whole.model().f_int[3 * lp.nodes[k] + d];
          ASSERT_NE(b, 0.0);
          differing += a != b;  // bits, not a tolerance
        }
      }
    }
    EXPECT_EQ(owned, m.node_count);
    if (equal)
      EXPECT_EQ(differing, 0) << parts << " parts";
    else
      EXPECT_GT(differing, 0) << parts << " parts";
  }
}

TEST(LocalModel, OwnedNodesGetTheSameForceBitsAsOneProcess) {
  expect_owned_forces_equal(FbarMode::Off, 1, true);
  expect_owned_forces_equal(FbarMode::Centroid, 1, true);
}

TEST(LocalModel, NodalFbarNeedsThreeLayersOfHeldElements) {
  EXPECT_EQ(ghost_layers(deformed_bar(FbarMode::Nodal)), 3);
  EXPECT_EQ(ghost_layers(deformed_bar(FbarMode::Off)), 1);
  expect_owned_forces_equal(FbarMode::Nodal, 3, true);
  expect_owned_forces_equal(FbarMode::Nodal, 2, false);
}
