// SPDX-License-Identifier: GPL-3.0-or-later
// One broadphase call against the number of boxes (Google Benchmark), NBS and FCL side by side:
//   Nbs/<N>: NbsBroadphase::find_pairs, warm (work arrays already grown, as in a run).
//   Fcl/<N>: fcl::DynamicAABBTreeCollisionManager: registerObjects + setup (tree build) + collide
//            collecting every overlapping pair of different bodies; the CollisionObjects (one
//            fcl::Box each, AABB computed) are made once outside the timing.
// Scene: spheres of radius 1 meshed with TET10 (io's generator, h = 0.5), the bounding boxes of
// their surface elements (corner tets with a boundary face) enlarged by 0.01 per side; spheres on
// a cubic lattice of spacing 2.02 with random jitter of +-0.02, so neighbours touch and contacts
// exist. N boxes = the first N of the lattice's boxes.
// Counters: ns_per_box (time / N: flat when the cost is linear), pairs, and for NBS
// bytes_per_box (its work arrays, memory_bytes() / N).
// Run: build/tools/bench/bench_broadphase --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "contact/nbs_broadphase.hpp"
#include "elements/tet10_surface.hpp"
#include "io/mesh/mesh_generators.hpp"

using namespace femdem;

namespace {

struct Scene {
  std::vector<Aabb> boxes;
  std::vector<std::int32_t> groups;
};

// Boxes of one sphere's surface elements, relative to its centre.
const std::vector<Aabb>& sphere_surface_boxes() {
  static const std::vector<Aabb> boxes = [] {
    const Tet10Mesh mesh = generate_sphere(1.0, 0.5);
    std::vector<Aabb> out;
    std::vector<bool> on_surface(mesh.elements.size(), false);
    for (const BoundaryFace& f : boundary_faces(mesh.elements)) on_surface[f.element] = true;
    const double margin = 0.01;
    for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
      if (!on_surface[e]) continue;
      Aabb b;
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = 1e300;
        b.hi[a] = -1e300;
      }
      for (int k = 0; k < 4; ++k) {
        const Vec3& x = mesh.nodes[mesh.elements[e][k]];
        for (int a = 0; a < 3; ++a) {
          b.lo[a] = std::min(b.lo[a], x[a] - margin);
          b.hi[a] = std::max(b.hi[a], x[a] + margin);
        }
      }
      out.push_back(b);
    }
    return out;
  }();
  return boxes;
}

const Scene& scene(std::size_t n) {
  static std::map<std::size_t, Scene> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const auto& local = sphere_surface_boxes();
  const std::size_t spheres = (n + local.size() - 1) / local.size();
  const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(spheres))));
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  Scene s;
  s.boxes.reserve(n);
  s.groups.reserve(n);
  for (std::size_t sp = 0; s.boxes.size() < n; ++sp) {
    const double c[3] = {2.02 * static_cast<double>(sp % side) + jitter(rng),
                         2.02 * static_cast<double>((sp / side) % side) + jitter(rng),
                         2.02 * static_cast<double>(sp / (side * side)) + jitter(rng)};
    for (const Aabb& b : local) {
      if (s.boxes.size() == n) break;
      Aabb t;
      for (int a = 0; a < 3; ++a) {
        t.lo[a] = b.lo[a] + c[a];
        t.hi[a] = b.hi[a] + c[a];
      }
      s.boxes.push_back(t);
      s.groups.push_back(static_cast<std::int32_t>(sp));
    }
  }
  return cache.emplace(n, std::move(s)).first->second;
}

void Nbs(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  NbsBroadphase nbs;
  std::vector<CandidatePair> pairs;
  nbs.find_pairs(s.boxes, s.groups, pairs);  // warm: grow the work arrays once
  for (auto _ : state) {
    nbs.find_pairs(s.boxes, s.groups, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  const double n = static_cast<double>(s.boxes.size());
  state.counters["ns_per_box"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs"] = static_cast<double>(pairs.size());
  state.counters["bytes_per_box"] = static_cast<double>(nbs.memory_bytes()) / n;
  state.counters["tests_per_box"] = static_cast<double>(nbs.box_tests()) / n;
}

struct FclCollect {
  const std::vector<std::int32_t>* groups = nullptr;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
};

bool fcl_collect(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
  auto* c = static_cast<FclCollect*>(data);
  const auto i = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(a->getUserData()));
  const auto j = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(b->getUserData()));
  if ((*c->groups)[i] != (*c->groups)[j]) c->found.emplace_back(i, j);
  return false;
}

void Fcl(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> raw;
  objects.reserve(s.boxes.size());
  for (std::size_t k = 0; k < s.boxes.size(); ++k) {
    const Aabb& b = s.boxes[k];
    auto shape =
        std::make_shared<fcl::Boxd>(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]);
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = fcl::Vector3d(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]),
                                     0.5 * (b.lo[2] + b.hi[2]));
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(shape, tf));
    objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(k)));
    raw.push_back(objects.back().get());
  }
  FclCollect c;
  c.groups = &s.groups;
  for (auto _ : state) {
    c.found.clear();
    fcl::DynamicAABBTreeCollisionManagerd manager;
    manager.registerObjects(raw);
    manager.setup();
    manager.collide(&c, fcl_collect);
    benchmark::DoNotOptimize(c.found.data());
  }
  state.counters["ns_per_box"] = benchmark::Counter(
      static_cast<double>(s.boxes.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs"] = static_cast<double>(c.found.size());
}

void sizes(benchmark::internal::Benchmark* b) {
  for (long n : {1000L, 10000L, 100000L, 1000000L}) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(Nbs)->Apply(sizes);
BENCHMARK(Fcl)->Apply(sizes);
BENCHMARK_MAIN();
