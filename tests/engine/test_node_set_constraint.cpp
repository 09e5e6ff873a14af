// SPDX-License-Identifier: GPL-3.0-or-later
// A constraint on a node set (a gmsh physical group, RegionSpec::Kind::Nodes) holds exactly the
// listed nodes of its body, counted from the body's first node, whatever bodies come before
// it; a node index past the body is an input error naming the set.
#include <gtest/gtest.h>

#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "support/steel_boxes.hpp"

using namespace femdem;

namespace {

ModelSpec two_boxes() {
  return test::steel_boxes(2, 2);
}

}  // namespace

TEST(NodeSetConstraint, HoldsExactlyTheListedNodesOfItsBody) {
  ModelSpec s = two_boxes();
  ConstraintSpec c;
  c.body = 1;  // the second body: its node indices start after the first body's
  c.region.kind = RegionSpec::Kind::Nodes;
  c.region.node_set = "bottom";
  for (std::size_t n = 0; n < s.bodies[1].mesh.nodes.size(); ++n)
    if (s.bodies[1].mesh.nodes[n].z() == 0.0)
      c.region.nodes.push_back(static_cast<std::int32_t>(n));
  c.fix = {true, true, true};
  s.constraints.push_back(c);
  const Model m = build_model(s);
  const std::int32_t first = m.bodies[1].first_node;
  int held = 0;
  for (int n = 0; n < m.node_count; ++n) {
    const bool expected = n >= first && m.X[3 * n + 2] == 0.0;
    for (int k = 0; k < 3; ++k) ASSERT_EQ(m.dof_mode[3 * n + k], expected ? 1 : 0) << n;
    held += expected;
  }
  EXPECT_EQ(held, static_cast<int>(c.region.nodes.size()));
  EXPECT_EQ(held, 5 * 5);  // the bottom face's 5 x 5 node grid
}

TEST(NodeSetConstraint, ANodePastTheBodyIsAnInputError) {
  ModelSpec s = two_boxes();
  ConstraintSpec c;
  c.body = 0;
  c.region.kind = RegionSpec::Kind::Nodes;
  c.region.node_set = "corner";
  c.region.nodes = {static_cast<std::int32_t>(s.bodies[0].mesh.nodes.size())};
  c.fix = {true, false, false};
  s.constraints.push_back(c);
  try {
    build_model(s);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node set 'corner'"), std::string::npos) << e.what();
  }
}
