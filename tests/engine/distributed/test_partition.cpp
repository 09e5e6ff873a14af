// SPDX-License-Identifier: GPL-3.0-or-later
// The partition of a distributed run (engine/distributed/partition.hpp): a large body cut into
// balanced parts along element faces, small bodies kept whole and dealt out by place, the same
// answer every time, and a clear error for a scene too small for the ranks.
#include <gtest/gtest.h>

#include <set>

#include "engine/distributed/partition.hpp"
#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"
#include "support/steel_bar.hpp"

using namespace femdem;

namespace {

ModelSpec boxes(int nx_bodies, int ny_bodies, int cells, Vec3 size) {
  ModelSpec s;
  s.materials.push_back(test::elastic_material("steel", 7800.0, 200e9, 0.3));
  for (int j = 0; j < ny_bodies; ++j)
    for (int i = 0; i < nx_bodies; ++i) {
      BodySpec b;
      // (appended piece by piece: GCC 12 warns, a false positive, on "b" + string)
      b.name = "b";
      b.name += std::to_string(i);
      b.name += '_';
      b.name += std::to_string(j);
      b.material = 0;
      b.mesh = test::kuhn_box(cells, cells, cells, size, 0.2, 1 + i + 7 * j);
      for (Vec3& p : b.mesh.nodes) p += Vec3(1.5 * size[0] * i, 1.5 * size[1] * j, 0.0);
      s.bodies.push_back(b);
    }
  return s;
}

}  // namespace

TEST(Partition, OneBodyIsCutIntoBalancedPartsAlongFaces) {
  const Model m = build_model(test::steel_bar());  // 12 x 3 x 3 cells, 648 elements
  for (int parts : {2, 3}) {
    const Partition p = partition_model(m, parts);
    ASSERT_EQ(p.element_rank.size(), static_cast<std::size_t>(m.element_count));
    const double share = static_cast<double>(m.element_count) / parts;
    for (int r = 0; r < parts; ++r)  // METIS's default imbalance allowance is 3 %
      EXPECT_NEAR(p.part_elements[r], share, 0.05 * share) << parts << " parts, rank " << r;
    // every node goes to the rank of its first element
    for (std::int32_t e = m.element_count - 1; e >= 0; --e)
      for (std::int32_t n : m.conn[e]) EXPECT_GE(p.node_rank[n], 0);
    // a cut along faces: far fewer nodes on a rank boundary than in the body (a 0.4 x 0.1
    // bar cut across has 2 x 7 x 7 such corner and mid-edge nodes, an interleaved one hundreds)
    int boundary = 0;
    std::vector<std::set<int>> ranks_of_node(m.node_count);
    for (std::int32_t e = 0; e < m.element_count; ++e)
      for (std::int32_t n : m.conn[e]) ranks_of_node[n].insert(p.element_rank[e]);
    for (const auto& s : ranks_of_node) boundary += s.size() > 1;
    EXPECT_LT(boundary, 60 * (parts - 1)) << parts << " parts";
    // the same answer again
    EXPECT_EQ(partition_model(m, parts).element_rank, p.element_rank);
  }
}

TEST(Partition, SmallBodiesStayWholeAndNeighboursShareARank) {
  // 8 x 2 boxes in a row along x: two ranks take the left and right halves, four ranks quarters
  const Model m = build_model(boxes(8, 2, 2, Vec3(0.1, 0.1, 0.1)));
  for (int parts : {2, 4}) {
    const Partition p = partition_model(m, parts);
    for (const Body& b : m.bodies) {
      const std::int32_t r = p.element_rank[b.first_element];
      for (std::int32_t e = b.first_element; e < b.first_element + b.element_count; ++e)
        ASSERT_EQ(p.element_rank[e], r) << b.name << " is cut";
      // the boxes are numbered along x first: box i of a row is in the (i / (8 / parts))-th slab
      const int i = std::stoi(b.name.substr(1, b.name.find('_') - 1));
      EXPECT_EQ(r, i / (8 / parts)) << b.name << ", " << parts << " ranks";
    }
    for (int r = 0; r < parts; ++r) EXPECT_EQ(p.part_elements[r], m.element_count / parts);
  }
}

TEST(Partition, ASceneTooSmallForTheRanksIsAnInputError) {
  ModelSpec s = boxes(1, 1, 1, Vec3(0.1, 0.1, 0.1));  // one body of 6 elements
  s.bodies[0].mesh = test::kuhn_box(1, 1, 1, Vec3(0.1, 0.1, 0.1));
  s.bodies[0].mesh.elements.resize(1);
  const Model m = build_model(s);
  EXPECT_NO_THROW(partition_model(m, 1));
  try {
    partition_model(m, 2);
    FAIL() << "a one-element scene was split among 2 ranks";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be split among 2 ranks"), std::string::npos)
        << e.what();
  }
}
