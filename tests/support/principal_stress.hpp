// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Helpers for the material tests: principal values of a symmetric stress (xx yy zz xy yz xz),
// sorted s1 >= s2 >= s3, its invariants p = tr/3 and q = sqrt(J2), random trial log strains,
// and a deformation gradient with given principal log strains in rotated axes.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace femdem::test {

inline std::array<double, 3> principal_sorted(const double t[6]) {
  Eigen::Matrix3d m;
  m << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues();
  return {ev[2], ev[1], ev[0]};
}

inline double mean_of(const std::array<double, 3>& s) {
  return (s[0] + s[1] + s[2]) / 3.0;
}

// sqrt(J2) of principal values
inline double sqrt_j2(const std::array<double, 3>& s) {
  const double p = mean_of(s);
  return std::sqrt(0.5 *
                   ((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p)));
}

// F = R diag(exp(e)) with a fixed rotation R (the principal axes are not the coordinate axes).
inline void stretch_in_rotated_axes(const double e[3], double F[3][3]) {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  Eigen::Matrix3d U = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) U(i, i) = std::exp(e[i]);
  const Eigen::Matrix3d Fm = R * U * R.transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F[i][j] = Fm(i, j);
}

// Random principal log strains of magnitude up to `scale` (volumetric and deviatoric parts).
struct TrialStrains {
  std::mt19937 rng{12345};
  std::array<double, 3> next(double scale) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    return {scale * u(rng), scale * u(rng), scale * u(rng)};
  }
};

}  // namespace femdem::test
