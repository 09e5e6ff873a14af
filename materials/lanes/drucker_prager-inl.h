// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the Drucker-Prager return of
// materials/drucker_prager.hpp in lanes: the smooth-cone and the apex returns both computed
// and the right one selected per lane.
#if defined(FEMDEM_DRUCKER_PRAGER_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_DRUCKER_PRAGER_LANES_INL_H_
#undef FEMDEM_DRUCKER_PRAGER_LANES_INL_H_
#else
#define FEMDEM_DRUCKER_PRAGER_LANES_INL_H_
#endif

#include "materials/drucker_prager.hpp"
#include "materials/lanes/finite_strain_update-inl.h"
#include "materials/lanes/meridian-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

HWY_INLINE PrincipalReturnLanes return_map_lanes(const DruckerPrager& d, const Lanes8 e[3],
                                                 const Lanes8& kappa_n, double /*dt*/) {
  PrincipalReturnLanes r;
  const CohesionLanes cohesion{d.cohesion};
  const MeridianTrialLanes trial = meridian_trial(e, d.K, d.G);
  const Lanes8 p_trial = trial.p, q_trial = trial.q;
  const Lanes8 c_n = cohesion.value(kappa_n);
  const Lanes8 phi = q_trial + Lanes8(d.eta) * p_trial - Lanes8(d.xi) * c_n;
  r.yielded = phi > Lanes8(1e-12) * (q_trial + abs(Lanes8(d.eta) * p_trial) + Lanes8(d.xi) * c_n);
  Lanes8 p = p_trial, factor(1.0);
  r.kappa = kappa_n;
  if (any(r.yielded)) {
    const Lanes8 dgamma = cohesion.solve(phi, Lanes8(d.G + d.K * d.eta * d.eta_bar), Lanes8(d.xi),
                                         Lanes8(d.xi), kappa_n);
    // the smooth cone
    Lanes8 factor_y =
        select(q_trial > Lanes8(0.0),
               max(Lanes8(0.0), Lanes8(1.0) - Lanes8(d.G) * dgamma / q_trial), Lanes8(0.0));
    Lanes8 p_y = p_trial - Lanes8(d.K * d.eta_bar) * dgamma;
    Lanes8 kappa_y = kappa_n + Lanes8(d.xi) * dgamma;
    if (d.eta > 0.0) {
      // the apex, where the smooth return would overshoot the axis
      const Mask8 apex = q_trial - Lanes8(d.G) * dgamma < Lanes8(0.0);
      if (any(apex & r.yielded)) {
        const double ratio = d.xi / d.eta;
        Lanes8 p_a, kappa_a;
        if (d.eta_bar > 0.0) {
          const double k = d.xi / d.eta_bar;
          const Lanes8 dev = cohesion.solve(p_trial - Lanes8(ratio) * c_n, Lanes8(d.K),
                                            Lanes8(ratio), Lanes8(k), kappa_n);
          p_a = p_trial - Lanes8(d.K) * dev;
          kappa_a = kappa_n + Lanes8(k) * dev;
        } else {
          p_a = Lanes8(ratio) * c_n;
          kappa_a = kappa_n;
        }
        factor_y = select(apex, Lanes8(0.0), factor_y);
        p_y = select(apex, p_a, p_y);
        kappa_y = select(apex, kappa_a, kappa_y);
      }
    }
    p = select(r.yielded, p_y, p);
    factor = select(r.yielded, factor_y, factor);
    r.kappa = select(r.yielded, kappa_y, kappa_n);
  }
  meridian_result(trial, p, factor, d.K, d.G, r.tau, r.e_el);
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_DRUCKER_PRAGER_LANES_INL_H_
