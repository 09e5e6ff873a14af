// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the finite-strain update of
// materials/finite_strain_update.hpp for eight Gauss points at once, branch-free (elastic and
// plastic points in one pack cost the same):
//   b_trial = F Cp^-1 F^T, its principal log strains, the model's return in lanes
//   (return_map_lanes, one overload per model in materials/lanes/), tau from the principal
//   stresses, and where a lane yielded: b_e = sum exp(2 e_el,i) n_i n_i^T and
//   Cp^-1 = F^-1 b_e F^-T.
// F^-1 comes in from the caller as F^-T (the element kernel has cof(F) / det F for its forces
// anyway): no inverse is formed here. Elastic materials keep no state (Cp^-1 stays I).
#if defined(FEMDEM_FINITE_STRAIN_UPDATE_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_FINITE_STRAIN_UPDATE_LANES_INL_H_
#undef FEMDEM_FINITE_STRAIN_UPDATE_LANES_INL_H_
#else
#define FEMDEM_FINITE_STRAIN_UPDATE_LANES_INL_H_
#endif

#include <type_traits>

#include "materials/finite_strain_update.hpp"
#include "materials/lanes/lanes8-inl.h"
#include "materials/lanes/symmetric_eigen3-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

// What a model's return in lanes gives back (materials/finite_strain_update.hpp's
// PrincipalReturn, lane by lane).
struct PrincipalReturnLanes {
  Lanes8 tau[3];
  Lanes8 e_el[3];
  Lanes8 kappa;
  Mask8 yielded;
};

// Gauss-point history in lanes (GaussPointState component by component).
struct GaussPointLanes {
  Lanes8 Cp_inv[6];
  Lanes8 eps_p;
  Lanes8 kappa;
};

struct FiniteStrainLanes {
  Lanes8 tau[6];       // Kirchhoff stress, xx yy zz xy yz xz
  Lanes8 energy;       // stored elastic energy per reference volume
  Lanes8 dissipation;  // plastic work increment per reference volume
};

// tau = sum_i t_i n_i n_i^T (6 components).
HWY_INLINE void assemble_from_principal(const Lanes8 t[3], const Lanes8 n[3][3], Lanes8 out[6]) {
  constexpr int kRow[6] = {0, 1, 2, 0, 1, 0}, kCol[6] = {0, 1, 2, 1, 2, 2};
  for (int c = 0; c < 6; ++c) {
    const int i = kRow[c], j = kCol[c];
    out[c] = t[0] * n[i][0] * n[j][0] + t[1] * n[i][1] * n[j][1] + t[2] * n[i][2] * n[j][2];
  }
}

// b = F S F^T for symmetric S.
HWY_INLINE void push_forward_sym(const Lanes8 F[3][3], const Lanes8 S[6], Lanes8 b[6]) {
  const Lanes8 s[3][3] = {{S[0], S[3], S[5]}, {S[3], S[1], S[4]}, {S[5], S[4], S[2]}};
  Lanes8 FS[3][3];
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

// b = F F^T.
HWY_INLINE void left_cauchy_green(const Lanes8 F[3][3], Lanes8 b[6]) {
  constexpr int kRow[6] = {0, 1, 2, 0, 1, 0}, kCol[6] = {0, 1, 2, 1, 2, 2};
  for (int c = 0; c < 6; ++c)
    b[c] = F[kRow[c]][0] * F[kCol[c]][0] + F[kRow[c]][1] * F[kCol[c]][1] +
           F[kRow[c]][2] * F[kCol[c]][2];
}

// One update of eight Gauss points. F: the deformation gradient the material sees (F-bar
// included), F_inv_T its inverse transposed. s: the history, updated (not read for elastic
// models). dt: the step (rate-dependent models).
template <class Model>
HWY_INLINE FiniteStrainLanes finite_strain_update(const Lanes8 F[3][3], const Lanes8 F_inv_T[3][3],
                                                  GaussPointLanes& s, const Model& model,
                                                  double dt) {
  constexpr bool kElastic = std::is_same_v<Model, ElasticModel>;
  Lanes8 b[6];
  if constexpr (kElastic)
    left_cauchy_green(F, b);
  else
    push_forward_sym(F, s.Cp_inv, b);
  const SymEig3Lanes eig = symmetric_eigen3(b);
  Lanes8 e_trial[3];
  for (int i = 0; i < 3; ++i) e_trial[i] = Lanes8(0.5) * log(eig.value[i]);

  const PrincipalReturnLanes ret =
      return_map_lanes(model, e_trial, kElastic ? Lanes8(0.0) : s.kappa, dt);

  FiniteStrainLanes r;
  assemble_from_principal(ret.tau, eig.vector, r.tau);
  r.energy = Lanes8(0.5) *
             (ret.tau[0] * ret.e_el[0] + ret.tau[1] * ret.e_el[1] + ret.tau[2] * ret.e_el[2]);
  r.dissipation = Lanes8(0.0);
  if constexpr (!kElastic) {
    if (any(ret.yielded)) {
      Lanes8 dep[3];
      for (int i = 0; i < 3; ++i) dep[i] = e_trial[i] - ret.e_el[i];
      const Lanes8 work = ret.tau[0] * dep[0] + ret.tau[1] * dep[1] + ret.tau[2] * dep[2];
      const Lanes8 dep2 = dep[0] * dep[0] + dep[1] * dep[1] + dep[2] * dep[2];
      const Lanes8 be_p[3] = {exp(Lanes8(2.0) * ret.e_el[0]), exp(Lanes8(2.0) * ret.e_el[1]),
                              exp(Lanes8(2.0) * ret.e_el[2])};
      Lanes8 be[6];
      assemble_from_principal(be_p, eig.vector, be);
      // Cp^-1 = F^-1 b_e F^-T, with F^-1 = (F^-T)^T
      Lanes8 F_inv[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F_inv[i][j] = F_inv_T[j][i];
      Lanes8 Cp[6];
      push_forward_sym(F_inv, be, Cp);
      const Mask8 y = ret.yielded;
      r.dissipation = select(y, work, Lanes8(0.0));
      for (int c = 0; c < 6; ++c) s.Cp_inv[c] = select(y, Cp[c], s.Cp_inv[c]);
      s.eps_p = select(y, s.eps_p + sqrt(Lanes8(2.0 / 3.0) * dep2), s.eps_p);
      s.kappa = select(y, ret.kappa, s.kappa);
    }
  }
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_FINITE_STRAIN_UPDATE_LANES_INL_H_
