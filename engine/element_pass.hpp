// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The element part of a step: every element's internal forces (into per-element buffers, for
// the deterministic gather), its Cauchy stresses and Gauss-point history (in the Model), and its
// ElementResult. Elements go through the SIMD update (engine/element_update/) two at a time
// where it has their material model and F-bar mode, the rest (and every element when asked for
// the reference) through the scalar kernel of engine/element_kernel.hpp.
//
// The pairs are planned once: consecutive elements of one body (same material and F-bar mode)
// and of one kind (straight-sided or curved), in chunks that the threads share statically, so
// every element's result is computed the same way whatever the thread count.
#include <cstdint>
#include <vector>

#include "engine/element_kernel.hpp"
#include "engine/element_update/element_update.hpp"
#include "engine/model.hpp"

namespace femdem {

// The nodal F-bar's per-node inputs and per-element outputs (engine/element_kernel.hpp; all
// null when the model has no nodal F-bar element).
struct NodalFbarArrays {
  const double* node_J = nullptr;     // in: each node's averaged volume ratio
  double* pressure_weight = nullptr;  // out: 4 per element, the corners' shares of dW/dJbar
  double* volume_gradient = nullptr;  // out: 30 per element, d(element volume)/dx
};

enum class ElementKernelChoice {
  simd,   // the SIMD update where it applies (the default)
  scalar  // every element through the scalar kernel (the reference)
};

class ElementPass {
 public:
  // kernels: the compiled return mapping of each of the model's materials.
  ElementPass(const Model& m, const std::vector<MaterialKernel>& kernels);

  void choose(ElementKernelChoice choice) { choice_ = choice; }
  ElementKernelChoice choice() const { return choice_; }
  // Elements the SIMD update takes with the current choice (for the log and benchmarks).
  std::int64_t simd_elements() const;

  // One pass at the current positions m.x. force: 30 per element (overwritten); result: one
  // per element; nodal: the nodal F-bar's arrays (only its elements' entries are written).
  void update(Model& m, const std::vector<MaterialKernel>& kernels, double dt,
              const NodalFbarArrays& nodal, std::vector<double>& force,
              std::vector<ElementResult>& result);

  // The current volume (sum_g w_g det F_g) of every nodal F-bar element into volume[e] (the
  // others are not written), the same way the update computes it.
  void nodal_volumes(const Model& m, double* volume) const;

 private:
  struct Chunk {
    std::int32_t material = 0;
    FbarMode fbar = FbarMode::Off;
    bool straight = false;
    std::size_t begin = 0, end = 0;  // in pairs_
  };
  void scalar_element(Model& m, const MaterialKernel& kernel, std::int32_t e, double dt,
                      const NodalFbarArrays& nodal, double* force, ElementResult& result) const;
  // the arrays the update reads: positions, connectivity, gradients, weights
  ElementUpdateArrays geometry(const Model& m) const;
  // ... and those it writes
  ElementUpdateArrays arrays(Model& m, std::vector<double>& force,
                             std::vector<ElementResult>& result,
                             const NodalFbarArrays& nodal) const;

  ElementKernelChoice choice_ = ElementKernelChoice::simd;
  std::vector<ElementPair> pairs_;
  std::vector<Chunk> chunks_;
  std::vector<std::int32_t> scalar_elements_;  // those the SIMD update does not take
  std::vector<double> dNdX_lanes_;  // curved elements taken by the SIMD update, [e][3a+j][g]
};

}  // namespace femdem
