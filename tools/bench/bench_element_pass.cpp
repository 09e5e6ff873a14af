// SPDX-License-Identifier: GPL-3.0-or-later
// The element pass and the whole step, SIMD update against the scalar reference kernel, in one
// run (Google Benchmark). Reports ns per element update (`ns_per_element`, thread CPU time of
// the process divided by the elements and passes: immune to a loaded machine's descheduling)
// and element updates per second (wall clock):
//   Pass/<model>/<elements>/<threads>/<kernel>   the elements only (forces, stresses, state)
//   Step/<model>/<elements>/<threads>/<kernel>   one whole explicit step (Simulation::step)
// model: 0 elastic, 1 von Mises (linear hardening), 2 von Mises + F-bar (volume average),
// 3 Drucker-Prager, 4 Mohr-Coulomb, 5 piece-wise Drucker-Prager (c 15 MPa, phi 30, psi 15;
// the thesis' five concrete pieces), 6 von Mises + nodal F-bar, 7 von Mises + sub-tet F-bar;
// kernel: 0 SIMD, 1 scalar, 2 SIMD reading the 120-number gradient table as for curved
// elements (what recomputing the gradients from J0^-1 saves). The block is stretched and
// sheared so that plastic points yield. FEMDEM_BENCH_TARGET=SCALAR (or another of
// element_update_targets()) runs the SIMD update on that instruction set instead of the best.
// Run: build/tools/bench/bench_element_pass --benchmark_counters_tabular=true
//      [--benchmark_filter='Pass/model:1/elements:100000/']
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "engine/element_pass.hpp"
#include "engine/simulation.hpp"
#include "io/mesh/mesh_generators.hpp"

using namespace femdem;

namespace {

ModelSpec block(int model, std::int64_t elements) {
  ModelSpec s;
  s.simulation.end_time = 1.0;
  MaterialParams mat;
  mat.name = "steel";
  mat.density = 7850.0;
  mat.youngs_modulus = 200e9;
  mat.poisson_ratio = 0.3;
  if (model == 1 || model == 2 || model >= 6) {
    VonMisesParams v;
    v.yield_stress = 250e6;
    v.hardening_modulus = 1e9;
    mat.model = v;
  }
  FrictionalParams f;
  f.cohesion = 15e6;
  f.friction_angle = 30.0;
  f.dilatancy_angle = 15.0;
  if (model == 3) {
    DruckerPragerParams p;
    static_cast<FrictionalParams&>(p) = f;
    mat.model = p;
  }
  if (model == 4) {
    MohrCoulombParams p;
    static_cast<FrictionalParams&>(p) = f;
    mat.model = p;
  }
  if (model == 5) {
    PiecewiseDruckerPragerParams p;
    p.pieces = {{0.42, 8e6}, {0.30, 14e6}, {0.14, 30e6}, {0.07, 40.5e6}, {0.035, 49.25e6}};
    mat.model = p;
  }
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = generate_box(Vec3(1.0, 1.0, 1.0), std::cbrt(6.0 / static_cast<double>(elements)));
  b.velocity = Vec3(1.0, 2.0, 3.0);
  if (model == 2) b.fbar = FbarMode::VolumeAverage;
  if (model == 6) b.fbar = FbarMode::Nodal;
  if (model == 7) b.fbar = FbarMode::SubTet;
  s.bodies.push_back(b);
  return s;
}

// The block's model, built once for consecutive benchmarks of the same model and size (at 10^6
// elements building it takes far longer than measuring it).
const Model& cached_block(int model, std::int64_t elements) {
  static int cached_model = -1;
  static std::int64_t cached_elements = -1;
  static Model m;
  if (model != cached_model || elements != cached_elements) {
    m = Model();
    m = build_model(block(model, elements));
    cached_model = model, cached_elements = elements;
  }
  return m;
}

// A deformation beyond yield (0.125 % here) in most points: stretch, shear and a ripple.
void deform(Model& m) {
  for (std::int32_t n = 0; n < m.node_count; ++n) {
    const double X = m.X[3 * n], Y = m.X[3 * n + 1], Z = m.X[3 * n + 2];
    m.x[3 * n] = X * 1.004 + 0.002 * Y + 1e-3 * std::sin(20.0 * Z);
    m.x[3 * n + 1] = Y * 0.998 + 0.001 * Z;
    m.x[3 * n + 2] = Z * 0.999 + 1e-3 * std::sin(17.0 * X);
  }
}

double process_cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The instruction set asked for by FEMDEM_BENCH_TARGET (the best one otherwise).
void choose_target(benchmark::State& state) {
  const char* t = std::getenv("FEMDEM_BENCH_TARGET");
  if (!use_element_update_target(t ? t : "")) state.SkipWithError("unknown FEMDEM_BENCH_TARGET");
}

void report(benchmark::State& state, std::int64_t elements, double cpu_s) {
  const double updates = static_cast<double>(elements) * static_cast<double>(state.iterations());
  state.counters["ns_per_element"] = 1e9 * cpu_s / updates / static_cast<double>(state.range(2));
  state.counters["element_updates_per_s"] = benchmark::Counter(
      static_cast<double>(elements), benchmark::Counter::kIsIterationInvariantRate);
  const char* kinds[] = {"simd ", "scalar", "simd table "};
  state.SetLabel(std::string(kinds[state.range(3)]) +
                 (state.range(3) == 1 ? "" : element_update_target()));
}

void Pass(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(2)));
  choose_target(state);
  Model m = cached_block(static_cast<int>(state.range(0)), state.range(1));
  deform(m);
  if (state.range(3) == 2) std::fill(m.straight_sided.begin(), m.straight_sided.end(), 0);
  const std::vector<MaterialKernel> kernels = {compile_material(m.materials[0])};
  ElementPass pass(m, kernels);
  pass.choose(state.range(3) == 1 ? ElementKernelChoice::scalar : ElementKernelChoice::simd);
  std::vector<double> force(30 * static_cast<std::size_t>(m.element_count));
  std::vector<ElementResult> results(m.element_count);
  // nodal F-bar's inputs and outputs (the corner volume ratios as at rest)
  const bool nodal = m.element_fbar[0] == FbarMode::Nodal;
  std::vector<double> node_J(nodal ? m.node_count : 0, 1.0);
  std::vector<double> pressure_weight(nodal ? 4 * static_cast<std::size_t>(m.element_count) : 0);
  std::vector<double> volume_gradient(nodal ? 30 * static_cast<std::size_t>(m.element_count) : 0);
  NodalFbarArrays arrays;
  if (nodal) arrays = {node_J.data(), pressure_weight.data(), volume_gradient.data()};
  const std::vector<ElementStates> fresh = m.states;
  pass.update(m, kernels, 1e-7, arrays, force, results);  // warm up
  double cpu = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    m.states = fresh;  // every pass yields the same points again
    state.ResumeTiming();
    const double c0 = process_cpu_seconds();
    pass.update(m, kernels, 1e-7, arrays, force, results);
    cpu += process_cpu_seconds() - c0;
    benchmark::DoNotOptimize(force.data());
  }
  report(state, m.element_count, cpu);
}

void Step(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(2)));
  choose_target(state);
  Model m = cached_block(static_cast<int>(state.range(0)), state.range(1));
  if (state.range(3) == 2) std::fill(m.straight_sided.begin(), m.straight_sided.end(), 0);
  Simulation sim(std::move(m));
  sim.choose_element_kernel(state.range(3) == 1 ? ElementKernelChoice::scalar
                                                : ElementKernelChoice::simd);
  sim.step();
  double cpu = 0.0;
  for (auto _ : state) {
    const double c0 = process_cpu_seconds();
    sim.step();
    cpu += process_cpu_seconds() - c0;
  }
  report(state, sim.model().element_count, cpu);
}

// Every model at 10^4, 10^5 and 10^6 elements; the table gradients at 10^5.
void arguments(benchmark::internal::Benchmark* b) {
  b->ArgNames({"model", "elements", "threads", "kernel"});
  for (std::int64_t n : {10000, 100000, 1000000})
    for (int model : {0, 1, 2, 3, 4, 5, 6, 7})
      for (int threads : {1, 2})
        for (int kernel : {0, 1, 2}) {
          if (kernel == 2 && (n != 100000 || model > 2)) continue;
          b->Args({model, n, threads, kernel});
        }
}

}  // namespace

BENCHMARK(Pass)->Apply(arguments)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(Step)->Apply(arguments)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
