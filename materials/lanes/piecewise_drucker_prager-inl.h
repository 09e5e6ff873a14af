// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the piece-wise linear
// Drucker-Prager return of materials/piecewise_drucker_prager.hpp in lanes. The piece of each
// lane's return is the one whose corner values g bracket the lane's g (a count of the corners
// below it, as the scalar code's binary search finds), its A and B gathered by selects.
#if defined(FEMDEM_PIECEWISE_DRUCKER_PRAGER_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_PIECEWISE_DRUCKER_PRAGER_LANES_INL_H_
#undef FEMDEM_PIECEWISE_DRUCKER_PRAGER_LANES_INL_H_
#else
#define FEMDEM_PIECEWISE_DRUCKER_PRAGER_LANES_INL_H_
#endif

#include "materials/lanes/finite_strain_update-inl.h"
#include "materials/lanes/meridian-inl.h"
#include "materials/piecewise_drucker_prager.hpp"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

HWY_INLINE PrincipalReturnLanes return_map_lanes(const PiecewiseDruckerPrager& m, const Lanes8 e[3],
                                                 const Lanes8& kappa_n, double /*dt*/) {
  PrincipalReturnLanes r;
  const double K = m.K, G = m.G;
  const MeridianTrialLanes trial = meridian_trial(e, K, G);
  const Lanes8 p_trial = trial.p, q_trial = trial.q;
  Lanes8 q_lim = Lanes8(m.B[0]) - Lanes8(m.A[0]) * p_trial;
  for (std::size_t k = 1; k < m.A.size(); ++k)
    q_lim = min(q_lim, Lanes8(m.B[k]) - Lanes8(m.A[k]) * p_trial);
  const Lanes8 phi = q_trial - q_lim;
  r.kappa = kappa_n;
  r.yielded = phi > Lanes8(1e-12) * (q_trial + abs(Lanes8(m.A[0]) * p_trial) + Lanes8(m.B[0]));
  Lanes8 p = p_trial, factor(1.0);
  if (any(r.yielded)) {
    const Lanes8 g = Lanes8(K * m.A_bar) * q_trial - Lanes8(G) * p_trial;
    // the piece: k = the number of corners with g_end <= g (std::upper_bound)
    Lanes8 A(m.A[0]), B(m.B[0]);
    for (std::size_t k = 0; k < m.g_end.size(); ++k) {
      const Mask8 beyond = Lanes8(m.g_end[k]) <= g;
      A = select(beyond, Lanes8(m.A[k + 1]), A);
      B = select(beyond, Lanes8(m.B[k + 1]), B);
    }
    const Lanes8 dgamma = (q_trial + A * p_trial - B) / (Lanes8(G) + Lanes8(K * m.A_bar) * A);
    Lanes8 factor_y =
        select(q_trial > Lanes8(0.0), max(Lanes8(0.0), Lanes8(1.0) - Lanes8(G) * dgamma / q_trial),
               Lanes8(0.0));
    Lanes8 p_y = p_trial - Lanes8(K * m.A_bar) * dgamma;
    Lanes8 kappa_y = kappa_n + dgamma;
    // beyond the apex: the apex
    const Mask8 apex = g <= Lanes8(m.g_apex);
    if (any(apex)) {
      factor_y = select(apex, Lanes8(0.0), factor_y);
      p_y = select(apex, Lanes8(m.p_apex), p_y);
      kappa_y = select(apex, kappa_n + q_trial / Lanes8(G), kappa_y);
    }
    p = select(r.yielded, p_y, p);
    factor = select(r.yielded, factor_y, factor);
    r.kappa = select(r.yielded, kappa_y, kappa_n);
  }
  meridian_result(trial, p, factor, K, G, r.tau, r.e_el);
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_PIECEWISE_DRUCKER_PRAGER_LANES_INL_H_
