// SPDX-License-Identifier: GPL-3.0-or-later
// Element-update kernels (Google Benchmark). Reports element updates per second:
//   ElementKernel/<elements>/<threads>: the TET10 elastic force kernel alone over a mesh
//   Step/<elements>/<threads>: one whole explicit step (kernel, gather, integration)
// Run: build/tools/bench/bench_element --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include "engine/element_kernel.hpp"
#include "engine/simulation.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "materials/von_mises.hpp"

using namespace femdem;

namespace {

ModelSpec box_spec(double h) {
  ModelSpec s;
  s.simulation.end_time = 1.0;
  MaterialParams mat;
  mat.name = "steel";
  mat.density = 7850.0;
  mat.youngs_modulus = 210e9;
  mat.poisson_ratio = 0.3;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "box";
  b.material = 0;
  b.mesh = generate_box(Vec3(1.0, 1.0, 1.0), h);
  b.velocity = Vec3(1.0, 2.0, 3.0);
  s.bodies.push_back(b);
  ConstraintSpec c;
  c.body = 0;
  c.region.kind = RegionSpec::Kind::Plane;
  c.fix = {true, true, true};
  s.constraints.push_back(c);
  return s;
}

// element size giving about n elements in the unit box (6 tets per cell)
double size_for(std::int64_t n) {
  return std::cbrt(6.0 / static_cast<double>(n));
}

void ElementKernel(benchmark::State& state) {
  Model m = build_model(box_spec(size_for(state.range(0))));
  omp_set_num_threads(static_cast<int>(state.range(1)));
  // a deformed state, so the eigen-solver sees a general spectrum
  for (int n = 0; n < m.node_count; ++n)
    for (int k = 0; k < 3; ++k)
      m.x[3 * n + k] = m.X[3 * n + k] * (1.0 + 0.01 * (k + 1)) + 0.003 * m.X[3 * n + (k + 1) % 3];
  std::vector<double> fe(30 * static_cast<std::size_t>(m.element_count));
  const MaterialParams& mat = m.materials[0];
  const double lambda = mat.lame_lambda(), G = mat.shear_modulus();
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (int e = 0; e < m.element_count; ++e) {
      double xe[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.x[3 * m.conn[e][a] + k];
      tet10_elastic_forces(xe, &m.dNdX[120 * static_cast<std::size_t>(e)],
                           &m.gauss_weight[4 * static_cast<std::size_t>(e)], lambda, G,
                           &fe[30 * static_cast<std::size_t>(e)],
                           &m.stress[24 * static_cast<std::size_t>(e)]);
    }
    benchmark::DoNotOptimize(fe.data());
  }
  state.counters["elements"] = m.element_count;
  state.counters["element_updates_per_s"] = benchmark::Counter(
      static_cast<double>(m.element_count), benchmark::Counter::kIsIterationInvariantRate);
}

// The same kernel with von Mises plasticity (every Gauss point yielding: sigma_y is far below
// the stress of the imposed deformation) and an F-bar variant: range(1) = 0 off,
// 1 volume_average, 2 centroid, 3 elastic Hencky for reference in the same run.
void ElementKernelPlastic(benchmark::State& state) {
  Model m = build_model(box_spec(size_for(state.range(0))));
  omp_set_num_threads(1);
  for (int n = 0; n < m.node_count; ++n)
    for (int k = 0; k < 3; ++k)
      m.x[3 * n + k] = m.X[3 * n + k] * (1.0 + 0.01 * (k + 1)) + 0.003 * m.X[3 * n + (k + 1) % 3];
  const MaterialParams& p = m.materials[0];
  VonMisesParams vmp;
  vmp.yield_stress = 50e6;
  vmp.hardening_modulus = 1e9;
  const VonMises vm = make_von_mises(p, vmp);
  const ElasticModel el{p.lame_lambda(), p.shear_modulus()};
  const FbarMode modes[3] = {FbarMode::Off, FbarMode::VolumeAverage, FbarMode::Centroid};
  const int variant = static_cast<int>(state.range(1));
  std::vector<double> fe(30 * static_cast<std::size_t>(m.element_count));
  for (auto _ : state) {
    for (int e = 0; e < m.element_count; ++e) {
      double xe[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.x[3 * m.conn[e][a] + k];
      const std::size_t es = static_cast<std::size_t>(e);
      GaussPointState st[4];  // fresh state: every call does the full return mapping
      if (variant == 3)
        tet10_internal_forces(xe, &m.dNdX[120 * es], &m.gauss_weight[4 * es], el, FbarMode::Off, st,
                              1e-7, &fe[30 * es], &m.stress[24 * es]);
      else
        tet10_internal_forces(xe, &m.dNdX[120 * es], &m.gauss_weight[4 * es], vm, modes[variant],
                              st, 1e-7, &fe[30 * es], &m.stress[24 * es]);
    }
    benchmark::DoNotOptimize(fe.data());
  }
  state.counters["element_updates_per_s"] = benchmark::Counter(
      static_cast<double>(m.element_count), benchmark::Counter::kIsIterationInvariantRate);
}

// The kernel with each material model, every Gauss point yielding (a compression with shear far
// beyond the strength): range(1) = 0 elastic, 1 von Mises, 2 Drucker-Prager, 3 Mohr-Coulomb,
// 4 piece-wise Drucker-Prager (the thesis' five concrete pieces). F-bar off.
void ElementKernelModels(benchmark::State& state) {
  Model m = build_model(box_spec(size_for(state.range(0))));
  omp_set_num_threads(1);
  for (int n = 0; n < m.node_count; ++n)
    for (int k = 0; k < 3; ++k)
      m.x[3 * n + k] = m.X[3 * n + k] * (1.0 - 0.01 * (k + 1)) + 0.003 * m.X[3 * n + (k + 1) % 3];
  const MaterialParams& p = m.materials[0];
  VonMisesParams vmp;
  vmp.yield_stress = 50e6;
  vmp.hardening_modulus = 1e9;
  DruckerPragerParams dpp;
  dpp.cohesion = 15e6;
  dpp.friction_angle = 30.0;
  dpp.dilatancy_angle = 15.0;
  MohrCoulombParams mcp;
  static_cast<FrictionalParams&>(mcp) = dpp;
  PiecewiseDruckerPragerParams pwp;
  pwp.pieces = {{0.42, 8e6}, {0.30, 14e6}, {0.14, 30e6}, {0.07, 40.5e6}, {0.035, 49.25e6}};
  const ElasticModel el{p.lame_lambda(), p.shear_modulus()};
  const VonMises vm = make_von_mises(p, vmp);
  const DruckerPrager dp = make_drucker_prager(p, dpp);
  const MohrCoulomb mc = make_mohr_coulomb(p, mcp);
  const PiecewiseDruckerPrager pw = make_piecewise_drucker_prager(p, pwp);
  const int variant = static_cast<int>(state.range(1));
  std::vector<double> fe(30 * static_cast<std::size_t>(m.element_count));
  auto run = [&](const auto& model) {
    for (int e = 0; e < m.element_count; ++e) {
      double xe[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.x[3 * m.conn[e][a] + k];
      const std::size_t es = static_cast<std::size_t>(e);
      GaussPointState st[4];
      tet10_internal_forces(xe, &m.dNdX[120 * es], &m.gauss_weight[4 * es], model, FbarMode::Off,
                            st, 1e-7, &fe[30 * es], &m.stress[24 * es]);
    }
  };
  for (auto _ : state) {
    switch (variant) {
      case 0:
        run(el);
        break;
      case 1:
        run(vm);
        break;
      case 2:
        run(dp);
        break;
      case 3:
        run(mc);
        break;
      default:
        run(pw);
        break;
    }
    benchmark::DoNotOptimize(fe.data());
  }
  state.counters["element_updates_per_s"] = benchmark::Counter(
      static_cast<double>(m.element_count), benchmark::Counter::kIsIterationInvariantRate);
}

void Step(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  Simulation sim(build_model(box_spec(size_for(state.range(0)))));
  for (auto _ : state) sim.step();
  state.counters["elements"] = sim.model().element_count;
  state.counters["element_updates_per_s"] =
      benchmark::Counter(static_cast<double>(sim.model().element_count),
                         benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(ElementKernel)
    ->ArgsProduct({{10000, 100000}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(ElementKernelPlastic)
    ->ArgsProduct({{10000}, {3, 0, 1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(ElementKernelModels)
    ->ArgsProduct({{10000}, {0, 1, 2, 3, 4}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(Step)
    ->ArgsProduct({{10000, 100000}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
