// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Mohr-Coulomb plasticity in principal stresses with dilatancy (non-associated when psi < phi)
// and linear cohesion hardening/softening; the multi-surface return of Peric & de Souza Neto
// (1999) / de Souza Neto, Peric & Owen 2008 Box 8.5, which the thesis implements (sec. 2.2.4.2).
//
// Tension positive, principal stresses sorted s1 >= s2 >= s3. Plane (i, j) of the hexagon:
//   Phi_ij = (s_i - s_j) + (s_i + s_j) sin(phi) - 2 c(kappa) cos(phi),
// flow n_ij = (1 + sin psi) e_i - (1 - sin psi) e_j, so the stress moves by -dgamma D n_ij
// (D the Hencky/isotropic elasticity in principal space) and kappa += 2 cos(phi) dgamma.
// Returns tried in order, each accepted if it keeps the ordering s1 >= s2 >= s3:
//   1. main plane (1,3);
//   2. an edge: right (planes (1,3) and (1,2), s2 = s3 after) if
//      (1 - sin psi) s1 - 2 s2 + (1 + sin psi) s3 > 0 on the trial state, else left ((1,3) and
//      (2,3), s1 = s2 after); two multipliers from a 2x2 system;
//   3. the apex s1 = s2 = s3 = c cot(phi): p_trial - K dev = cot(phi) c(kappa_n + cos(phi) /
//      sin(psi) dev). With psi = 0 the flow cannot change the pressure; the stress goes to the
//      apex (the only admissible point) and kappa is unchanged. With phi = 0 (Tresca) there is
//      no apex and the edge return always holds.
// The thesis' printed formulas have misprints that the generic form here avoids (notes
// seed002-part1 sec. 2.5 and 6: the factor 2 lost from the main-plane return (2.94), "sigma_j +
// sigma_j" in (2.98), a sign in the flow rule (2.86)).
// The stiffnesses a_PQ = m_P . D n_Q (m_P the yield gradient) are computed from the sorted
// planes; a_PP and the edge couplings equal de Souza Neto's a and b.
#include <algorithm>
#include <cmath>
#include <string>

#include "materials/cohesion_hardening.hpp"
#include "materials/finite_strain_update.hpp"
#include "materials/material_base.hpp"

namespace femdem {

struct MohrCoulomb {
  double K = 0.0, G = 0.0;
  double sin_phi = 0.0, cos_phi = 1.0, sin_psi = 0.0;
  CohesionHardening cohesion;

  // Stress change per unit multiplier of plane (i, j): D n_ij.
  void flow_stress(int i, int j, double out[3]) const {
    const double lam = K - 2.0 / 3.0 * G;
    const double vol = lam * 2.0 * sin_psi;  // lambda tr(n)
    for (int k = 0; k < 3; ++k) out[k] = vol;
    out[i] += 2.0 * G * (1.0 + sin_psi);
    out[j] -= 2.0 * G * (1.0 - sin_psi);
  }
  // m_ij . v: the change of Phi_ij for a stress change v.
  double yield_dot(int i, int j, const double v[3]) const {
    return (1.0 + sin_phi) * v[i] - (1.0 - sin_phi) * v[j];
  }
  double yield_value(int i, int j, const double s[3], double c) const {
    return (s[i] - s[j]) + (s[i] + s[j]) * sin_phi - 2.0 * c * cos_phi;
  }

  PrincipalReturn return_map(const double e_trial[3], double kappa_n, double /*dt*/) const {
    PrincipalReturn r;
    // sort: o[0] the largest principal strain (and stress), o[2] the smallest
    int o[3] = {0, 1, 2};
    if (e_trial[o[0]] < e_trial[o[1]]) std::swap(o[0], o[1]);
    if (e_trial[o[1]] < e_trial[o[2]]) std::swap(o[1], o[2]);
    if (e_trial[o[0]] < e_trial[o[1]]) std::swap(o[0], o[1]);
    const double ev = e_trial[0] + e_trial[1] + e_trial[2];
    const double lam = K - 2.0 / 3.0 * G;
    double st[3];  // sorted trial stresses
    for (int k = 0; k < 3; ++k) st[k] = lam * ev + 2.0 * G * e_trial[o[k]];
    const double c_n = cohesion.value(kappa_n);
    const double phi13 = yield_value(0, 2, st, c_n);
    const double scale = std::fabs(st[0]) + std::fabs(st[2]) + 2.0 * c_n * cos_phi;
    r.kappa = kappa_n;
    r.yielded = phi13 > 1e-12 * scale;
    double s[3] = {st[0], st[1], st[2]};
    if (r.yielded) {
      const double tol = 1e-10 * scale;
      auto ordered = [&](const double x[3]) { return x[0] >= x[1] - tol && x[1] >= x[2] - tol; };
      const double m2 = 2.0 * cos_phi;  // -dPhi/dc and dkappa/dgamma
      double d13[3];
      flow_stress(0, 2, d13);
      // 1. main plane
      const double a = yield_dot(0, 2, d13);
      const double dg = cohesion.solve(phi13, a, m2, m2, kappa_n);
      for (int k = 0; k < 3; ++k) s[k] = st[k] - dg * d13[k];
      bool done = ordered(s);
      if (done) r.kappa = kappa_n + m2 * dg;
      // 2. edge
      if (!done) {
        const bool right = (1.0 - sin_psi) * st[0] - 2.0 * st[1] + (1.0 + sin_psi) * st[2] > 0.0;
        const int bi = right ? 0 : 1, bj = right ? 1 : 2;  // second plane
        double db[3];
        flow_stress(bi, bj, db);
        const double aab = yield_dot(0, 2, db), aba = yield_dot(bi, bj, d13);
        const double abb = yield_dot(bi, bj, db);
        const double phib = yield_value(bi, bj, st, c_n);
        // [a + h, aab + h; aba + h, abb + h] [x; y] = [phi13 - w; phib - w], with h the
        // hardening stiffness and w the cohesion change past the knee (CohesionHardening)
        auto solve2 = [&](double h, double w, double* x, double* y) {
          const double A11 = a + h, A12 = aab + h, A21 = aba + h, A22 = abb + h;
          const double det = A11 * A22 - A12 * A21;
          const double r1 = phi13 - w, r2 = phib - w;
          *x = (r1 * A22 - A12 * r2) / det;
          *y = (A11 * r2 - A21 * r1) / det;
        };
        double x, y;
        const double H = cohesion.slope(kappa_n);
        solve2(m2 * m2 * H, 0.0, &x, &y);
        if (H != 0.0 && kappa_n + m2 * (x + y) > cohesion.knee())
          solve2(0.0, m2 * (cohesion.residual - c_n), &x, &y);
        for (int k = 0; k < 3; ++k) s[k] = st[k] - x * d13[k] - y * db[k];
        done = x >= 0.0 && y >= 0.0 && ordered(s);
        if (done) r.kappa = kappa_n + m2 * (x + y);
      }
      // 3. apex
      if (!done && sin_phi > 0.0) {
        const double cot = cos_phi / sin_phi;
        const double p_trial = K * ev;
        double p;
        if (sin_psi > 0.0) {
          const double k = cos_phi / sin_psi;
          const double dev = cohesion.solve(p_trial - cot * c_n, K, cot, k, kappa_n);
          p = p_trial - K * dev;
          r.kappa = kappa_n + k * dev;
        } else {
          p = cot * c_n;
        }
        s[0] = s[1] = s[2] = p;
      }
    }
    const double p = (s[0] + s[1] + s[2]) / 3.0;
    for (int k = 0; k < 3; ++k) {
      r.tau[o[k]] = s[k];
      r.e_el[o[k]] = (s[k] - p) / (2.0 * G) + p / (3.0 * K);
    }
    return r;
  }
};

// A Mohr-Coulomb material's constants as the scene gives them.
struct MohrCoulombParams : FrictionalParams {};

inline MohrCoulomb make_mohr_coulomb(const MaterialBase& e, const MohrCoulombParams& m) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  MohrCoulomb mc;
  mc.K = e.bulk_modulus();
  mc.G = e.shear_modulus();
  mc.sin_phi = std::sin(m.friction_angle * deg);
  mc.cos_phi = std::cos(m.friction_angle * deg);
  mc.sin_psi = std::sin(m.dilatancy_angle * deg);
  mc.cohesion = {m.cohesion, m.cohesion_hardening_modulus, m.residual_cohesion};
  return mc;
}

inline std::string mohr_coulomb_param_error(const MaterialBase& e, const MohrCoulombParams& m) {
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 90.0))
    return "friction_angle must lie in [0, 90) degrees";
  if (!(m.dilatancy_angle >= 0.0 && m.dilatancy_angle <= m.friction_angle))
    return "dilatancy_angle must lie in [0, friction_angle]";
  const MohrCoulomb mc = make_mohr_coulomb(e, m);
  // main plane a + 4 cos^2 H > 0; edges (a + b) + 8 cos^2 H > 0 (the sum of the two
  // multipliers); apex K + cos / (sin_psi tan) H > 0
  double d13[3], d12[3], d23[3];
  mc.flow_stress(0, 2, d13);
  mc.flow_stress(0, 1, d12);
  mc.flow_stress(1, 2, d23);
  const double a = mc.yield_dot(0, 2, d13), c2 = 4.0 * mc.cos_phi * mc.cos_phi;
  double steepest = -a / c2;
  steepest = std::fmax(steepest, -(a + mc.yield_dot(0, 2, d12)) / (2.0 * c2));
  steepest = std::fmax(steepest, -(a + mc.yield_dot(0, 2, d23)) / (2.0 * c2));
  if (mc.sin_phi > 0.0 && mc.sin_psi > 0.0)
    steepest = std::fmax(steepest, -mc.K * mc.sin_psi * mc.sin_phi / (mc.cos_phi * mc.cos_phi));
  return cohesion_param_error(m, steepest);
}

// The scene model `mohr_coulomb` (docs/SCENES.md, [[materials]]).
struct MohrCoulombMaterial {
  static constexpr const char* name = "mohr_coulomb";
  using Params = MohrCoulombParams;
  using Kernel = MohrCoulomb;
  static std::vector<std::string> keys() { return frictional_keys(); }
  static std::string check(const MaterialBase& e, const Params& p) {
    return mohr_coulomb_param_error(e, p);
  }
  static Kernel compile(const MaterialBase& e, const Params& p) { return make_mohr_coulomb(e, p); }
  static Params read(const MaterialBase& e, MaterialKeys& k) {
    Params m;
    read_frictional(k, m);
    const std::string err = mohr_coulomb_param_error(e, m);
    if (!err.empty()) k.fail("cohesion_hardening_modulus", err);
    return m;
  }
  static std::string describe(const MaterialBase&, const Params& m) {
    return describe_frictional(m) + describe_cohesion_hardening(m);
  }
};

}  // namespace femdem
