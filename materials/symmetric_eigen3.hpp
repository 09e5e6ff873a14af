// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations.
//
// Why Jacobi: the closed-form cubic loses accuracy near repeated eigenvalues (the thesis found it
// unstable, and Eigen's computeDirect errs by ~1e-8 in the log strain there), while Jacobi
// rotations stay accurate to round-off for any spectrum, repeated or not, and converge
// quadratically (3-5 sweeps at machine precision). No allocation, no branches on the spectrum.
#include <cmath>

namespace femdem {

// Symmetric 3x3 stored as 6 numbers: xx yy zz xy yz xz.
struct SymEig3 {
  double value[3];      // unsorted
  double vector[3][3];  // vector[k][i]: component k of eigenvector i (columns are eigenvectors)
};

inline SymEig3 symmetric_eigen3(const double s[6]) {
  double a[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  SymEig3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.vector[i][j] = (i == j) ? 1.0 : 0.0;
  constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < 30; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-36 * diag || off == 0.0) break;
    for (const auto& pq : kPairs) {
      const int p = pq[0], q = pq[1];
      const double apq = a[p][q];
      if (apq == 0.0) continue;
      // Rotation angle that zeroes a[p][q]; t = tan(phi) of the smaller root for stability.
      const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
      const double t = std::copysign(1.0, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
      const double c = 1.0 / std::sqrt(t * t + 1.0);
      const double sn = t * c;
      for (int k = 0; k < 3; ++k) {  // a <- a J
        const double akp = a[k][p], akq = a[k][q];
        a[k][p] = c * akp - sn * akq;
        a[k][q] = sn * akp + c * akq;
      }
      for (int k = 0; k < 3; ++k) {  // a <- J^T a
        const double apk = a[p][k], aqk = a[q][k];
        a[p][k] = c * apk - sn * aqk;
        a[q][k] = sn * apk + c * aqk;
      }
      a[p][q] = a[q][p] = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double vkp = r.vector[k][p], vkq = r.vector[k][q];
        r.vector[k][p] = c * vkp - sn * vkq;
        r.vector[k][q] = sn * vkp + c * vkq;
      }
    }
  }
  for (int i = 0; i < 3; ++i) r.value[i] = a[i][i];
  return r;
}

}  // namespace femdem
