// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the lanes returns of the
// registry's models (materials/material_registry.hpp), one file each. A model without one here
// is updated by the scalar element kernel (has_lanes_return below is false for it).
#if defined(FEMDEM_MATERIAL_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_MATERIAL_LANES_INL_H_
#undef FEMDEM_MATERIAL_LANES_INL_H_
#else
#define FEMDEM_MATERIAL_LANES_INL_H_
#endif

#include "materials/lanes/drucker_prager-inl.h"
#include "materials/lanes/elastic-inl.h"
#include "materials/lanes/mohr_coulomb-inl.h"
#include "materials/lanes/piecewise_drucker_prager-inl.h"
#include "materials/lanes/von_mises-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

template <class Kernel>
inline constexpr bool has_lanes_return = requires(const Kernel& k, const Lanes8* e,
                                                  const Lanes8& kappa, double dt) {
  { return_map_lanes(k, e, kappa, dt) } -> std::same_as<PrincipalReturnLanes>;
};

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_MATERIAL_LANES_INL_H_
