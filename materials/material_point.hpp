// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Material-point driver: applies a homogeneous deformation history to one Gauss point of a
// material and returns the stress path. Used by the tests (thesis ch. 3 homogeneous tests) and by
// `femdem check --material`. Two kinds of control:
//  (a) deformation-gradient control: a list of F (each optionally split into sub-increments by
//      linear interpolation in F from the previous one);
//  (b) mixed control for the thesis' cylinder tests: the axial (z) log strain e_a and a shear
//      gamma are prescribed, the lateral stretches are unknowns,
//        F = [[l_x, 0, gamma], [0, l_y, 0], [0, 0, exp(e_a)]],
//      and either the lateral stresses sigma_xx = sigma_yy = 0 (uniaxial stress; Newton on
//      ln l_x, ln l_y, each increment) or l_x = l_y = 1 (uniaxial strain). gamma = F_xz shifts the
//      top of a base-fixed cylinder sideways (u_x = gamma Z): the thesis' mixed compression +
//      shear test. Prescribing log strains (stretch = exp(e)) makes the finite-strain update
//      reproduce small-strain numbers: with the Hencky law the Kirchhoff stress is the
//      small-strain stress function of the log strain while the principal axes stay fixed.
// Tension positive (the thesis' ch. 3 uses compression positive).
#include <cmath>
#include <stdexcept>
#include <vector>

#include "materials/finite_strain_update.hpp"
#include "materials/material_params.hpp"

namespace femdem {

struct MaterialPointStep {
  double F[3][3];
  double sigma[6];        // Cauchy stress, xx yy zz xy yz xz
  double tau[6];          // Kirchhoff stress
  double eps_p;           // equivalent plastic strain
  double elastic_energy;  // stored elastic energy per reference volume
  double dissipation;     // cumulative plastic work per reference volume
  bool yielded;           // this increment was plastic
  int segment;            // index of the target this increment moves towards
  GaussPointState state;  // history after the increment (Cp^-1, eps_p)
};

struct F3 {
  double m[3][3];
};

// One mixed-control target: reached from the previous target (or from rest) in `increments`
// equal increments of e_a and gamma.
struct MixedTarget {
  double axial_log_strain = 0.0;  // e_a = ln(l_z)
  double shear = 0.0;             // gamma = F_xz
  int increments = 100;
};

enum class LateralControl { ZeroStress, ZeroStrain };

// Thrown when a lateral Newton solve does not converge or a model cannot be built.
struct MaterialPointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace detail {

template <class Model>
MaterialPointStep material_point_increment(const double F[3][3], GaussPointState& s,
                                           const Model& model, double dt, double& dissipation) {
  MaterialPointStep st;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) st.F[i][j] = F[i][j];
  const FiniteStrainResult r = finite_strain_update(F, s, model, dt);
  const double J = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) -
                   F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                   F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
  dissipation += r.dissipation;
  for (int k = 0; k < 6; ++k) {
    st.tau[k] = r.tau[k];
    st.sigma[k] = r.tau[k] / J;
  }
  st.eps_p = s.eps_p;
  st.elastic_energy = r.energy;
  st.dissipation = dissipation;
  st.yielded = r.yielded;
  st.segment = 0;
  st.state = s;
  return st;
}

}  // namespace detail

// (a) Deformation-gradient control. Each F in `path` is reached from the previous one (the
// first from the identity) in `substeps` increments linear in F; every increment is returned.
// dt: time per increment (rate-dependent models only; 0 = quasi-static).
template <PrincipalReturnModel Model>
std::vector<MaterialPointStep> drive_deformation(const Model& model, const std::vector<F3>& path,
                                                 int substeps = 1, double dt = 0.0) {
  if (substeps < 1) throw MaterialPointError("substeps must be >= 1");
  std::vector<MaterialPointStep> out;
  out.reserve(path.size() * static_cast<std::size_t>(substeps));
  GaussPointState s;
  double dissipation = 0.0;
  F3 prev = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (std::size_t seg = 0; seg < path.size(); ++seg) {
    for (int k = 1; k <= substeps; ++k) {
      const double t = static_cast<double>(k) / substeps;
      double F[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          F[i][j] = (k == substeps) ? path[seg].m[i][j]
                                    : prev.m[i][j] + t * (path[seg].m[i][j] - prev.m[i][j]);
      MaterialPointStep st = detail::material_point_increment(F, s, model, dt, dissipation);
      st.segment = static_cast<int>(seg);
      out.push_back(st);
    }
    prev = path[seg];
  }
  return out;
}

// (b) Mixed control (see the top of the file). Every increment is returned.
template <PrincipalReturnModel Model>
std::vector<MaterialPointStep> drive_mixed(const Model& model, const std::vector<MixedTarget>& path,
                                           LateralControl lateral, double dt = 0.0) {
  std::vector<MaterialPointStep> out;
  GaussPointState s;
  double dissipation = 0.0;
  double ea = 0.0, gamma = 0.0;
  double a[2] = {0.0, 0.0};  // ln l_x, ln l_y: the unknowns under ZeroStress
  for (std::size_t seg = 0; seg < path.size(); ++seg) {
    const MixedTarget& tg = path[seg];
    if (tg.increments < 1) throw MaterialPointError("increments must be >= 1");
    const double ea0 = ea, g0 = gamma;
    for (int k = 1; k <= tg.increments; ++k) {
      const double t = static_cast<double>(k) / tg.increments;
      ea = (k == tg.increments) ? tg.axial_log_strain : ea0 + t * (tg.axial_log_strain - ea0);
      gamma = (k == tg.increments) ? tg.shear : g0 + t * (tg.shear - g0);
      auto make_F = [&](const double ax, const double ay, double F[3][3]) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) F[i][j] = 0.0;
        F[0][0] = std::exp(ax);
        F[1][1] = std::exp(ay);
        F[2][2] = std::exp(ea);
        F[0][2] = gamma;
      };
      double F[3][3];
      if (lateral == LateralControl::ZeroStress) {
        // Newton on (ln l_x, ln l_y) for tau_xx = tau_yy = 0, each trial from the state at the
        // start of the increment; central-difference Jacobian.
        auto residual = [&](const double x[2], double r[2]) {
          double Ft[3][3];
          make_F(x[0], x[1], Ft);
          GaussPointState st = s;
          const FiniteStrainResult res = finite_strain_update(Ft, st, model, dt);
          r[0] = res.tau[0];
          r[1] = res.tau[1];
          return std::fmax(std::fabs(res.tau[2]), std::fabs(res.tau[5]));
        };
        bool ok = false;
        for (int it = 0; it < 60; ++it) {
          double r[2];
          const double scale = residual(a, r);
          constexpr double h = 1e-7;
          double Jm[2][2];
          for (int c = 0; c < 2; ++c) {
            double xp[2] = {a[0], a[1]}, xm[2] = {a[0], a[1]}, rp[2], rm[2];
            xp[c] += h;
            xm[c] -= h;
            residual(xp, rp);
            residual(xm, rm);
            Jm[0][c] = (rp[0] - rm[0]) / (2.0 * h);
            Jm[1][c] = (rp[1] - rm[1]) / (2.0 * h);
          }
          // Converged when the lateral stresses are round-off: relative to the stress, or to a
          // modulus times machine precision (the floor of the log of a stretch near 1).
          const double noise = 1e-14 * (std::fabs(Jm[0][0]) + std::fabs(Jm[1][1]));
          if (std::fabs(r[0]) + std::fabs(r[1]) <= 1e-12 * scale + noise) {
            ok = true;
            break;
          }
          // Levenberg-Marquardt step with a tiny damping: Newton where the Jacobian is regular,
          // still a (minimum-norm) step where it is singular (a fully softened material has no
          // deviatoric stiffness, so only the lateral volume change is determined).
          const double A00 = Jm[0][0] * Jm[0][0] + Jm[1][0] * Jm[1][0];
          const double A11 = Jm[0][1] * Jm[0][1] + Jm[1][1] * Jm[1][1];
          const double A01 = Jm[0][0] * Jm[0][1] + Jm[1][0] * Jm[1][1];
          const double mu = 1e-12 * (A00 + A11);
          const double g0 = Jm[0][0] * r[0] + Jm[1][0] * r[1];
          const double g1 = Jm[0][1] * r[0] + Jm[1][1] * r[1];
          const double det = (A00 + mu) * (A11 + mu) - A01 * A01;
          if (!(det > 0.0)) break;
          a[0] -= ((A11 + mu) * g0 - A01 * g1) / det;
          a[1] -= (-A01 * g0 + (A00 + mu) * g1) / det;
        }
        if (!ok) throw MaterialPointError("material point: lateral stress Newton did not converge");
      }
      make_F(a[0], a[1], F);
      MaterialPointStep st = detail::material_point_increment(F, s, model, dt, dissipation);
      st.segment = static_cast<int>(seg);
      out.push_back(st);
    }
  }
  return out;
}

// The same drivers for a material as a scene defines it (any model); throws
// MaterialPointError for a model it does not know or invalid constants.
std::vector<MaterialPointStep> drive_deformation(const MaterialParams& material,
                                                 const std::vector<F3>& path, int substeps = 1,
                                                 double dt = 0.0);
std::vector<MaterialPointStep> drive_mixed(const MaterialParams& material,
                                           const std::vector<MixedTarget>& path,
                                           LateralControl lateral, double dt = 0.0);

}  // namespace femdem
