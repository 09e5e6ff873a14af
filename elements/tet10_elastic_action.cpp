// SPDX-License-Identifier: GPL-3.0-or-later
#include "elements/tet10_elastic_action.hpp"

#include "elements/tet10_shape.hpp"

namespace femdem {

bool tet10_elastic_action(const double* x, const double* dNdX, const double* w, double lambda,
                          double G, const double* u, double* f) {
  for (int i = 0; i < 30; ++i) f[i] = 0.0;
  for (int g = 0; g < tet10::kGauss; ++g) {
    const double* d = dNdX + 30 * g;
    // F = sum_a x_a (x) dN_a/dX and H = sum_a u_a (x) dN_a/dX (the displacement gradient over X)
    double F[9] = {}, H[9] = {};
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          F[3 * i + j] += x[3 * a + i] * d[3 * a + j];
          H[3 * i + j] += u[3 * a + i] * d[3 * a + j];
        }
    const double c00 = F[4] * F[8] - F[5] * F[7], c01 = F[5] * F[6] - F[3] * F[8],
                 c02 = F[3] * F[7] - F[4] * F[6];
    const double J = F[0] * c00 + F[1] * c01 + F[2] * c02;
    if (!(J > 0.0)) {
      for (int i = 0; i < 30; ++i) f[i] = 0.0;
      return false;
    }
    // F^-1 (row-major) = cofactor' / J
    const double Fi[9] = {
        c00 / J, (F[2] * F[7] - F[1] * F[8]) / J, (F[1] * F[5] - F[2] * F[4]) / J,
        c01 / J, (F[0] * F[8] - F[2] * F[6]) / J, (F[2] * F[3] - F[0] * F[5]) / J,
        c02 / J, (F[1] * F[6] - F[0] * F[7]) / J, (F[0] * F[4] - F[1] * F[3]) / J};
    // the gradient over the current shape, L = H F^-1, its strain and stress
    double L[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        L[3 * i + j] = H[3 * i] * Fi[j] + H[3 * i + 1] * Fi[3 + j] + H[3 * i + 2] * Fi[6 + j];
    const double tr = L[0] + L[4] + L[8];
    double s[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s[3 * i + j] = G * (L[3 * i + j] + L[3 * j + i]);
    s[0] += lambda * tr, s[4] += lambda * tr, s[8] += lambda * tr;
    // f_a = (w J sigma F^-T) dN_a/dX: the current-gradient form without forming dN/dx
    const double dv = w[g] * J;
    double P[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[3 * i + j] = dv * (s[3 * i] * Fi[3 * j] + s[3 * i + 1] * Fi[3 * j + 1] +
                             s[3 * i + 2] * Fi[3 * j + 2]);
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        f[3 * a + i] +=
            P[3 * i] * d[3 * a] + P[3 * i + 1] * d[3 * a + 1] + P[3 * i + 2] * d[3 * a + 2];
  }
  return true;
}

}  // namespace femdem
