// SPDX-License-Identifier: GPL-3.0-or-later
// The SIMD element update (element_update.hpp): the choice of variant (F-bar mode and gradient
// kind, each compiled in its own generated source from element_update_variant.cpp.in) and of
// instruction set. Compiled once per target by Highway's foreach_target for what needs the lanes
// code beside the variants: which material models it has, and the elements' volumes.
#include "engine/element_update/element_update.hpp"

#include <type_traits>
#include <variant>

#include "engine/element_update/element_update_variants.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/element_update/element_update.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/element_update/element_pairs-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

bool HasLanesReturn(const MaterialKernel& material) {
  return std::visit([](const auto& m) { return has_lanes_return<std::decay_t<decltype(m)>>; },
                    material);
}

void PairVolumes(bool straight, const ElementUpdateArrays& arrays, const ElementPair* pairs,
                 std::size_t count, double* volume) {
  if (straight)
    element_pairs_detail::pair_volumes<true>(arrays, pairs, count, volume);
  else
    element_pairs_detail::pair_volumes<false>(arrays, pairs, count, volume);
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace femdem {

HWY_EXPORT(HasLanesReturn);
HWY_EXPORT(PairVolumes);

void element_pair_volumes(bool straight, const ElementUpdateArrays& arrays,
                          const ElementPair* pairs, std::size_t count, double* volume) {
  HWY_DYNAMIC_DISPATCH(PairVolumes)(straight, arrays, pairs, count, volume);
}

bool element_update_supports(const MaterialKernel& material, FbarMode /*fbar*/) {
  return HWY_DYNAMIC_DISPATCH(HasLanesReturn)(material);  // every F-bar mode
}

void update_element_pairs(const MaterialKernel& material, FbarMode fbar, bool straight,
                          const ElementUpdateArrays& arrays, const ElementPair* pairs,
                          std::size_t count, double dt) {
  switch (fbar) {
    case FbarMode::Off:
      return (straight ? update_pairs_off_straight : update_pairs_off_curved)(material, arrays,
                                                                              pairs, count, dt);
    case FbarMode::VolumeAverage:
      return (straight ? update_pairs_volume_average_straight : update_pairs_volume_average_curved)(
          material, arrays, pairs, count, dt);
    case FbarMode::Centroid:
      return (straight ? update_pairs_centroid_straight : update_pairs_centroid_curved)(
          material, arrays, pairs, count, dt);
    case FbarMode::Nodal:
      return (straight ? update_pairs_nodal_straight : update_pairs_nodal_curved)(material, arrays,
                                                                                  pairs, count, dt);
    case FbarMode::SubTet:
      return (straight ? update_pairs_subtet_straight : update_pairs_subtet_curved)(
          material, arrays, pairs, count, dt);
  }
}

std::vector<std::string> element_update_targets() {
  std::vector<std::string> out;
  for (const std::int64_t t : hwy::SupportedAndGeneratedTargets())
    out.emplace_back(hwy::TargetName(t));
  return out;
}

std::string element_update_target() {
  // the target the dispatch chose: the best of the supported and generated ones
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets.empty() ? std::string("none") : hwy::TargetName(targets.front());
}

bool use_element_update_target(const std::string& name) {
  hwy::SetSupportedTargetsForTest(0);  // all of them again, then the one asked for
  if (name.empty()) return true;
  for (const std::int64_t t : hwy::SupportedAndGeneratedTargets())
    if (name == hwy::TargetName(t)) {
      hwy::SetSupportedTargetsForTest(t);
      return true;
    }
  return false;
}

}  // namespace femdem
#endif  // HWY_ONCE
