// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): Hencky elasticity in lanes,
// the return of materials/finite_strain_update.hpp's ElasticModel (no yield).
#if defined(FEMDEM_ELASTIC_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_ELASTIC_LANES_INL_H_
#undef FEMDEM_ELASTIC_LANES_INL_H_
#else
#define FEMDEM_ELASTIC_LANES_INL_H_
#endif

#include "materials/lanes/finite_strain_update-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

HWY_INLINE PrincipalReturnLanes return_map_lanes(const ElasticModel& m, const Lanes8 e[3],
                                                 const Lanes8& kappa, double /*dt*/) {
  PrincipalReturnLanes r;
  const Lanes8 tr = e[0] + e[1] + e[2];
  for (int i = 0; i < 3; ++i) {
    r.tau[i] = Lanes8(m.lambda) * tr + Lanes8(2.0 * m.G) * e[i];
    r.e_el[i] = e[i];
  }
  r.kappa = kappa;
  r.yielded = all_lanes(false);
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_ELASTIC_LANES_INL_H_
