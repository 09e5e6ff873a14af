// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Hencky strain e = 0.5 ln(b) of a left Cauchy-Green tensor close to the identity, as a
// tensor series: no eigen-decomposition and no logarithms.
//
// Why: in elastic bodies (armour units, impacting spheres) the strains are small, and the
// eigen-decomposition plus three logarithms were half the cost of an element update (perf,
// docs/PERFORMANCE.md). b = F F^T carries no rotation, so small strain means b close to I
// whatever the body's rotation, and then
//   0.5 ln b = artanh(Y) = Y + Y^3/3 + Y^5/5 + ...,   Y = (b - I)(b + I)^-1,
// with eigenvalues y = (lambda - 1)/(lambda + 1) of Y, |y| about the principal strain. (b - I)
// and (b + I)^-1 commute, so Y and all its powers are symmetric; the odd series in Y converges
// twice as fast as the series of ln(I + X) and needs only odd powers.
//
// Truncated after Y^11/11, the first term left out is y^13/13 against e ~ y: a relative error
// below y^12/13, under 1e-16 when |y| < 0.06 (strains up to about 6 %). The spectral radius of Y
// is bounded by its Frobenius norm, which is what the range check uses. Outside the range the
// caller takes the eigen-decomposition.
//
// Accuracy against the eigen route: for tiny strains this one is the more accurate. ln(lambda)
// of an eigenvalue 1 + x keeps only an absolute error of 1e-16, i.e. a relative error of 1e-16/x
// in e, while the series works on b - I, whose entries are exact differences.
#include <cmath>

namespace femdem {

namespace detail {

// c = a b for symmetric a, b that commute (c is then symmetric); xx yy zz xy yz xz.
inline void commuting_product(const double a[6], const double b[6], double c[6]) {
  c[0] = a[0] * b[0] + a[3] * b[3] + a[5] * b[5];
  c[1] = a[3] * b[3] + a[1] * b[1] + a[4] * b[4];
  c[2] = a[5] * b[5] + a[4] * b[4] + a[2] * b[2];
  c[3] = a[0] * b[3] + a[3] * b[1] + a[5] * b[4];
  c[4] = a[3] * b[5] + a[1] * b[4] + a[4] * b[2];
  c[5] = a[0] * b[5] + a[3] * b[4] + a[5] * b[2];
}

}  // namespace detail

// Largest |y| for which the series is used (relative truncation error below 1e-16, above).
inline constexpr double kLogStrainSeriesRadius = 0.06;

// e = 0.5 ln(b) (6 components) if b is within the series' range; false (e untouched) otherwise.
inline bool log_strain_by_series(const double b[6], double e[6]) {
  const double x[6] = {b[0] - 1.0, b[1] - 1.0, b[2] - 1.0, b[3], b[4], b[5]};
  // Large strains leave at once: |X|_F > 0.25 means an eigenvalue |x| > 0.25 / sqrt(3), where
  // |y| = |x / (2 + x)| > 0.067 is out of range anyway (the check on Y below would decline).
  const double x_norm2 =
      x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + 2.0 * (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
  if (!(x_norm2 <= 0.0625)) return false;
  // (b + I)^-1 = (2I + X)^-1 by its adjugate
  const double m[6] = {2.0 + x[0], 2.0 + x[1], 2.0 + x[2], x[3], x[4], x[5]};
  const double a0 = m[1] * m[2] - m[4] * m[4];
  const double a1 = m[0] * m[2] - m[5] * m[5];
  const double a2 = m[0] * m[1] - m[3] * m[3];
  const double a3 = m[4] * m[5] - m[3] * m[2];
  const double a4 = m[3] * m[5] - m[0] * m[4];
  const double a5 = m[3] * m[4] - m[1] * m[5];
  const double det = m[0] * a0 + m[3] * a3 + m[5] * a5;
  const double inv_det = 1.0 / det;
  const double minv[6] = {a0 * inv_det, a1 * inv_det, a2 * inv_det,
                          a3 * inv_det, a4 * inv_det, a5 * inv_det};
  double y[6];
  detail::commuting_product(x, minv, y);
  const double y_norm2 =
      y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + 2.0 * (y[3] * y[3] + y[4] * y[4] + y[5] * y[5]);
  // det > 0 keeps b + I positive definite: b itself may be anything here
  if (!(y_norm2 < kLogStrainSeriesRadius * kLogStrainSeriesRadius) || !(det > 0.0)) return false;
  double y2[6];
  detail::commuting_product(y, y, y2);
  // p = I + Y2/3 + Y2^2/5 + ... + Y2^5/11 by Horner, then e = Y p
  double p[6] = {1.0 / 11.0, 1.0 / 11.0, 1.0 / 11.0, 0.0, 0.0, 0.0};
  constexpr double kCoefficients[5] = {1.0 / 9.0, 1.0 / 7.0, 1.0 / 5.0, 1.0 / 3.0, 1.0};
  for (const double c : kCoefficients) {
    double q[6];
    detail::commuting_product(p, y2, q);
    for (int i = 0; i < 6; ++i) p[i] = q[i];
    p[0] += c;
    p[1] += c;
    p[2] += c;
  }
  detail::commuting_product(y, p, e);
  return true;
}

}  // namespace femdem
