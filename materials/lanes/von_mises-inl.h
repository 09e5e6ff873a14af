// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the von Mises radial return of
// materials/von_mises.hpp in lanes, with every hardening law and the Johnson-Cook rate factor.
// The closed-form linear return is one expression; the other laws take the same safeguarded
// Newton iteration as the scalar code, each lane stopping where the scalar code would (a lane
// that has converged is frozen by a mask), until no lane is left.
#if defined(FEMDEM_VON_MISES_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_VON_MISES_LANES_INL_H_
#undef FEMDEM_VON_MISES_LANES_INL_H_
#else
#define FEMDEM_VON_MISES_LANES_INL_H_
#endif

#include "materials/lanes/finite_strain_update-inl.h"
#include "materials/von_mises.hpp"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {
namespace von_mises_lanes_detail {

// sigma_y(eps_p) and its slope, lane by lane (VonMises::flow_stress).
HWY_INLINE Lanes8 flow_stress(const VonMises& m, const Lanes8& eps_p, Lanes8& slope) {
  switch (m.law) {
    case HardeningLaw::Linear: {
      const Lanes8 sy = Lanes8(m.yield_stress) + Lanes8(m.hardening_modulus) * eps_p;
      const Mask8 off = sy <= Lanes8(0.0);
      slope = select(off, Lanes8(0.0), Lanes8(m.hardening_modulus));
      return select(off, Lanes8(0.0), sy);
    }
    case HardeningLaw::Tabulated: {
      // the segment [x_i, x_i+1) holding eps_p: the last i with x_i <= eps_p; constant
      // beyond the last point
      const auto& c = m.curve;
      const std::size_t n = c.size();
      Lanes8 sy(c[0].second);
      slope = Lanes8(0.0);
      for (std::size_t i = 0; i + 1 < n; ++i) {
        const double h = (c[i + 1].second - c[i].second) / (c[i + 1].first - c[i].first);
        const Mask8 in = eps_p >= Lanes8(c[i].first);
        sy = select(in, Lanes8(c[i].second) + Lanes8(h) * (eps_p - Lanes8(c[i].first)), sy);
        slope = select(in, Lanes8(h), slope);
      }
      const Mask8 beyond = eps_p >= Lanes8(c[n - 1].first);
      slope = select(beyond, Lanes8(0.0), slope);
      return select(beyond, Lanes8(c[n - 1].second), sy);
    }
    case HardeningLaw::Swift: {
      const Lanes8 x = Lanes8(m.swift_eps0) + eps_p;
      const Lanes8 sy = Lanes8(m.swift_K) * exp(Lanes8(m.swift_n) * log(x));
      slope = Lanes8(m.swift_n) * sy / x;
      return sy;
    }
  }
  slope = Lanes8(0.0);
  return Lanes8(0.0);
}

// Johnson-Cook R(dgamma) and dR/d dgamma (VonMises::rate_factor).
HWY_INLINE Lanes8 rate_factor(const VonMises& m, const Lanes8& dgamma, double dt, Lanes8& dR) {
  if (m.jc_C <= 0.0 || dt <= 0.0) {
    dR = Lanes8(0.0);
    return Lanes8(1.0);
  }
  const Lanes8 ratio = dgamma / Lanes8(dt * m.jc_epsdot0);
  const Mask8 fast = ratio > Lanes8(1.0);
  dR = select(fast, Lanes8(m.jc_C) / dgamma, Lanes8(0.0));
  return select(fast, Lanes8(1.0) + Lanes8(m.jc_C) * log(select(fast, ratio, Lanes8(1.0))),
                Lanes8(1.0));
}

// VonMises::solve_dgamma in the lanes `active`.
HWY_INLINE Lanes8 solve_dgamma(const VonMises& m, const Lanes8& q_trial, const Lanes8& eps_p_n,
                               const Lanes8& f_trial, double dt, Mask8 active) {
  const Lanes8 three_G(3.0 * m.G);
  Lanes8 lo(0.0), hi = q_trial / three_G;
  Lanes8 h0;
  flow_stress(m, eps_p_n, h0);
  Lanes8 x = f_trial / (three_G + max(h0, Lanes8(0.0)));
  x = select((x > lo) & (x < hi), x, Lanes8(0.5) * (lo + hi));
  const Lanes8 tol = Lanes8(1e-14) * q_trial;
  for (int it = 0; it < 200 && any(active); ++it) {
    Lanes8 H, dR;
    const Lanes8 sy = flow_stress(m, eps_p_n + x, H);
    const Lanes8 R = rate_factor(m, x, dt, dR);
    const Lanes8 phi = q_trial - three_G * x - sy * R;
    active &= !(abs(phi) <= tol);
    const Mask8 up = phi > Lanes8(0.0);
    lo = select(active & up, x, lo);
    hi = select(active & !up, x, hi);
    const Lanes8 dphi = -three_G - H * R - sy * dR;
    Lanes8 xn = select(dphi < Lanes8(0.0), x - phi / dphi, lo - Lanes8(1.0));
    xn = select((xn > lo) & (xn < hi), xn, Lanes8(0.5) * (lo + hi));
    const Mask8 collapsed = hi - lo <= Lanes8(4e-16) * hi;
    x = select(active, xn, x);
    active &= !collapsed;
  }
  return x;
}

}  // namespace von_mises_lanes_detail

HWY_INLINE PrincipalReturnLanes return_map_lanes(const VonMises& m, const Lanes8 e[3],
                                                 const Lanes8& eps_p_n, double dt) {
  namespace d = von_mises_lanes_detail;
  PrincipalReturnLanes r;
  const Lanes8 ev = e[0] + e[1] + e[2];
  const Lanes8 em = ev / Lanes8(3.0);
  const Lanes8 ed[3] = {e[0] - em, e[1] - em, e[2] - em};
  const Lanes8 p = Lanes8(m.lambda + 2.0 / 3.0 * m.G) * ev;
  const Lanes8 q_trial =
      Lanes8(2.0 * m.G) * sqrt(Lanes8(1.5) * (ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2]));
  Lanes8 H;
  const Lanes8 sy = d::flow_stress(m, eps_p_n, H);
  const Lanes8 f = q_trial - sy;
  const Mask8 yielded = (f > Lanes8(1e-12) * sy) & (q_trial > Lanes8(0.0));
  r.yielded = yielded;
  if (!any(yielded)) {
    for (int i = 0; i < 3; ++i) {
      r.tau[i] = p + Lanes8(2.0 * m.G) * ed[i];
      r.e_el[i] = e[i];
    }
    r.kappa = eps_p_n;
    return r;
  }
  Lanes8 dgamma;
  if (m.law == HardeningLaw::Linear && m.hardening_modulus >= 0.0 && !(m.jc_C > 0.0 && dt > 0.0))
    dgamma = f / Lanes8(3.0 * m.G + m.hardening_modulus);
  else
    dgamma = d::solve_dgamma(m, q_trial, eps_p_n, f, dt, yielded);
  dgamma = select(yielded, dgamma, Lanes8(0.0));
  const Lanes8 factor =
      select(yielded, Lanes8(1.0) - Lanes8(3.0 * m.G) * dgamma / q_trial, Lanes8(1.0));
  for (int i = 0; i < 3; ++i) {
    r.e_el[i] = select(yielded, em + factor * ed[i], e[i]);
    r.tau[i] = p + Lanes8(2.0 * m.G) * factor * ed[i];
  }
  r.kappa = eps_p_n + dgamma;
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_VON_MISES_LANES_INL_H_
