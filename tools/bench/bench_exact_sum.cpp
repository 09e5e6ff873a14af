// SPDX-License-Identifier: GPL-3.0-or-later
// The exact sums every energy, work and stable-step dot product goes through
// (engine/exact_sum.hpp), against a plain serial sum of the same terms (Google Benchmark):
//   Sum/<kind>/<n>: kind 0 a plain `s += x` loop, 1 ExactSum::add term by term, 2 exact_sum
//   (the parallel form the engine calls; one thread with OMP_NUM_THREADS=1). n terms of
//   kinetic-energy-like magnitude (0.5 m v^2 with m in [1e-6, 1e-3], v in [-10, 10]), in memory.
// Reports the time per term ("ns per term" = cpu_time / n). Run:
//   OMP_NUM_THREADS=1 build/tools/bench/bench_exact_sum
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "engine/exact_sum.hpp"

using namespace femdem;

namespace {

std::vector<double> terms(std::int64_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mass(1e-6, 1e-3), speed(-10.0, 10.0);
  std::vector<double> t(static_cast<std::size_t>(n));
  for (double& x : t) {
    const double v = speed(rng);
    x = 0.5 * mass(rng) * v * v;
  }
  return t;
}

void Sum(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const std::int64_t n = state.range(1);
  const std::vector<double> t = terms(n);
  for (auto _ : state) {
    double s = 0.0;
    if (kind == 0) {
      for (const double x : t) s += x;
    } else if (kind == 1) {
      ExactSum e;
      for (const double x : t) e.add(x);
      s = e.value();
    } else {
      s = exact_sum(n, [&](std::int64_t i) { return t[static_cast<std::size_t>(i)]; });
    }
    benchmark::DoNotOptimize(s);
  }
  state.counters["ns_per_term"] = benchmark::Counter(
      static_cast<double>(n) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(Sum)->ArgsProduct({{0, 1, 2}, {1 << 10, 1 << 16, 1 << 20}});
BENCHMARK_MAIN();
