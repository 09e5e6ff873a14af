// SPDX-License-Identifier: GPL-3.0-or-later
// Symmetric 3x3 eigen-solvers on the element kernel's inputs (Google Benchmark):
//   Eigen3/<solver>/<strain>: b = F F^T with F = R (I + h X), X uniform in [-1, 1], R a random
//   rotation; h = 1e-3 (strain 0) or 0.3 (strain 1). solver 0: symmetric_eigen3 (closed form +
//   Jacobi polish), 1: symmetric_eigen3_jacobi, 2: Eigen computeDirect, 3: Eigen compute().
//   HenckyStrain/<route>/<strain>: the Hencky strain tensor 0.5 ln b that the elastic update
//   needs; route 0: symmetric_eigen3, three logarithms and the assembly (the general route),
//   1: log_strain_by_series (materials/log_strain_series.hpp; the general route where it
//   declines, i.e. at strain 1).
// Reports s_per_call (ns shown as "n"). Run: build/tools/bench/bench_eigen3
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <random>
#include <vector>

#include "materials/hencky.hpp"
#include "materials/log_strain_series.hpp"
#include "materials/symmetric_eigen3.hpp"

using namespace femdem;

namespace {

constexpr int kPool = 4096;  // distinct inputs, cycled (fits in L1/L2 like a kernel's data)

std::vector<double> inputs(double h) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> out(6 * kPool);
  for (int i = 0; i < kPool; ++i) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    Eigen::Matrix3d X;
    for (int k = 0; k < 9; ++k) X.data()[k] = u(rng);
    const Eigen::Matrix3d F = R * (Eigen::Matrix3d::Identity() + h * X);
    const Eigen::Matrix3d b = F * F.transpose();
    double* s = &out[6 * i];
    s[0] = b(0, 0);
    s[1] = b(1, 1);
    s[2] = b(2, 2);
    s[3] = b(0, 1);
    s[4] = b(1, 2);
    s[5] = b(0, 2);
  }
  return out;
}

Eigen::Matrix3d full(const double* s) {
  Eigen::Matrix3d A;
  A << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return A;
}

void Eigen3(benchmark::State& state) {
  const int solver = static_cast<int>(state.range(0));
  const std::vector<double> in = inputs(state.range(1) == 0 ? 1e-3 : 0.3);
  double sink = 0.0;
  for (auto _ : state) {
    for (int i = 0; i < kPool; ++i) {
      const double* s = &in[6 * i];
      switch (solver) {
        case 0: {
          const SymEig3 r = symmetric_eigen3(s);
          sink += r.value[0] + r.vector[0][0];
          break;
        }
        case 1: {
          const SymEig3 r = symmetric_eigen3_jacobi(s);
          sink += r.value[0] + r.vector[0][0];
          break;
        }
        case 2: {
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
          es.computeDirect(full(s));
          sink += es.eigenvalues()[0] + es.eigenvectors()(0, 0);
          break;
        }
        default: {
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
          es.compute(full(s));
          sink += es.eigenvalues()[0] + es.eigenvectors()(0, 0);
          break;
        }
      }
    }
    benchmark::DoNotOptimize(sink);
  }
  static const char* names[] = {"closed form + Jacobi polish", "Jacobi", "Eigen computeDirect",
                                "Eigen compute"};
  state.SetLabel(names[solver]);
  state.counters["s_per_call"] = benchmark::Counter(
      kPool, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void hencky_strain_by_eigen(const double* s, double e[6]) {
  const PrincipalStrains p = principal_log_strains(s);
  assemble_from_principal(p.e, p.n, e);
}

void HenckyStrain(benchmark::State& state) {
  const bool series = state.range(0) == 1;
  const std::vector<double> in = inputs(state.range(1) == 0 ? 1e-3 : 0.3);
  double sink = 0.0;
  for (auto _ : state) {
    for (int i = 0; i < kPool; ++i) {
      const double* s = &in[6 * i];
      double e[6];
      if (!series || !log_strain_by_series(s, e)) hencky_strain_by_eigen(s, e);
      sink += e[0] + e[3];
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetLabel(series ? "series (eigen where it declines)" : "eigen + 3 logs");
  state.counters["s_per_call"] = benchmark::Counter(
      kPool, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(Eigen3)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(HenckyStrain)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
