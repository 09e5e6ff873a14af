// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Internal forces of one TET10 element at finite strain (total Lagrangian form):
//   F_g = sum_a x_a (x) dN_a/dX,   f_a = sum_g w_g P_g dN_a/dX
// with the Kirchhoff stress tau from the material's finite-strain update (materials/), and
// optionally F-bar against volumetric locking. Writes Cauchy stress per Gauss point. No
// allocation; called once per element per step from the parallel element loop.
//
// F-bar (de Souza Neto et al. 1996; the thesis names it without a formula): the material sees
// F_bar_g = (J0 / J_g)^(1/3) F_g, with J0 the element's volume ratio, either
//   VolumeAverage: J0 = v / V = sum_g w_g J_g / sum_g w_g (mean dilatation), or
//   Centroid:      J0 = det F at the element centre (the mean of the F_g, exact for straight
//                  edges since the 4-point rule is symmetric about the centroid).
// The force is the exact derivative of sum_g w_g W(F_bar_g): differentiating F_bar gives
//   delta W_g = dev(tau_g) F_g^-T : delta F_g + (tr tau_g / 3) delta J0 / J0,
// so the deviatoric stress acts through each point's own F and the mean pressure through J0.
// This keeps the energy balance exact (unlike the common sigma(F_bar) : grad N form), which the
// energy tests rely on.
#include <cmath>

#include "elements/fbar_mode.hpp"
#include "elements/tet10_shape.hpp"
#include "materials/finite_strain_update.hpp"

namespace femdem {

struct ElementResult {
  double energy = 0.0;       // stored elastic energy of the element
  double dissipation = 0.0;  // plastic work increment of this step
  double min_J = 0.0;        // smallest det F over the Gauss points
  double max_eps_p = 0.0;    // largest equivalent plastic strain over the Gauss points
  // smallest altitude of the corner tetrahedron at the current positions (the stable step's
  // length, corner_tet_min_altitude); set by the element pass, not by tet10_internal_forces
  double min_altitude = 0.0;
};

namespace detail {

inline double det3(const double A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

// cof = det(A) A^-T
inline void cofactor3(const double F[3][3], double cof[3][3]) {
  cof[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
  cof[0][1] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
  cof[0][2] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
  cof[1][0] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
  cof[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
  cof[1][2] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
  cof[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
  cof[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
  cof[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
}

// G = sum_a u_a (x) dN_a/dX over the 10 nodes: F from positions, its rate from velocities.
inline void nodal_gradient(const double* u, const double* d, double G[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) G[i][j] = 0.0;
  for (int a = 0; a < 10; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) G[i][j] += u[3 * a + i] * d[3 * a + j];
}

// f_a += scale * (S cof) dN_a, S symmetric (6), for the 10 nodes
inline void add_force(const double S6[6], const double cof[3][3], double scale, const double* d,
                      double* fe) {
  const double S[3][3] = {{S6[0], S6[3], S6[5]}, {S6[3], S6[1], S6[4]}, {S6[5], S6[4], S6[2]}};
  double P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      P[i][j] = scale * (S[i][0] * cof[0][j] + S[i][1] * cof[1][j] + S[i][2] * cof[2][j]);
  for (int a = 0; a < 10; ++a)
    for (int i = 0; i < 3; ++i)
      fe[3 * a + i] += P[i][0] * d[3 * a] + P[i][1] * d[3 * a + 1] + P[i][2] * d[3 * a + 2];
}

}  // namespace detail

// xe: 30 current coordinates (node-major); dNdX: 4 x 10 x 3; w: 4 Gauss weights x det J0;
// state: 4 Gauss-point states (updated); dt: this step (rate-dependent models).
// fe: 30 internal forces out; sigma: 4 x 6 Cauchy stress out.
// Nodal mode only: corner_J (in) the 4 corner nodes' averaged volume ratios; pressure_weight
// (out) sum_g w_g p_g L_c(g) / J0_g per corner c: the element's share of dW/dJbar_c, which the
// caller gathers per node and turns into forces (see Simulation::compute_forces).
// Xe (optional): the 30 reference coordinates; F is then I + sum_a u_a (x) dN_a/dX with the
// displacements u = x - X, whose rounding error is relative to the displacement rather than to
// the position (a body far from the origin, or a small strain, keeps its digits).
template <class Material>
inline ElementResult tet10_internal_forces(
    const double* xe, const double* dNdX, const double* w, const Material& material, FbarMode fbar,
    GaussPointState* state, double dt, double* fe, double* sigma, const double* corner_J = nullptr,
    double* pressure_weight = nullptr, double subtet_volume0 = 0.0, const double* Xe = nullptr) {
  ElementResult res;
  res.min_J = HUGE_VAL;
  for (int i = 0; i < 30; ++i) fe[i] = 0.0;
  double F[4][3][3];
  double J[4];
  double ue[30];
  if (Xe)
    for (int i = 0; i < 30; ++i) ue[i] = xe[i] - Xe[i];
  for (int g = 0; g < 4; ++g) {
    if (Xe) {
      detail::nodal_gradient(ue, dNdX + g * 30, F[g]);
      for (int i = 0; i < 3; ++i) F[g][i][i] += 1.0;
    } else {
      detail::nodal_gradient(xe, dNdX + g * 30, F[g]);
    }
    J[g] = detail::det3(F[g]);
    res.min_J = std::fmin(res.min_J, J[g]);
  }
  if (!(res.min_J > 0.0)) return res;  // the caller stops the run

  const double vol0 = w[0] + w[1] + w[2] + w[3];
  double J0 = 0.0;
  double Fc[3][3] = {};
  if (fbar == FbarMode::VolumeAverage) {
    for (int g = 0; g < 4; ++g) J0 += w[g] * J[g];
    J0 /= vol0;
  } else if (fbar == FbarMode::SubTet) {
    J0 = tet10::subtet_volume(xe) / subtet_volume0;
    if (!(J0 > 0.0)) {
      res.min_J = std::fmin(res.min_J, J0);
      return res;
    }
  } else if (fbar == FbarMode::Centroid) {
    for (int g = 0; g < 4; ++g)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Fc[i][j] += 0.25 * F[g][i][j];
    J0 = detail::det3(Fc);
    if (!(J0 > 0.0)) {
      res.min_J = std::fmin(res.min_J, J0);
      return res;
    }
  }

  double J0g[4] = {J0, J0, J0, J0};
  if (fbar == FbarMode::Nodal && corner_J && pressure_weight) {
    for (int g = 0; g < 4; ++g) {
      J0g[g] = 0.0;
      for (int c = 0; c < 4; ++c)
        J0g[g] += (c == g ? tet10::kGaussA : tet10::kGaussB) * corner_J[c];
    }
    for (int c = 0; c < 4; ++c) pressure_weight[c] = 0.0;
  }

  double pressure_work = 0.0;  // sum_g w_g tr(tau_g) / 3
  for (int g = 0; g < 4; ++g) {
    double Fm[3][3];
    double scale = 1.0;
    if (fbar != FbarMode::Off) scale = std::cbrt(J0g[g] / J[g]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Fm[i][j] = scale * F[g][i][j];
    const FiniteStrainResult r = finite_strain_update(Fm, state[g], material, dt);
    res.energy += w[g] * r.energy;
    res.dissipation += w[g] * r.dissipation;
    res.max_eps_p = std::fmax(res.max_eps_p, state[g].eps_p);
    const double Jm = (fbar != FbarMode::Off) ? J0g[g] : J[g];
    for (int k = 0; k < 6; ++k) sigma[6 * g + k] = r.tau[k] / Jm;
    double cof[3][3];
    detail::cofactor3(F[g], cof);
    if (fbar == FbarMode::Off) {
      detail::add_force(r.tau, cof, w[g] / J[g], dNdX + g * 30, fe);  // P = tau F^-T
    } else {
      const double p = (r.tau[0] + r.tau[1] + r.tau[2]) / 3.0;
      const double dev[6] = {r.tau[0] - p, r.tau[1] - p, r.tau[2] - p,
                             r.tau[3],     r.tau[4],     r.tau[5]};
      detail::add_force(dev, cof, w[g] / J[g], dNdX + g * 30, fe);
      pressure_work += w[g] * p;
      if (fbar == FbarMode::Nodal && pressure_weight)
        for (int c = 0; c < 4; ++c)
          pressure_weight[c] += w[g] * p * (c == g ? tet10::kGaussA : tet10::kGaussB) / J0g[g];
    }
  }
  if (fbar == FbarMode::VolumeAverage) {
    // (sum_g w_g p_g) dJ0/J0 with J0 = sum_h w_h J_h / V: a pressure acting through each J_h
    const double identity[6] = {1, 1, 1, 0, 0, 0};
    for (int h = 0; h < 4; ++h) {
      double cof[3][3];
      detail::cofactor3(F[h], cof);
      detail::add_force(identity, cof, pressure_work * w[h] / (vol0 * J0), dNdX + h * 30, fe);
    }
  } else if (fbar == FbarMode::SubTet) {
    // dJ0 = d(sum_s V_s) / V0: each sub-tet's volume gradient on its 4 nodes
    tet10::add_subtet_volume_gradient(xe, pressure_work / (J0 * subtet_volume0 * 6.0), fe);
  } else if (fbar == FbarMode::Centroid) {
    // J0 = det(Fc), Fc = sum_h F_h / 4: dJ0/J0 = Fc^-T : sum_h dF_h / 4
    double cof[3][3];
    detail::cofactor3(Fc, cof);
    const double identity[6] = {1, 1, 1, 0, 0, 0};
    for (int h = 0; h < 4; ++h)
      detail::add_force(identity, cof, 0.25 * pressure_work / J0, dNdX + h * 30, fe);
  }
  return res;
}

// f_a += s sum_h w_h J_h F_h^-T dN_a/dX|_h = s d(element volume)/dx_a: the nodal F-bar's
// pressure forces, s = sum over the element's corners of Q_c / V_c.
inline void tet10_add_volume_gradient(const double* xe, const double* dNdX, const double* w,
                                      double s, double* fe) {
  const double identity[6] = {1, 1, 1, 0, 0, 0};
  for (int g = 0; g < 4; ++g) {
    const double* d = dNdX + g * 30;
    double F[3][3];
    detail::nodal_gradient(xe, d, F);
    double cof[3][3];
    detail::cofactor3(F, cof);
    detail::add_force(identity, cof, s * w[g], d, fe);
  }
}

// Artificial bulk viscosity (von Neumann-Richtmyer, in the form of the explicit codes): under
// volumetric compression at rate D = tr(d) < 0 each Gauss point carries an extra pressure
//   q = rho l (q_quadratic l D^2 - q_linear c D),
// which spreads a shock over a few elements instead of letting it ring (the light corner nodes of
// TET10 ring most). Adds the forces to fe and returns the dissipated power (>= 0); c_eff gets
// Q + sqrt(Q^2 + c^2) with Q = q_linear c + q_quadratic l |D|, the sound speed the stable step
// must use.
inline double tet10_bulk_viscosity(const double* xe, const double* ve, const double* dNdX,
                                   const double* w, double rho0, double c, double l,
                                   double q_linear, double q_quadratic, double* fe, double& c_eff) {
  double power = 0.0;
  c_eff = c;
  for (int g = 0; g < 4; ++g) {
    const double* d = dNdX + g * 30;
    double F[3][3], Fdot[3][3];
    detail::nodal_gradient(xe, d, F);
    detail::nodal_gradient(ve, d, Fdot);
    double cof[3][3];
    detail::cofactor3(F, cof);
    const double J = detail::det3(F);
    double trd = 0.0;  // tr(Fdot F^-1) = Fdot : cof / J
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) trd += Fdot[i][j] * cof[i][j];
    trd /= J;
    if (trd >= 0.0) continue;
    const double q = (rho0 / J) * l * (q_quadratic * l * trd * trd - q_linear * c * trd);
    const double identity[6] = {1, 1, 1, 0, 0, 0};
    detail::add_force(identity, cof, -w[g] * q, d, fe);  // P = -q J F^-T = -q cof
    power += -w[g] * J * q * trd;
    const double Q = q_linear * c + q_quadratic * l * std::fabs(trd);
    c_eff = std::fmax(c_eff, Q + std::sqrt(Q * Q + c * c));
  }
  return power;
}

// Current volume of the element: sum_g w_g det F_g.
inline double tet10_current_volume(const double* xe, const double* dNdX, const double* w) {
  double v = 0.0;
  for (int g = 0; g < 4; ++g) {
    const double* d = dNdX + g * 30;
    double F[3][3];
    detail::nodal_gradient(xe, d, F);
    v += w[g] * detail::det3(F);
  }
  return v;
}

// The elastic element without state or F-bar (kept for tests and benchmarks of the bare kernel).
inline ElementResult tet10_elastic_forces(const double* xe, const double* dNdX, const double* w,
                                          double lambda, double G, double* fe, double* sigma) {
  GaussPointState st[4];
  return tet10_internal_forces(xe, dNdX, w, ElasticModel{lambda, G}, FbarMode::Off, st, 0.0, fe,
                               sigma);
}

// Smallest altitude of the corner tetrahedron (3 V / largest face area): the length that scales
// the element's highest frequency as it deforms.
inline double corner_tet_min_altitude(const double* xe) {
  const double* p0 = xe;
  const double* p1 = xe + 3;
  const double* p2 = xe + 6;
  const double* p3 = xe + 9;
  auto sub = [](const double* a, const double* b, double* o) {
    for (int i = 0; i < 3; ++i) o[i] = a[i] - b[i];
  };
  auto cross_norm = [](const double* a, const double* b) {
    const double c0 = a[1] * b[2] - a[2] * b[1], c1 = a[2] * b[0] - a[0] * b[2],
                 c2 = a[0] * b[1] - a[1] * b[0];
    return std::sqrt(c0 * c0 + c1 * c1 + c2 * c2);
  };
  double e01[3], e02[3], e03[3], e12[3], e13[3];
  sub(p1, p0, e01);
  sub(p2, p0, e02);
  sub(p3, p0, e03);
  sub(p2, p1, e12);
  sub(p3, p1, e13);
  const double vol6 = e01[0] * (e02[1] * e03[2] - e02[2] * e03[1]) -
                      e01[1] * (e02[0] * e03[2] - e02[2] * e03[0]) +
                      e01[2] * (e02[0] * e03[1] - e02[1] * e03[0]);
  const double a2max = std::fmax(std::fmax(cross_norm(e01, e02), cross_norm(e01, e03)),
                                 std::fmax(cross_norm(e02, e03), cross_norm(e12, e13)));
  return vol6 / a2max;  // (6V)/(2A) = 3V/A
}

}  // namespace femdem
