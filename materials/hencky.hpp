// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Hencky (logarithmic-strain) hyperelasticity: the elastic part of every femdem material.
//
// Why Hencky and not neo-Hookean: the finite-strain plasticity of the thesis (de Souza Neto et
// al. 2008, ch. 14) works in principal logarithmic elastic strains, where the return mapping is
// the small-strain one and the exponential map makes plastic flow exactly volume-preserving.
// With Hencky elasticity the Kirchhoff stress is linear in the log strain,
//   tau_i = lambda (e_1 + e_2 + e_3) + 2 G e_i,   e_i = ln(lambda_i) = 0.5 ln(b_i),
// so the elastic and elasto-plastic bodies share one stress law. It is accurate for moderate
// elastic strains (metals, concrete, rock: elastic strains below a few percent).
#include <cmath>

#include "materials/symmetric_eigen3.hpp"

namespace femdem {

struct HenckyResult {
  double tau[6];  // Kirchhoff stress, xx yy zz xy yz xz
  double energy;  // stored energy per reference volume
};

// Principal log strains of b (elastic left Cauchy-Green tensor, 6 components) and its frame.
struct PrincipalStrains {
  double e[3];
  double n[3][3];  // n[k][i]: component k of principal direction i
};

inline PrincipalStrains principal_log_strains(const double b[6]) {
  const SymEig3 eig = symmetric_eigen3(b);
  PrincipalStrains p;
  for (int i = 0; i < 3; ++i) p.e[i] = 0.5 * std::log(eig.value[i]);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) p.n[k][i] = eig.vector[k][i];
  return p;
}

// tau = sum_i tau_i n_i (x) n_i
inline void assemble_from_principal(const double t[3], const double n[3][3], double out[6]) {
  out[0] = t[0] * n[0][0] * n[0][0] + t[1] * n[0][1] * n[0][1] + t[2] * n[0][2] * n[0][2];
  out[1] = t[0] * n[1][0] * n[1][0] + t[1] * n[1][1] * n[1][1] + t[2] * n[1][2] * n[1][2];
  out[2] = t[0] * n[2][0] * n[2][0] + t[1] * n[2][1] * n[2][1] + t[2] * n[2][2] * n[2][2];
  out[3] = t[0] * n[0][0] * n[1][0] + t[1] * n[0][1] * n[1][1] + t[2] * n[0][2] * n[1][2];
  out[4] = t[0] * n[1][0] * n[2][0] + t[1] * n[1][1] * n[2][1] + t[2] * n[1][2] * n[2][2];
  out[5] = t[0] * n[0][0] * n[2][0] + t[1] * n[0][1] * n[2][1] + t[2] * n[0][2] * n[2][2];
}

inline HenckyResult hencky_stress(const double b[6], double lambda, double G) {
  const PrincipalStrains p = principal_log_strains(b);
  const double tr = p.e[0] + p.e[1] + p.e[2];
  double t[3];
  for (int i = 0; i < 3; ++i) t[i] = lambda * tr + 2.0 * G * p.e[i];
  HenckyResult r;
  assemble_from_principal(t, p.n, r.tau);
  r.energy = 0.5 * lambda * tr * tr + G * (p.e[0] * p.e[0] + p.e[1] * p.e[1] + p.e[2] * p.e[2]);
  return r;
}

// The meridian-plane view of a principal log-strain trial that pressure-dependent models work
// in: p = K ev and q = sqrt(J2) = sqrt(s:s / 2) = G sqrt(2 ed:ed), since s = 2 G ed.
struct MeridianTrial {
  double ed[3];  // deviatoric log strains
  double p, q;
};

inline MeridianTrial meridian_trial(const double e[3], double K, double G) {
  MeridianTrial t;
  const double ev = e[0] + e[1] + e[2];
  const double em = ev / 3.0;
  for (int i = 0; i < 3; ++i) t.ed[i] = e[i] - em;
  t.p = K * ev;
  t.q = G * std::sqrt(2.0 * (t.ed[0] * t.ed[0] + t.ed[1] * t.ed[1] + t.ed[2] * t.ed[2]));
  return t;
}

// Principal Kirchhoff stress and elastic log strain of a return that keeps the trial's
// deviatoric direction, scaled by `factor`, and ends at pressure p.
inline void meridian_result(const MeridianTrial& t, double p, double factor, double K, double G,
                            double tau[3], double e_el[3]) {
  for (int i = 0; i < 3; ++i) {
    tau[i] = p + 2.0 * G * factor * t.ed[i];
    e_el[i] = p / (3.0 * K) + factor * t.ed[i];
  }
}

}  // namespace femdem
