// SPDX-License-Identifier: GPL-3.0-or-later
#include "elements/tet10_frequency.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "elements/tet10_shape.hpp"

namespace femdem {

double tet10_max_frequency(const double* dNdX, const double* w, double element_mass, double lambda,
                           double G) {
  Eigen::Matrix<double, 30, 30> K = Eigen::Matrix<double, 30, 30>::Zero();
  for (int g = 0; g < tet10::kGauss; ++g) {
    const double* d = dNdX + 30 * g;
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b) {
        const double dot =
            d[3 * a] * d[3 * b] + d[3 * a + 1] * d[3 * b + 1] + d[3 * a + 2] * d[3 * b + 2];
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) {
            double v = lambda * d[3 * a + i] * d[3 * b + k] + G * d[3 * a + k] * d[3 * b + i];
            if (i == k) v += G * dot;
            K(3 * a + i, 3 * b + k) += w[g] * v;
          }
      }
  }
  // Symmetric scaling M^-1/2 K M^-1/2 keeps the problem symmetric.
  Eigen::Matrix<double, 30, 1> s;
  for (int a = 0; a < 10; ++a) {
    const double m = element_mass * (a < 4 ? tet10::kHrzCorner : tet10::kHrzMidEdge);
    for (int i = 0; i < 3; ++i) s(3 * a + i) = 1.0 / std::sqrt(m);
  }
  const Eigen::Matrix<double, 30, 30> A = s.asDiagonal() * K * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 30, 30>> eig(A, Eigen::EigenvaluesOnly);
  return std::sqrt(std::fmax(eig.eigenvalues().maxCoeff(), 0.0));
}

}  // namespace femdem
