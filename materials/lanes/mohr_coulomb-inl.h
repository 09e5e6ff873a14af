// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the multi-surface Mohr-Coulomb
// return of materials/mohr_coulomb.hpp in lanes. Each lane sorts its principal strains with a
// three-comparator network (carrying where each came from, to scatter the result back); the
// main-plane, edge and apex returns are computed for the lanes that need them and the first one
// the scalar code would accept is kept, lane by lane (an edge attempt that fails where there is
// no apex is kept too, as there).
#if defined(FEMDEM_MOHR_COULOMB_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_MOHR_COULOMB_LANES_INL_H_
#undef FEMDEM_MOHR_COULOMB_LANES_INL_H_
#else
#define FEMDEM_MOHR_COULOMB_LANES_INL_H_
#endif

#include "materials/lanes/finite_strain_update-inl.h"
#include "materials/lanes/meridian-inl.h"
#include "materials/mohr_coulomb.hpp"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {
namespace mohr_coulomb_lanes_detail {

// v[a], v[b] (and their origins) swapped where v[a] < v[b].
HWY_INLINE void order(Lanes8 v[3], Lanes8 o[3], int a, int b) {
  const Mask8 swap = v[a] < v[b];
  const Lanes8 va = v[a], oa = o[a];
  v[a] = select(swap, v[b], va);
  v[b] = select(swap, va, v[b]);
  o[a] = select(swap, o[b], oa);
  o[b] = select(swap, oa, o[b]);
}

}  // namespace mohr_coulomb_lanes_detail

HWY_INLINE PrincipalReturnLanes return_map_lanes(const MohrCoulomb& mc, const Lanes8 e_trial[3],
                                                 const Lanes8& kappa_n, double /*dt*/) {
  namespace d = mohr_coulomb_lanes_detail;
  const double K = mc.K, G = mc.G, sin_phi = mc.sin_phi, cos_phi = mc.cos_phi, sin_psi = mc.sin_psi;
  const CohesionLanes cohesion{mc.cohesion};
  PrincipalReturnLanes r;
  // sort: e[0] the largest principal strain (and stress), o[k] where e[k] came from
  Lanes8 e[3] = {e_trial[0], e_trial[1], e_trial[2]};
  Lanes8 o[3] = {Lanes8(0.0), Lanes8(1.0), Lanes8(2.0)};
  d::order(e, o, 0, 1);
  d::order(e, o, 1, 2);
  d::order(e, o, 0, 1);
  const Lanes8 ev = e_trial[0] + e_trial[1] + e_trial[2];
  const double lam = K - 2.0 / 3.0 * G;
  Lanes8 st[3];
  for (int k = 0; k < 3; ++k) st[k] = Lanes8(lam) * ev + Lanes8(2.0 * G) * e[k];
  const Lanes8 c_n = cohesion.value(kappa_n);
  auto yield_value = [&](const Lanes8& si, const Lanes8& sj) {
    return (si - sj) + (si + sj) * Lanes8(sin_phi) - Lanes8(2.0 * cos_phi) * c_n;
  };
  auto yield_dot = [&](const Lanes8& vi, const Lanes8& vj) {
    return Lanes8(1.0 + sin_phi) * vi - Lanes8(1.0 - sin_phi) * vj;
  };
  const Lanes8 phi13 = yield_value(st[0], st[2]);
  const Lanes8 scale = abs(st[0]) + abs(st[2]) + Lanes8(2.0 * cos_phi) * c_n;
  r.kappa = kappa_n;
  r.yielded = phi13 > Lanes8(1e-12) * scale;
  Lanes8 s[3] = {st[0], st[1], st[2]};
  if (any(r.yielded)) {
    const Lanes8 tol = Lanes8(1e-10) * scale;
    auto ordered = [&](const Lanes8 x[3]) { return (x[0] >= x[1] - tol) & (x[1] >= x[2] - tol); };
    const double m2 = 2.0 * cos_phi;
    // flow stresses D n_ij of the planes (0,2), (0,1), (1,2): constants
    double f13[3], f12[3], f23[3];
    mc.flow_stress(0, 2, f13);
    mc.flow_stress(0, 1, f12);
    mc.flow_stress(1, 2, f23);
    // 1. main plane
    const double a = (1.0 + sin_phi) * f13[0] - (1.0 - sin_phi) * f13[2];
    const Lanes8 dg = cohesion.solve(phi13, Lanes8(a), Lanes8(m2), Lanes8(m2), kappa_n);
    Lanes8 sm[3];
    for (int k = 0; k < 3; ++k) sm[k] = st[k] - dg * Lanes8(f13[k]);
    const Mask8 main_done = r.yielded & ordered(sm);
    Mask8 done = main_done | !r.yielded;
    for (int k = 0; k < 3; ++k) s[k] = select(main_done, sm[k], s[k]);
    r.kappa = select(main_done, kappa_n + Lanes8(m2) * dg, r.kappa);
    // 2. edge: right (planes (0,2) and (0,1)) or left ((0,2) and (1,2)), per lane
    if (any(!done)) {
      const Mask8 right =
          Lanes8(1.0 - sin_psi) * st[0] - Lanes8(2.0) * st[1] + Lanes8(1.0 + sin_psi) * st[2] >
          Lanes8(0.0);
      Lanes8 db[3];
      for (int k = 0; k < 3; ++k) db[k] = select(right, Lanes8(f12[k]), Lanes8(f23[k]));
      const Lanes8 aab = yield_dot(db[0], db[2]);
      // a_ba = m_b . D n_13 and a_bb = m_b . D n_b, m_b the gradient of the second plane
      const Lanes8 aba_r((1.0 + sin_phi) * f13[0] - (1.0 - sin_phi) * f13[1]);
      const Lanes8 aba_l((1.0 + sin_phi) * f13[1] - (1.0 - sin_phi) * f13[2]);
      const Lanes8 abb_r((1.0 + sin_phi) * f12[0] - (1.0 - sin_phi) * f12[1]);
      const Lanes8 abb_l((1.0 + sin_phi) * f23[1] - (1.0 - sin_phi) * f23[2]);
      const Lanes8 a_ba = select(right, aba_r, aba_l), a_bb = select(right, abb_r, abb_l);
      const Lanes8 phib = select(right, yield_value(st[0], st[1]), yield_value(st[1], st[2]));
      auto solve2 = [&](const Lanes8& h, const Lanes8& w, Lanes8& x, Lanes8& y) {
        const Lanes8 A11 = Lanes8(a) + h, A12 = aab + h, A21 = a_ba + h, A22 = a_bb + h;
        const Lanes8 det = A11 * A22 - A12 * A21;
        const Lanes8 r1 = phi13 - w, r2 = phib - w;
        x = (r1 * A22 - A12 * r2) / det;
        y = (A11 * r2 - A21 * r1) / det;
      };
      Lanes8 x, y;
      const Lanes8 H = cohesion.slope(kappa_n);
      solve2(Lanes8(m2 * m2) * H, Lanes8(0.0), x, y);
      if (mc.cohesion.H < 0.0) {
        const Mask8 past =
            (H != Lanes8(0.0)) & (kappa_n + Lanes8(m2) * (x + y) > Lanes8(mc.cohesion.knee()));
        if (any(past)) {
          Lanes8 x2, y2;
          solve2(Lanes8(0.0), Lanes8(m2) * (Lanes8(mc.cohesion.residual) - c_n), x2, y2);
          x = select(past, x2, x);
          y = select(past, y2, y);
        }
      }
      Lanes8 se[3];
      for (int k = 0; k < 3; ++k) se[k] = st[k] - x * Lanes8(f13[k]) - y * db[k];
      const Mask8 edge_done = (!done) & (x >= Lanes8(0.0)) & (y >= Lanes8(0.0)) & ordered(se);
      // where the main plane failed the edge state is kept, accepted or not (as the scalar code)
      for (int k = 0; k < 3; ++k) s[k] = select(done, s[k], se[k]);
      r.kappa = select(edge_done, kappa_n + Lanes8(m2) * (x + y), r.kappa);
      done = done | edge_done;
      // 3. apex
      if (sin_phi > 0.0 && any(!done)) {
        const double cot = cos_phi / sin_phi;
        const Lanes8 p_trial = Lanes8(K) * ev;
        Lanes8 p, kappa_a = kappa_n;
        if (sin_psi > 0.0) {
          const double k = cos_phi / sin_psi;
          const Lanes8 dev = cohesion.solve(p_trial - Lanes8(cot) * c_n, Lanes8(K), Lanes8(cot),
                                            Lanes8(k), kappa_n);
          p = p_trial - Lanes8(K) * dev;
          kappa_a = kappa_n + Lanes8(k) * dev;
        } else {
          p = Lanes8(cot) * c_n;
        }
        for (int k = 0; k < 3; ++k) s[k] = select(done, s[k], p);
        r.kappa = select(done, r.kappa, kappa_a);
      }
    }
  }
  const Lanes8 p = (s[0] + s[1] + s[2]) / Lanes8(3.0);
  // scatter back to the eigen-solver's order
  for (int j = 0; j < 3; ++j) {
    r.tau[j] = Lanes8(0.0);
    r.e_el[j] = Lanes8(0.0);
  }
  for (int k = 0; k < 3; ++k) {
    const Lanes8 el = (s[k] - p) / Lanes8(2.0 * G) + p / Lanes8(3.0 * K);
    for (int j = 0; j < 3; ++j) {
      const Mask8 here = o[k] == Lanes8(static_cast<double>(j));
      r.tau[j] = select(here, s[k], r.tau[j]);
      r.e_el[j] = select(here, el, r.e_el[j]);
    }
  }
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_MOHR_COULOMB_LANES_INL_H_
