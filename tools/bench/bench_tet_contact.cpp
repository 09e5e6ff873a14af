// SPDX-License-Identifier: GPL-3.0-or-later
// The tet-tet penalty-potential pair kernel (contact/tet_potential_contact.hpp), one core:
//   TetContact/0  overlapping, deep: B's centre within 0.5 of A's (tets of size about 1)
//   TetContact/1  overlapping, shallow: B pushed in along a random direction until the overlap
//                 is 0.1-2 % of the smaller volume (what contact between bodies looks like)
//   TetContact/2  apart, boxes disjoint (rejected by the box test)
//   TetContact/3  apart, boxes overlap (rejected by a face plane or, failing that, by clipping)
// The second argument is the clipper: 0 the kernel (regions clipped into sets of tetrahedra), 1
// the same integral with the regions clipped as polyhedra (tests/support/convex_polyhedron.hpp),
// measured on the same pairs in one run. Reports pairs per second
// (items_per_second). Run:
//   build/tools/bench/bench_tet_contact --benchmark_repetitions=3
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/tet_potential_contact.hpp"
#include "contact/tet_potential_integral.hpp"
#include "tests/support/convex_polyhedron.hpp"

using femdem::contact::tet_potential_contact;
using femdem::contact::tet_potential_contact_with;
using femdem::contact::TetCorners;
using femdem::contact::TetPairContact;

namespace {

constexpr int kPool = 1024;  // distinct pairs, cycled

double volume(const TetCorners& t) {
  double e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d) e[k][d] = t[k + 1][d] - t[0][d];
  return std::abs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                  e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                  e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

TetCorners random_tet(std::mt19937_64& rng, double cx, double cy, double cz) {
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  for (;;) {
    TetCorners t;
    for (auto& x : t) x = {cx + u(rng), cy + u(rng), cz + u(rng)};
    if (volume(t) >= 0.03) return t;
  }
}

TetCorners shifted(TetCorners t, const double* dir, double s) {
  for (auto& x : t)
    for (int d = 0; d < 3; ++d) x[d] += s * dir[d];
  return t;
}

std::vector<std::pair<TetCorners, TetCorners>> pairs(int kind) {
  std::mt19937_64 rng(2024 + kind);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<std::pair<TetCorners, TetCorners>> out;
  TetPairContact c{};
  while (static_cast<int>(out.size()) < kPool) {
    const TetCorners a = random_tet(rng, 0, 0, 0);
    if (kind == 0) {
      const TetCorners b = random_tet(rng, u(rng), u(rng), u(rng));
      if (tet_potential_contact(a, b, 1.0, c)) out.emplace_back(a, b);
    } else if (kind == 1) {
      // Bisect the distance along a random direction for an overlap of 0.1-2 % of the volume.
      const TetCorners b0 = random_tet(rng, 0, 0, 0);
      double dir[3] = {n(rng), n(rng), n(rng)};
      const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      for (double& x : dir) x /= len;
      const double vmin = std::min(volume(a), volume(b0));
      double lo = 0.0, hi = 3.0;  // overlapping at lo, apart at hi
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        c = TetPairContact{};
        tet_potential_contact(a, shifted(b0, dir, mid), 1.0, c);
        const double f = c.overlap_volume / vmin;
        if (f >= 1e-3 && f <= 2e-2) {
          out.emplace_back(a, shifted(b0, dir, mid));
          break;
        }
        (f > 2e-2 ? lo : hi) = mid;
      }
    } else if (kind == 2) {
      const TetCorners b = random_tet(rng, 1.5 + u(rng), u(rng), u(rng));
      bool disjoint = false;
      for (int d = 0; d < 3; ++d) {
        double amin = 1e9, amax = -1e9, bmin = 1e9, bmax = -1e9;
        for (int k = 0; k < 4; ++k) {
          amin = std::min(amin, a[k][d]);
          amax = std::max(amax, a[k][d]);
          bmin = std::min(bmin, b[k][d]);
          bmax = std::max(bmax, b[k][d]);
        }
        disjoint = disjoint || amax <= bmin || bmax <= amin;
      }
      if (disjoint) out.emplace_back(a, b);
    } else {
      const TetCorners b = random_tet(rng, 1.0 + u(rng), u(rng), u(rng));
      if (!tet_potential_contact(a, b, 1.0, c)) out.emplace_back(a, b);
    }
  }
  return out;
}

void TetContact(benchmark::State& state) {
  const auto in = pairs(static_cast<int>(state.range(0)));
  const auto kernel = state.range(1) == 0
                          ? tet_potential_contact
                          : tet_potential_contact_with<femdem::test::ConvexPolyhedron>;
  double sink = 0.0;
  for (auto _ : state) {
    for (const auto& [a, b] : in) {
      TetPairContact c{};
      kernel(a, b, 1.0e9, c);
      sink += c.energy + c.force_a[0][0];
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations() * kPool);
  state.counters["ns_per_pair"] =
      benchmark::Counter(static_cast<double>(kPool), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}
BENCHMARK(TetContact)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->ArgNames({"pairs", "kernel"})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
