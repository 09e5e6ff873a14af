// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Internal forces of one TET10 element at finite strain (total Lagrangian form):
//   F = sum_a x_a (x) dN_a/dX,   P = tau F^-T,   f_a = sum_g w_g P dN_a/dX
// with tau the Kirchhoff stress of the material. Writes Cauchy stress sigma = tau / J per Gauss
// point. No allocation; called once per element per step from the parallel element loop.
#include <cmath>

#include "elements/tet10_shape.hpp"
#include "materials/hencky.hpp"

namespace femdem {

struct ElementResult {
  double energy = 0.0;  // stored energy of the element
  double min_J = 0.0;   // smallest det F over the Gauss points
};

// xe: 30 current coordinates (node-major); dNdX: 4 x 10 x 3; w: 4 Gauss weights x det J0.
// fe: 30 internal forces out; sigma: 4 x 6 Cauchy stress out.
inline ElementResult tet10_elastic_forces(const double* xe, const double* dNdX, const double* w,
                                          double lambda, double G, double* fe, double* sigma) {
  ElementResult res;
  res.min_J = HUGE_VAL;
  for (int i = 0; i < 30; ++i) fe[i] = 0.0;
  for (int g = 0; g < tet10::kGauss; ++g) {
    const double* d = dNdX + g * 30;
    double F[3][3] = {};
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F[i][j] += xe[3 * a + i] * d[3 * a + j];
    // cofactor matrix: cof = J F^-T
    double cof[3][3];
    cof[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
    cof[0][1] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
    cof[0][2] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
    cof[1][0] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
    cof[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
    cof[1][2] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
    cof[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    cof[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    cof[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    const double J = F[0][0] * cof[0][0] + F[0][1] * cof[0][1] + F[0][2] * cof[0][2];
    res.min_J = std::fmin(res.min_J, J);
    if (!(J > 0.0)) continue;  // the caller stops the run; avoid log of a negative number
    double b[6];
    b[0] = F[0][0] * F[0][0] + F[0][1] * F[0][1] + F[0][2] * F[0][2];
    b[1] = F[1][0] * F[1][0] + F[1][1] * F[1][1] + F[1][2] * F[1][2];
    b[2] = F[2][0] * F[2][0] + F[2][1] * F[2][1] + F[2][2] * F[2][2];
    b[3] = F[0][0] * F[1][0] + F[0][1] * F[1][1] + F[0][2] * F[1][2];
    b[4] = F[1][0] * F[2][0] + F[1][1] * F[2][1] + F[1][2] * F[2][2];
    b[5] = F[0][0] * F[2][0] + F[0][1] * F[2][1] + F[0][2] * F[2][2];
    const HenckyResult h = hencky_stress(b, lambda, G);
    res.energy += w[g] * h.energy;
    const double invJ = 1.0 / J;
    double* s = sigma + 6 * g;
    for (int k = 0; k < 6; ++k) s[k] = h.tau[k] * invJ;
    // P = tau F^-T = tau cof / J
    const double tau[3][3] = {{h.tau[0], h.tau[3], h.tau[5]},
                              {h.tau[3], h.tau[1], h.tau[4]},
                              {h.tau[5], h.tau[4], h.tau[2]}};
    double P[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[i][j] = (tau[i][0] * cof[0][j] + tau[i][1] * cof[1][j] + tau[i][2] * cof[2][j]) * invJ;
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        fe[3 * a + i] += w[g] * (P[i][0] * d[3 * a] + P[i][1] * d[3 * a + 1] + P[i][2] * d[3 * a + 2]);
  }
  return res;
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
