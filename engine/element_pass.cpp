// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/element_pass.hpp"

#include <algorithm>

#include "engine/parallel_threshold.hpp"

namespace femdem {
namespace {

// Pairs per chunk: enough to amortise the dispatch, small enough to share among threads.
constexpr std::size_t kPairsPerChunk = 32;

}  // namespace

ElementPass::ElementPass(const Model& m, const std::vector<MaterialKernel>& kernels) {
  const std::int32_t ne = m.element_count;
  bool curved_taken = false;
  // whether the SIMD update takes a (material, F-bar mode): asked once per pair, not per element
  std::vector<signed char> supported(kernels.size() * 5, -1);
  auto takes = [&](std::int32_t e) {
    signed char& s = supported[5 * m.element_material[e] + static_cast<int>(m.element_fbar[e])];
    if (s < 0) s = element_update_supports(kernels[m.element_material[e]], m.element_fbar[e]);
    return s == 1;
  };
  auto same_kind = [&](std::int32_t a, std::int32_t b) {
    return m.element_body[a] == m.element_body[b] && m.element_fbar[a] == m.element_fbar[b] &&
           m.element_material[a] == m.element_material[b] &&
           m.straight_sided[a] == m.straight_sided[b];
  };
  // pairs of consecutive elements of one kind, each run of a kind in chunks
  std::int32_t e = 0;
  while (e < ne) {
    if (!takes(e)) {
      scalar_elements_.push_back(e++);
      continue;
    }
    const std::int32_t first = e;
    while (e < ne && takes(e) && same_kind(first, e)) ++e;
    Chunk run;
    run.material = m.element_material[first];
    run.fbar = m.element_fbar[first];
    run.straight = m.straight_sided[first] != 0;
    curved_taken = curved_taken || !run.straight;
    const std::size_t run_begin = pairs_.size();
    for (std::int32_t a = first; a < e; a += 2) pairs_.push_back({a, std::min(a + 1, e - 1)});
    for (std::size_t b = run_begin; b < pairs_.size(); b += kPairsPerChunk) {
      run.begin = b;
      run.end = std::min(pairs_.size(), b + kPairsPerChunk);
      chunks_.push_back(run);
    }
  }
  if (curved_taken) {
    // the table in the lanes' layout: [e][3a+j][g] from dNdX's [e][g][3a+j]
    dNdX_lanes_.assign(120 * static_cast<std::size_t>(ne), 0.0);
    for (std::size_t el = 0; el < static_cast<std::size_t>(ne); ++el)
      for (int g = 0; g < 4; ++g)
        for (int aj = 0; aj < 30; ++aj)
          dNdX_lanes_[120 * el + 4 * aj + g] = m.dNdX[120 * el + 30 * g + aj];
  }
}

std::int64_t ElementPass::simd_elements() const {
  if (choice_ == ElementKernelChoice::scalar) return 0;
  std::int64_t n = 0;
  for (const ElementPair& p : pairs_) n += p.first == p.second ? 1 : 2;
  return n;
}

void ElementPass::scalar_element(Model& m, const MaterialKernel& kernel, std::int32_t e, double dt,
                                 const NodalFbarArrays& nodal, double* force,
                                 ElementResult& result) const {
  const Tet10& c = m.conn[e];
  double xe[30], Xe[30];
  for (int a = 0; a < 10; ++a)
    for (int k = 0; k < 3; ++k) {
      xe[3 * a + k] = m.x[3 * c[a] + k];
      Xe[3 * a + k] = m.X[3 * c[a] + k];
    }
  const std::size_t es = static_cast<std::size_t>(e);
  const FbarMode fbar = m.element_fbar[e];
  double cJ[4] = {1, 1, 1, 1};
  double* q = nullptr;
  const bool nodal_fbar = fbar == FbarMode::Nodal && nodal.node_J;
  if (nodal_fbar) {
    for (int k = 0; k < 4; ++k) cJ[k] = nodal.node_J[c[k]];
    q = nodal.pressure_weight + 4 * es;
  }
  const double altitude = corner_tet_min_altitude(xe);
  GaussPointState st[4];
  for (int g = 0; g < 4; ++g) st[g] = m.states[e].at(g);
  double sigma[24];
  result = std::visit(
      [&](const auto& model) {
        return tet10_internal_forces(xe, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es,
                                     model, fbar, st, dt, force, sigma, cJ, q, m.subtet_volume0[e],
                                     Xe);
      },
      kernel);
  result.min_altitude = altitude;
  if (nodal_fbar) {
    double* vg = nodal.volume_gradient + 30 * es;
    for (int i = 0; i < 30; ++i) vg[i] = 0.0;
    tet10_add_volume_gradient(xe, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es, 1.0,
                              vg);
  }
  for (int g = 0; g < 4; ++g) {
    m.states[e].set(g, st[g]);
    for (int k = 0; k < 6; ++k) m.stress[24 * es + 4 * k + g] = sigma[6 * g + k];
  }
}

ElementUpdateArrays ElementPass::geometry(const Model& m) const {
  ElementUpdateArrays a;
  a.x = m.x.data();
  a.X = m.X.data();
  a.conn = m.conn.data();
  a.inverse_jacobian = m.inverse_jacobian.data();
  a.gauss_weight = m.gauss_weight.data();
  a.dNdX_lanes = dNdX_lanes_.data();
  return a;
}

ElementUpdateArrays ElementPass::arrays(Model& m, std::vector<double>& force,
                                        std::vector<ElementResult>& result,
                                        const NodalFbarArrays& nodal) const {
  ElementUpdateArrays a = geometry(m);
  a.subtet_volume0 = m.subtet_volume0.data();
  a.node_J = nodal.node_J;
  a.pressure_weight = nodal.pressure_weight;
  a.volume_gradient = nodal.volume_gradient;
  a.state = m.states.data();
  a.stress = m.stress.data();
  a.force = force.data();
  a.result = result.data();
  return a;
}

void ElementPass::nodal_volumes(const Model& m, double* volume) const {
  const ElementUpdateArrays in = geometry(m);  // what the volumes read
  const auto nc = static_cast<std::int64_t>(chunks_.size());
  const auto ns = static_cast<std::int64_t>(scalar_elements_.size());
  const bool simd = choice_ == ElementKernelChoice::simd;
#pragma omp parallel if (m.element_count > kParallelMinElements)
  {
    if (simd) {
#pragma omp for schedule(static) nowait
      for (std::int64_t c = 0; c < nc; ++c) {
        const Chunk& k = chunks_[c];
        if (k.fbar == FbarMode::Nodal)
          element_pair_volumes(k.straight, in, pairs_.data() + k.begin, k.end - k.begin, volume);
      }
    }
    // the scalar kernel's elements (every element when it is the choice)
    const std::int64_t n = simd ? ns : m.element_count;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int32_t e = simd ? scalar_elements_[i] : static_cast<std::int32_t>(i);
      if (m.element_fbar[e] != FbarMode::Nodal) continue;
      double xe[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.x[3 * m.conn[e][a] + k];
      const std::size_t es = static_cast<std::size_t>(e);
      volume[e] =
          tet10_current_volume(xe, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es);
    }
  }
}

void ElementPass::update(Model& m, const std::vector<MaterialKernel>& kernels, double dt,
                         const NodalFbarArrays& nodal, std::vector<double>& force,
                         std::vector<ElementResult>& result) {
  const std::int32_t ne = m.element_count;
  if (choice_ == ElementKernelChoice::scalar) {
#pragma omp parallel for schedule(static) if (ne > kParallelMinElements)
    for (std::int32_t e = 0; e < ne; ++e)
      scalar_element(m, kernels[m.element_material[e]], e, dt, nodal,
                     force.data() + 30 * static_cast<std::size_t>(e), result[e]);
    return;
  }
  const ElementUpdateArrays in = arrays(m, force, result, nodal);
  const auto nc = static_cast<std::int64_t>(chunks_.size());
  const auto ns = static_cast<std::int64_t>(scalar_elements_.size());
#pragma omp parallel if (ne > kParallelMinElements)
  {
#pragma omp for schedule(static) nowait
    for (std::int64_t c = 0; c < nc; ++c) {
      const Chunk& k = chunks_[c];
      update_element_pairs(kernels[k.material], k.fbar, k.straight, in, pairs_.data() + k.begin,
                           k.end - k.begin, dt);
    }
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < ns; ++i) {
      const std::int32_t e = scalar_elements_[i];
      scalar_element(m, kernels[m.element_material[e]], e, dt, nodal,
                     force.data() + 30 * static_cast<std::size_t>(e), result[e]);
    }
  }
}

}  // namespace femdem
