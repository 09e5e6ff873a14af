// SPDX-License-Identifier: GPL-3.0-or-later
// The NBS broadphase against two independent references: the O(N^2) double loop and FCL's
// dynamic AABB tree (DynamicAABBTreeCollisionManager, all overlapping pairs through its collide
// callback). Plus the edge cases, the no-allocation promise, and the Verlet-buffer rule.
#include <gtest/gtest.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <random>
#include <stdexcept>
#include <vector>

#include "contact/nbs_broadphase.hpp"
#include "contact/verlet_buffer.hpp"

using namespace femdem;

// Counts heap allocations, to test that find_pairs does not allocate once warmed up. Replacing
// the global operator new is legal in a program; this test file is its own executable.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace
// GCC flags malloc/free inside replaced operators as mismatched (a false positive here: new and
// delete are replaced together).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

using Pairs = std::vector<CandidatePair>;

struct Scene {
  std::vector<Aabb> boxes;
  std::vector<std::int32_t> groups;
  void add(const Aabb& b, std::int32_t g) {
    boxes.push_back(b);
    groups.push_back(g);
  }
};

Aabb box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return Aabb{{x0, y0, z0}, {x1, y1, z1}};
}

Pairs brute_force(const Scene& s) {
  Pairs out;
  for (std::size_t i = 0; i < s.boxes.size(); ++i)
    for (std::size_t j = i + 1; j < s.boxes.size(); ++j)
      if (s.groups[i] != s.groups[j] && boxes_overlap(s.boxes[i], s.boxes[j]))
        out.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
  return out;  // sorted by construction
}

struct FclCollect {
  const std::vector<std::int32_t>* groups = nullptr;
  Pairs pairs;
};

bool fcl_collect(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto* c = static_cast<FclCollect*>(data);
  auto i = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(a->getUserData()));
  auto j = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(b->getUserData()));
  if ((*c->groups)[i] != (*c->groups)[j]) c->pairs.push_back({std::min(i, j), std::max(i, j)});
  return false;  // keep going
}

// FCL's broadphase on the same boxes: an fcl::Box of the box's sides at the box's centre. The
// scenes use dyadic coordinates, so centre +- side / 2 reproduces lo and hi exactly (checked).
Pairs fcl_pairs(const Scene& s) {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  for (std::size_t k = 0; k < s.boxes.size(); ++k) {
    const Aabb& b = s.boxes[k];
    auto shape =
        std::make_shared<fcl::Boxd>(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]);
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = fcl::Vector3d(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]),
                                     0.5 * (b.lo[2] + b.hi[2]));
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(shape, tf));
    objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(k)));
    const fcl::AABBd& a = objects.back()->getAABB();
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(a.min_[d], b.lo[d]) << "FCL's box " << k << " differs: scene not dyadic";
      EXPECT_EQ(a.max_[d], b.hi[d]) << "FCL's box " << k << " differs: scene not dyadic";
    }
    raw.push_back(objects.back().get());
  }
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObjects(raw);
  manager.setup();
  FclCollect c;
  c.groups = &s.groups;
  manager.collide(&c, fcl_collect);
  std::sort(c.pairs.begin(), c.pairs.end());
  return c.pairs;
}

Pairs nbs_pairs(const Scene& s) {
  NbsBroadphase nbs;
  Pairs out;
  nbs.find_pairs(s.boxes, s.groups, out);
  return out;
}

bool sorted_unique(const Pairs& p) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!(p[k].i < p[k].j)) return false;
    if (k > 0 && !(p[k - 1] < p[k])) return false;
  }
  return true;
}

// Many bodies, each a cluster of boxes (like the surface sub-tets of a small body) around a
// random centre. All coordinates are multiples of 1/8, so FCL sees the very same boxes and many
// boxes touch exactly (testing the closed-interval convention). `large` is the fraction of
// bodies whose boxes are `large_factor` times bigger.
struct SceneSpec {
  unsigned seed;
  int bodies;
  int boxes_per_body;
  double domain;  // body centres uniform in [0, domain]^3
  double large;
  double large_factor;
  int shuffle;  // 1: boxes of all bodies interleaved in input order
  int cluster;  // > 1: bodies in clusters of this many (centres within +-3), so sparse scenes
                // still have contacts
};

Scene random_scene(const SceneSpec& spec) {
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto eighth = [](double x) { return std::round(8.0 * x) / 8.0; };
  Scene s;
  double cluster_centre[3] = {0, 0, 0};
  for (int b = 0; b < spec.bodies; ++b) {
    if (spec.cluster <= 1 || b % spec.cluster == 0)
      for (double& c : cluster_centre) c = eighth(spec.domain * u(rng));
    const double spread = spec.cluster > 1 ? 3.0 : 0.0;
    const double cx = eighth(cluster_centre[0] + spread * (2 * u(rng) - 1)),
                 cy = eighth(cluster_centre[1] + spread * (2 * u(rng) - 1)),
                 cz = eighth(cluster_centre[2] + spread * (2 * u(rng) - 1));
    const double size = u(rng) < spec.large ? spec.large_factor : 1.0;
    for (int k = 0; k < spec.boxes_per_body; ++k) {
      const double x = eighth(cx + 2 * size * (u(rng) - 0.5)),
                   y = eighth(cy + 2 * size * (u(rng) - 0.5)),
                   z = eighth(cz + 2 * size * (u(rng) - 0.5));
      s.add(box(x, y, z, x + eighth(size * u(rng)), y + eighth(size * u(rng)),
                z + eighth(size * u(rng))),
            b);
    }
  }
  if (spec.shuffle) {
    std::vector<std::size_t> perm(s.boxes.size());
    for (std::size_t k = 0; k < perm.size(); ++k) perm[k] = k;
    std::shuffle(perm.begin(), perm.end(), rng);
    Scene t;
    for (std::size_t k : perm) t.add(s.boxes[k], s.groups[k]);
    s = t;
  }
  return s;
}

class RandomScenes : public ::testing::TestWithParam<SceneSpec> {};

}  // namespace

TEST_P(RandomScenes, EqualBruteForceAndFcl) {
  const Scene s = random_scene(GetParam());
  ASSERT_GE(s.boxes.size(), 2000u);
  const Pairs expected = brute_force(s);
  const Pairs nbs = nbs_pairs(s);
  const Pairs fcl = fcl_pairs(s);
  EXPECT_GT(expected.size(), 0u) << "scene too sparse to test anything";
  EXPECT_TRUE(sorted_unique(nbs));
  EXPECT_EQ(nbs.size(), expected.size());
  EXPECT_TRUE(nbs == expected) << "NBS differs from the O(N^2) loop";
  EXPECT_EQ(fcl.size(), expected.size());
  EXPECT_TRUE(fcl == expected) << "FCL differs from the O(N^2) loop";
}

// seed, bodies, boxes per body, domain, large fraction, large factor, shuffle, cluster
INSTANTIATE_TEST_SUITE_P(
    NbsBroadphase, RandomScenes,
    ::testing::Values(SceneSpec{1, 400, 10, 25.0, 0.0, 1.0, 0, 1},    // dense, equal sizes
                      SceneSpec{2, 400, 10, 25.0, 0.0, 1.0, 1, 1},    // same, input shuffled
                      SceneSpec{3, 300, 12, 400.0, 0.0, 1.0, 0, 4},   // sparse
                      SceneSpec{4, 500, 8, 30.0, 0.1, 4.0, 1, 1},     // dense, mixed sizes
                      SceneSpec{5, 250, 16, 200.0, 0.05, 8.0, 0, 5},  // sparse, mixed sizes
                      SceneSpec{6, 1000, 4, 12.0, 0.0, 1.0, 1, 1},    // very dense
                      SceneSpec{7, 200, 20, 1e6, 0.0, 1.0, 0, 3},     // widely scattered
                      SceneSpec{8, 600, 6, 60.0, 0.2, 2.0, 1, 2}));

TEST(NbsBroadphase, EmptyAndSingleBox) {
  NbsBroadphase nbs;
  Pairs out{{0, 1}};  // stale content must be cleared
  nbs.find_pairs({}, {}, out);
  EXPECT_TRUE(out.empty());
  Scene s;
  s.add(box(0, 0, 0, 1, 1, 1), 0);
  out = {{0, 1}};
  nbs.find_pairs(s.boxes, s.groups, out);
  EXPECT_TRUE(out.empty());
}

TEST(NbsBroadphase, OneGroupGivesNoPairs) {
  Scene s = random_scene({11, 100, 10, 5.0, 0.0, 1.0, 0, 1});
  std::fill(s.groups.begin(), s.groups.end(), 7);
  EXPECT_TRUE(nbs_pairs(s).empty());
  // One box of another group brings exactly the pairs with that box.
  s.add(box(2, 2, 2, 3, 3, 3), 8);
  const Pairs expected = brute_force(s);
  EXPECT_GT(expected.size(), 0u);
  for (const auto& p : expected) EXPECT_EQ(p.j, s.boxes.size() - 1);
  EXPECT_EQ(nbs_pairs(s), expected);
}

TEST(NbsBroadphase, TouchingBoxesOverlap) {
  Scene s;
  s.add(box(0, 0, 0, 1, 1, 1), 0);
  s.add(box(1, 0, 0, 2, 1, 1), 1);          // shares a face with 0
  s.add(box(1, 1, 0, 2, 2, 1), 2);          // shares an edge with 0, a face with 1
  s.add(box(1, 1, 1, 2, 2, 2), 3);          // shares a corner with 0
  s.add(box(1.0078125, 0, 0, 2, 1, 1), 4);  // just apart from 0 (1 + 2^-7: dyadic for FCL)
  s.add(box(-1, -1, -1, -0.5, 2, 2), 5);    // apart from all
  const Pairs expected{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {1, 4}, {2, 3}, {2, 4}, {3, 4}};
  EXPECT_EQ(brute_force(s), expected);
  EXPECT_EQ(nbs_pairs(s), expected);
  EXPECT_EQ(fcl_pairs(s), expected);
}

TEST(NbsBroadphase, ZeroSizeBoxes) {
  Scene s;
  s.add(box(0, 0, 0, 1, 1, 1), 0);
  s.add(box(0.5, 1, 0.5, 0.5, 1, 0.5), 1);  // a point on 0's face
  s.add(box(0.5, 1, 0.5, 0.5, 1, 0.5), 2);  // the same point, another body
  s.add(box(0.5, 1, 0.5, 0.5, 1, 0.5), 2);  // again, same body as 2
  s.add(box(3, 3, 3, 3, 3, 3), 3);          // an isolated point
  s.add(box(0, 0, 2, 1, 1, 2), 4);          // a flat square
  s.add(box(0.5, 0.5, 2, 0.5, 0.5, 2), 5);  // a point inside the square
  const Pairs expected{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {5, 6}};
  EXPECT_EQ(brute_force(s), expected);
  EXPECT_EQ(nbs_pairs(s), expected);
  EXPECT_EQ(fcl_pairs(s), expected);

  // Only points: the largest extent is 0, so the cell size falls back to the mean spacing.
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> lattice(0, 20);
  Scene p;
  for (int k = 0; k < 3000; ++k) {
    const double x = lattice(rng), y = lattice(rng), z = lattice(rng);
    p.add(box(x, y, z, x, y, z), k % 50);
  }
  const Pairs ep = brute_force(p);
  EXPECT_GT(ep.size(), 0u);
  EXPECT_EQ(nbs_pairs(p), ep);
  EXPECT_EQ(fcl_pairs(p), ep);
  // All at one point.
  Scene q;
  for (int k = 0; k < 50; ++k) q.add(box(1, 2, 3, 1, 2, 3), k % 3);
  EXPECT_EQ(nbs_pairs(q), brute_force(q));
  EXPECT_EQ(nbs_pairs(q).size(), 50u * 49 / 2 - 3 * (17 * 16 / 2) + (17 * 16 / 2 - 16 * 15 / 2));
}

// Boxes whose size equals the spacing and non-dyadic coordinates (k * 0.1), so box faces fall
// on cell boundaries up to rounding: the 1e-6 margin of the cell size must absorb it.
TEST(NbsBroadphase, RoundingAtCellBoundaries) {
  Scene s;
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> lattice(0, 40);
  for (int k = 0; k < 4000; ++k) {
    const double x = 0.1 * lattice(rng), y = 0.1 * lattice(rng), z = 0.1 * lattice(rng);
    s.add(box(x, y, z, x + 0.1, y + 0.1, z + 0.1), k);
  }
  // far from the origin too, where 0.1 has fewer bits
  for (int k = 0; k < 2000; ++k) {
    const double x = 1e4 + 0.3 * lattice(rng), y = 1e4 + 0.3 * lattice(rng),
                 z = -1e4 + 0.3 * lattice(rng);
    s.add(box(x, y, z, x + 0.3, y + 0.3, z + 0.3), 100000 + k);
  }
  const Pairs expected = brute_force(s);
  EXPECT_GT(expected.size(), 1000u);
  EXPECT_EQ(nbs_pairs(s), expected);
}

// One box as large as the scene: correct, at the cost the header documents (all boxes in one
// cell: N^2 / 2 tests).
TEST(NbsBroadphase, VeryDifferentSizes) {
  Scene s = random_scene({21, 300, 10, 40.0, 0.0, 1.0, 0, 1});
  s.add(box(-5, -5, -5, 50, 50, 50), -1);
  s.add(box(10, 10, 10, 30, 12, 12), -2);  // a long one
  const Pairs expected = brute_force(s);
  NbsBroadphase nbs;
  Pairs out;
  nbs.find_pairs(s.boxes, s.groups, out);
  EXPECT_EQ(out, expected);
  EXPECT_EQ(fcl_pairs(s), expected);
  std::size_t with_huge = 0;
  for (const auto& p : out) with_huge += p.j == 3000;
  EXPECT_EQ(with_huge, 3000u);
  EXPECT_GE(nbs.cell_size(), 55.0);
}

TEST(NbsBroadphase, InvalidInputNamesTheBox) {
  NbsBroadphase nbs;
  Pairs out;
  Scene s = random_scene({31, 10, 2, 5.0, 0.0, 1.0, 0, 1});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto expect_throw = [&](const Scene& t, const std::string& text) {
    try {
      nbs.find_pairs(t.boxes, t.groups, out);
      ADD_FAILURE() << "no throw, expected: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  Scene t = s;
  t.boxes[3].lo[1] = nan;
  expect_throw(t, "box 3 has a non-finite coordinate");
  t = s;
  t.boxes[17].hi[2] = inf;
  expect_throw(t, "box 17 has a non-finite coordinate");
  t = s;
  t.boxes[0].lo[0] = -inf;
  expect_throw(t, "box 0 has a non-finite coordinate");
  t = s;
  t.boxes[5].lo[0] = t.boxes[5].hi[0] + 1;
  expect_throw(t, "box 5 has lo > hi");
  t = s;
  t.groups.pop_back();
  expect_throw(t, "20 boxes but 19 group ids");
  // A non-finite box is reported even when it is alone or all boxes share a group.
  Scene one;
  one.add(box(0, 0, nan, 1, 1, 1), 0);
  expect_throw(one, "box 0 has a non-finite coordinate");
}

// Bodies far apart with tiny boxes: a grid over the bounding box would have ~1e18 cells (and
// ~1e40 at 1e12 apart); the work arrays must stay proportional to N, and at 1e5 apart the cells
// must still be fine enough that few boxes share a cell.
TEST(NbsBroadphase, WidelyScatteredBodiesUseLinearMemory) {
  for (const double spread : {1e5, 1e12}) {
    Scene s;
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double far[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, -1, 0.3}, {0.5, 0.5, 1}};
    for (int k = 0; k < 4000; ++k) {
      const double* c = far[k % 4];
      const double x = spread * c[0] + u(rng), y = spread * c[1] + u(rng),
                   z = spread * c[2] + u(rng);
      s.add(box(x, y, z, x + 0.05, y + 0.05, z + 0.05), k);
    }
    NbsBroadphase nbs;
    Pairs out;
    nbs.find_pairs(s.boxes, s.groups, out);
    EXPECT_EQ(out, brute_force(s)) << spread;
    EXPECT_GT(out.size(), 0u);
    // 92 bytes per box plus 8 per pair (see memory_bytes()); allow for vector growth
    EXPECT_LT(nbs.memory_bytes(), 2 * (92 * s.boxes.size() + 8 * out.size()) + 4096) << spread;
    EXPECT_LE(nbs.occupied_cells(), s.boxes.size());
    if (spread == 1e5) {
      EXPECT_LT(nbs.cell_size(), 0.08);  // 1.5e5 / 2^21
      EXPECT_LT(nbs.box_tests(), 20 * s.boxes.size());
    }
  }
}

TEST(NbsBroadphase, NoAllocationOnceWarm) {
  const Scene big = random_scene({51, 400, 10, 25.0, 0.1, 2.0, 1, 1});
  const Scene small = random_scene({52, 100, 10, 10.0, 0.0, 1.0, 0, 1});
  NbsBroadphase nbs;
  Pairs out;
  nbs.find_pairs(big.boxes, big.groups, out);
  const Pairs first = out;
  const std::size_t bytes = nbs.memory_bytes();
  const long before = g_allocations.load();
  nbs.find_pairs(big.boxes, big.groups, out);
  nbs.find_pairs(small.boxes, small.groups, out);
  const std::size_t small_pairs = out.size();
  nbs.find_pairs(big.boxes, big.groups, out);
  const long after = g_allocations.load();
  EXPECT_EQ(small_pairs, brute_force(small).size());
  EXPECT_EQ(after - before, 0) << "find_pairs allocated in steady state";
  EXPECT_EQ(nbs.memory_bytes(), bytes);
  EXPECT_EQ(out, first);
}

// The Verlet rule in isolation.
TEST(VerletBuffer, RebuildBeyondHalfTheBuffer) {
  EXPECT_THROW(VerletBuffer(0.0), std::invalid_argument);
  EXPECT_THROW(VerletBuffer(-1.0), std::invalid_argument);
  EXPECT_THROW(VerletBuffer(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  VerletBuffer vb(0.2);
  std::vector<Vec3> x{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(vb.needs_rebuild(x));  // nothing recorded yet
  vb.record(x);
  EXPECT_FALSE(vb.needs_rebuild(x));
  x[1] += Vec3(0.0, 0.06, 0.08);  // |d| = 0.1 = buffer / 2: still safe
  EXPECT_NEAR(vb.max_displacement(x), 0.1, 1e-15);
  EXPECT_FALSE(vb.needs_rebuild(x));
  x[2] += Vec3(0, 0, 0.1001);
  EXPECT_TRUE(vb.needs_rebuild(x));
  vb.record(x);
  EXPECT_FALSE(vb.needs_rebuild(x));
  x[0].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(vb.needs_rebuild(x));
  x[0].x() = 0;
  EXPECT_FALSE(vb.needs_rebuild(x));
  x.push_back(Vec3::Zero());  // node count changed
  EXPECT_TRUE(vb.needs_rebuild(x));
}

namespace {

// Entities of 4 nodes (tets); their bounding boxes enlarged by `margin` per side.
void entity_boxes(const std::vector<Vec3>& x, double margin, std::vector<Aabb>& out) {
  out.resize(x.size() / 4);
  for (std::size_t e = 0; e < out.size(); ++e) {
    Aabb b{{x[4 * e].x(), x[4 * e].y(), x[4 * e].z()}, {x[4 * e].x(), x[4 * e].y(), x[4 * e].z()}};
    for (int k = 1; k < 4; ++k)
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = std::min(b.lo[a], x[4 * e + k][a]);
        b.hi[a] = std::max(b.hi[a], x[4 * e + k][a]);
      }
    for (int a = 0; a < 3; ++a) {
      b.lo[a] -= margin;
      b.hi[a] += margin;
    }
    out[e] = b;
  }
}

}  // namespace

// The property the rule exists for: while no node has moved more than buffer / 2, every pair of
// entities whose true boxes overlap is in the list built at the start; and the bound is tight.
TEST(VerletBuffer, ListStaysCompleteWithinHalfBuffer) {
  const double buffer = 0.1;
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x0;
  std::vector<std::int32_t> groups;
  for (int e = 0; e < 3000; ++e) {
    const Vec3 c(6 * u(rng), 6 * u(rng), 6 * u(rng));
    for (int k = 0; k < 4; ++k) x0.push_back(c + 0.15 * Vec3(u(rng), u(rng), u(rng)));
    groups.push_back(e / 3);
  }
  VerletBuffer vb(buffer);
  NbsBroadphase nbs;
  std::vector<Aabb> boxes;
  entity_boxes(x0, vb.margin(), boxes);
  Pairs listed;
  nbs.find_pairs(boxes, groups, listed);
  vb.record(x0);

  for (int trial = 0; trial < 5; ++trial) {
    // Every node moves by up to buffer / 2 (most by exactly that, in random directions).
    std::vector<Vec3> x = x0;
    for (auto& p : x) {
      Vec3 d(u(rng), u(rng), u(rng));
      if (d.norm() < 1e-3) continue;
      const double len = (trial == 0 ? 1.0 : std::abs(u(rng))) * vb.margin() * (1 - 1e-12);
      p += len * d.normalized();
    }
    ASSERT_FALSE(vb.needs_rebuild(x));
    std::vector<Aabb> now;
    entity_boxes(x, 0.0, now);
    Pairs touching;
    nbs.find_pairs(now, groups, touching);
    ASSERT_GT(touching.size(), 0u);
    for (const auto& p : touching)
      EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), p))
          << "pair " << p.i << "," << p.j << " missed by the list at trial " << trial;
  }

  // Tight: two entities 1.01 buffer apart are not listed; each moving 0.51 buffer towards the
  // other makes them touch, and exactly then the rule asks for a rebuild.
  std::vector<Vec3> y{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int k = 0; k < 4; ++k) y.push_back(y[k] + Vec3(1 + 1.01 * buffer, 0, 0));
  const std::vector<std::int32_t> two{0, 1};
  entity_boxes(y, vb.margin(), boxes);
  nbs.find_pairs(boxes, two, listed);
  EXPECT_TRUE(listed.empty());
  vb.record(y);
  for (int k = 0; k < 4; ++k) {
    y[k].x() += 0.51 * buffer;
    y[4 + k].x() -= 0.51 * buffer;
  }
  entity_boxes(y, 0.0, boxes);
  nbs.find_pairs(boxes, two, listed);
  EXPECT_EQ(listed.size(), 1u);
  EXPECT_TRUE(vb.needs_rebuild(y));
}
