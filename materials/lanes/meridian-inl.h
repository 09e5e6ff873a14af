// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): what the pressure-dependent
// models share, in lanes: the trial state on the meridian plane (materials/hencky.hpp's
// meridian_trial and meridian_result) and linear cohesion hardening
// (materials/cohesion_hardening.hpp).
#if defined(FEMDEM_MERIDIAN_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_MERIDIAN_LANES_INL_H_
#undef FEMDEM_MERIDIAN_LANES_INL_H_
#else
#define FEMDEM_MERIDIAN_LANES_INL_H_
#endif

#include "materials/cohesion_hardening.hpp"
#include "materials/hencky.hpp"
#include "materials/lanes/lanes8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

struct MeridianTrialLanes {
  Lanes8 ed[3];  // deviatoric log strains
  Lanes8 p, q;
};

HWY_INLINE MeridianTrialLanes meridian_trial(const Lanes8 e[3], double K, double G) {
  MeridianTrialLanes t;
  const Lanes8 ev = e[0] + e[1] + e[2];
  const Lanes8 em = ev / Lanes8(3.0);
  for (int i = 0; i < 3; ++i) t.ed[i] = e[i] - em;
  t.p = Lanes8(K) * ev;
  t.q = Lanes8(G) * sqrt(Lanes8(2.0) * (t.ed[0] * t.ed[0] + t.ed[1] * t.ed[1] + t.ed[2] * t.ed[2]));
  return t;
}

HWY_INLINE void meridian_result(const MeridianTrialLanes& t, const Lanes8& p, const Lanes8& factor,
                                double K, double G, Lanes8 tau[3], Lanes8 e_el[3]) {
  for (int i = 0; i < 3; ++i) {
    tau[i] = p + Lanes8(2.0 * G) * factor * t.ed[i];
    e_el[i] = p / Lanes8(3.0 * K) + factor * t.ed[i];
  }
}

// CohesionHardening lane by lane.
struct CohesionLanes {
  const CohesionHardening& law;
  HWY_INLINE Lanes8 value(const Lanes8& kappa) const {
    return max(Lanes8(law.residual), Lanes8(law.c0) + Lanes8(law.H) * kappa);
  }
  HWY_INLINE Lanes8 slope(const Lanes8& kappa) const {
    if (!(law.H < 0.0)) return Lanes8(law.H);
    return select(kappa < Lanes8(law.knee()), Lanes8(law.H), Lanes8(0.0));
  }
  // CohesionHardening::solve: the root of phi - a x - m (c(kappa_n + k x) - c(kappa_n)).
  HWY_INLINE Lanes8 solve(const Lanes8& phi_trial, const Lanes8& a, const Lanes8& m,
                          const Lanes8& k, const Lanes8& kappa_n) const {
    const Lanes8 h = slope(kappa_n);
    const Lanes8 x = phi_trial / (a + m * k * h);
    if (!(law.H < 0.0)) return x;  // no knee
    const Mask8 past = (h != Lanes8(0.0)) & (kappa_n + k * x > Lanes8(law.knee()));
    return select(past, (phi_trial - m * (Lanes8(law.residual) - value(kappa_n))) / a, x);
  }
};

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_MERIDIAN_LANES_INL_H_
