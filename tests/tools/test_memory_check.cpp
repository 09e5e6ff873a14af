// SPDX-License-Identifier: GPL-3.0-or-later
// The memory check before a model is built (tools/femdem/run/memory_check.hpp): the estimate
// counts the scene's nodes and elements with the measured costs (docs/PERFORMANCE.md "Memory",
// where it is compared with the peak resident size of real runs), and a model above the
// available memory is refused with the estimate, the available memory and the fix.
#include "tools/femdem/run/memory_check.hpp"

#include <gtest/gtest.h>

#include "engine/errors.hpp"
#include "engine/memory_estimate.hpp"
#include "io/mesh/mesh_generators.hpp"

namespace femdem {
namespace {

ModelSpec two_boxes() {
  ModelSpec spec;
  for (int i = 0; i < 2; ++i) {
    BodySpec b;
    b.name = "box" + std::to_string(i);
    b.mesh = generate_box(Vec3(1, 1, 1), 0.25);
    spec.bodies.push_back(b);
  }
  return spec;
}

TEST(MemoryCheck, CountsEveryBodysNodesAndElements) {
  const ModelSpec spec = two_boxes();
  const MemoryEstimate e = estimate_memory(spec);
  EXPECT_EQ(e.nodes, 2 * static_cast<std::int64_t>(spec.bodies[0].mesh.nodes.size()));
  EXPECT_EQ(e.elements, 2 * static_cast<std::int64_t>(spec.bodies[0].mesh.elements.size()));
  EXPECT_DOUBLE_EQ(e.bytes,
                   kMemoryBase + kMemoryPerElement * e.elements + kMemoryPerNode * e.nodes);
}

TEST(MemoryCheck, AModelAboveTheAvailableMemoryIsRefusedWithTheEstimate) {
  const ModelSpec spec = two_boxes();
  const double need = estimate_memory(spec).bytes;
  EXPECT_NO_THROW(check_memory(spec, 2.0 * need));
  EXPECT_NO_THROW(check_memory(spec, -1.0));  // unknown: not refused
  try {
    check_memory(spec, 0.5 * need);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("TET10 elements needs about"), std::string::npos) << m;
    EXPECT_NE(m.find("available on this machine now: coarsen the meshes"), std::string::npos) << m;
  }
  EXPECT_GT(available_memory_bytes(), 0.0);  // Linux: /proc/meminfo
}

}  // namespace
}  // namespace femdem
