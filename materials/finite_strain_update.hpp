// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Multiplicative finite-strain elasto-plastic update (de Souza Neto, Peric & Owen 2008, ch. 14;
// thesis ch. 4, eqs 4.19-4.27) in a form that needs no F_n.
//
// The thesis keeps F_n and the elastic log strain and forms F_delta = F_n+1 F_n^-1 and
// b_e,trial = F_delta b_e,n F_delta^T. Since b_e,n = F_n Cp_n^-1 F_n^T (Cp = Fp^T Fp, the plastic
// right Cauchy-Green tensor), the same trial tensor is
//   b_e,trial = F_n+1 Cp_n^-1 F_n+1^T,
// so each Gauss point stores only Cp^-1 (6 numbers) and the equivalent plastic strain. Steps:
//   1. b_e,trial = F Cp^-1 F^T, principal log strains e_trial,i = 0.5 ln(b_i), directions n_i;
//   2. the model's small-strain return mapping in principal space (the Hencky law makes it the
//      small-strain one): tau_i, e_el,i, new eps_p;
//   3. tau = sum tau_i n_i (x) n_i;
//   4. if the step was plastic, b_e = sum exp(2 e_el,i) n_i (x) n_i and Cp^-1 = F^-1 b_e F^-T
//      (an elastic step leaves Cp^-1 unchanged, so no round-off accumulates while elastic).
// The exponential map makes isochoric flow exactly volume-preserving: det Cp^-1 stays 1 to
// round-off for von Mises. Objective by construction: F -> Q F gives b_e -> Q b_e Q^T, tau ->
// Q tau Q^T and leaves Cp^-1 unchanged.
//
// Interface for return-mapping models (von Mises, Drucker-Prager, Mohr-Coulomb, the piece-wise
// Drucker-Prager). A model is any type with
//   PrincipalReturn return_map(const double e_trial[3], double kappa_n, double dt) const;
// that takes the trial principal elastic log strains (unsorted, in the eigen-solver's order) and
// its hardening variable kappa, and returns, in the SAME order, the principal Kirchhoff stresses
// and elastic log strains after the return, the new kappa and whether the step was plastic.
// kappa is the model's own variable (von Mises: the equivalent plastic strain; Mohr-Coulomb and
// Drucker-Prager: de Souza Neto's cohesion-hardening variable). The update keeps, besides, the
// same equivalent plastic strain for every model, eps_p = sum sqrt(2/3 de_p : de_p) with
// de_p = e_trial - e_el the principal plastic log-strain increment (coaxial with the trial
// state), which is what the outputs show. The elastic law
// must be the linear Hencky law tau_i = lambda tr(e_el) + 2 G e_el,i (every femdem material);
// the stored energy is then 0.5 tau : e_el. Models needing an ordering (Mohr-Coulomb) sort
// internally and scatter back. Isotropy makes the result coaxial with the trial state.
// Header-only, no allocation, no virtual calls: it runs per Gauss point per step.
#include <cmath>
#include <concepts>

#include "materials/hencky.hpp"
#include "materials/log_strain_series.hpp"
#include "materials/symmetric_eigen3.hpp"

namespace femdem {

// Per Gauss point history. Symmetric tensors as xx yy zz xy yz xz.
struct GaussPointState {
  double Cp_inv[6] = {1.0, 1.0, 1.0, 0.0, 0.0, 0.0};  // inverse plastic right Cauchy-Green
  double eps_p = 0.0;                                 // equivalent plastic strain
  double kappa = 0.0;                                 // the model's hardening variable
};

// What a model's principal-space return mapping gives back (same order as e_trial).
struct PrincipalReturn {
  double tau[3];   // principal Kirchhoff stresses
  double e_el[3];  // principal elastic log strains after the return
  double kappa;    // new hardening variable
  bool yielded;    // true if the step was plastic
};

template <class M>
concept PrincipalReturnModel = requires(const M& m, const double* e, double x) {
  { m.return_map(e, x, x) } -> std::same_as<PrincipalReturn>;
};

struct FiniteStrainResult {
  double tau[6];       // Kirchhoff stress, xx yy zz xy yz xz (Cauchy = tau / det F)
  double energy;       // stored elastic (Hencky) energy per reference volume
  double dissipation;  // plastic work increment per reference volume, tau : (e_trial - e_el)
  bool yielded;        // the step was plastic
};

// Hencky elasticity through the same interface: no yield; gives the same tau as hencky_stress.
struct ElasticModel {
  double lambda = 0.0;
  double G = 0.0;
  PrincipalReturn return_map(const double e_trial[3], double kappa_n, double /*dt*/) const {
    PrincipalReturn r;
    const double tr = e_trial[0] + e_trial[1] + e_trial[2];
    for (int i = 0; i < 3; ++i) {
      r.tau[i] = lambda * tr + 2.0 * G * e_trial[i];
      r.e_el[i] = e_trial[i];
    }
    r.kappa = kappa_n;
    r.yielded = false;
    return r;
  }
};

namespace detail {

// b = F S F^T for symmetric S (6 components).
inline void push_forward_sym(const double F[3][3], const double S[6], double b[6]) {
  const double s[3][3] = {{S[0], S[3], S[5]}, {S[3], S[1], S[4]}, {S[5], S[4], S[2]}};
  double FS[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      FS[i][j] = F[i][0] * s[0][j] + F[i][1] * s[1][j] + F[i][2] * s[2][j];
  b[0] = FS[0][0] * F[0][0] + FS[0][1] * F[0][1] + FS[0][2] * F[0][2];
  b[1] = FS[1][0] * F[1][0] + FS[1][1] * F[1][1] + FS[1][2] * F[1][2];
  b[2] = FS[2][0] * F[2][0] + FS[2][1] * F[2][1] + FS[2][2] * F[2][2];
  b[3] = FS[0][0] * F[1][0] + FS[0][1] * F[1][1] + FS[0][2] * F[1][2];
  b[4] = FS[1][0] * F[2][0] + FS[1][1] * F[2][1] + FS[1][2] * F[2][2];
  b[5] = FS[0][0] * F[2][0] + FS[0][1] * F[2][1] + FS[0][2] * F[2][2];
}

// Inverse of a 3x3 (caller guarantees det F > 0).
inline void inverse3(const double F[3][3], double Fi[3][3]) {
  const double c00 = F[1][1] * F[2][2] - F[1][2] * F[2][1];
  const double c01 = F[1][2] * F[2][0] - F[1][0] * F[2][2];
  const double c02 = F[1][0] * F[2][1] - F[1][1] * F[2][0];
  const double inv = 1.0 / (F[0][0] * c00 + F[0][1] * c01 + F[0][2] * c02);
  Fi[0][0] = c00 * inv;
  Fi[1][0] = c01 * inv;
  Fi[2][0] = c02 * inv;
  Fi[0][1] = (F[0][2] * F[2][1] - F[0][1] * F[2][2]) * inv;
  Fi[1][1] = (F[0][0] * F[2][2] - F[0][2] * F[2][0]) * inv;
  Fi[2][1] = (F[0][1] * F[2][0] - F[0][0] * F[2][1]) * inv;
  Fi[0][2] = (F[0][1] * F[1][2] - F[0][2] * F[1][1]) * inv;
  Fi[1][2] = (F[0][2] * F[1][0] - F[0][0] * F[1][2]) * inv;
  Fi[2][2] = (F[0][0] * F[1][1] - F[0][1] * F[1][0]) * inv;
}

}  // namespace detail

// One Gauss-point update. F: the new deformation gradient (or F-bar), det F > 0 (the caller
// checks). s: the history, updated in place. dt: the step (rate-dependent models only).
template <class Model>
requires PrincipalReturnModel<Model>
inline FiniteStrainResult finite_strain_update(const double F[3][3], GaussPointState& s,
                                               const Model& model, double dt) {
  double b[6];
  detail::push_forward_sym(F, s.Cp_inv, b);
  if constexpr (std::same_as<Model, ElasticModel>) {
    // Hencky elasticity is linear in the strain tensor itself: with the strain from the series
    // (materials/log_strain_series.hpp) no principal frame is needed.
    double e[6];
    if (log_strain_by_series(b, e)) {
      const double tr = e[0] + e[1] + e[2];
      FiniteStrainResult r;
      double ee = 0.0;
      for (int i = 0; i < 6; ++i) {
        r.tau[i] = 2.0 * model.G * e[i];
        ee += (i < 3 ? 1.0 : 2.0) * e[i] * e[i];
      }
      for (int i = 0; i < 3; ++i) r.tau[i] += model.lambda * tr;
      r.energy = 0.5 * model.lambda * tr * tr + model.G * ee;
      r.dissipation = 0.0;
      r.yielded = false;
      return r;
    }
  }
  const SymEig3 eig = symmetric_eigen3(b);
  double e_trial[3];
  for (int i = 0; i < 3; ++i) e_trial[i] = 0.5 * std::log(eig.value[i]);

  const PrincipalReturn ret = model.return_map(e_trial, s.kappa, dt);

  FiniteStrainResult r;
  assemble_from_principal(ret.tau, eig.vector, r.tau);
  r.energy = 0.5 * (ret.tau[0] * ret.e_el[0] + ret.tau[1] * ret.e_el[1] + ret.tau[2] * ret.e_el[2]);
  r.yielded = ret.yielded;
  r.dissipation = 0.0;
  if (ret.yielded) {
    double dep2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double dep = e_trial[i] - ret.e_el[i];
      r.dissipation += ret.tau[i] * dep;
      dep2 += dep * dep;
    }
    const double be_p[3] = {std::exp(2.0 * ret.e_el[0]), std::exp(2.0 * ret.e_el[1]),
                            std::exp(2.0 * ret.e_el[2])};
    double be[6];
    assemble_from_principal(be_p, eig.vector, be);
    double Fi[3][3];
    detail::inverse3(F, Fi);
    detail::push_forward_sym(Fi, be, s.Cp_inv);
    s.eps_p += std::sqrt(2.0 / 3.0 * dep2);
    s.kappa = ret.kappa;
  }
  return r;
}

}  // namespace femdem
