// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Eigen-decomposition of a symmetric 3x3 matrix: closed form refined by a Jacobi sweep.
//
// Why not the closed form alone: the trigonometric cubic solution loses accuracy near repeated
// eigenvalues (the thesis found it unstable; Eigen's computeDirect errs by ~1e-8 in the log
// strain there). Why not cyclic Jacobi alone (kept below as symmetric_eigen3_jacobi): it is
// accurate to round-off for any spectrum but needs 3-5 sweeps of 3 rotations, which made it the
// largest cost of the element update. So:
//  1. Shift by the mean eigenvalue m = tr(A)/3 and scale by the largest entry of A - m I: C.
//  2. The eigenvalue of C farthest from the other two (the largest if det C >= 0, otherwise the
//     smallest) is a simple root of the depressed cubic, separated from the others by at least
//     sqrt(3) p with p^2 = tr(C^2)/6: p times a polynomial fit of 2 cos(acos(r)/3) (3e-9) and
//     one Newton step on the cubic (round-off).
//  3. Its eigenvector is the largest cross product of two rows of C - beta I (well conditioned
//     because of that separation). Complete it to an orthonormal frame Q = [v, u, v x u].
//  4. G = Q^T C Q; one exact Jacobi rotation diagonalises the (u, w) block (accurate whatever its
//     spectrum, repeated or not), then a Jacobi sweep removes what the closed form left in the
//     (v, .) couplings: their angles are ~1e-15, where a Jacobi rotation is exactly
//     [1 t; -t 1] in double (c = 1, t = g_pq / (g_qq - g_pp)), so the two are applied at once.
//     If an angle is not that small (not seen in practice) full cyclic sweeps take over until
//     the off-diagonal is negligible: accurate whatever the closed form's error.
// The eigenvalues are the diagonal of the polished G (Rayleigh quotients), the eigenvectors the
// columns of Q times the rotations: orthonormal to round-off by construction.
// Domain: finite entries of magnitude below about 1e300 (m and A - m I must not overflow).
#include <algorithm>
#include <cfloat>
#include <cmath>

namespace femdem {

// Symmetric 3x3 stored as 6 numbers: xx yy zz xy yz xz.
struct SymEig3 {
  double value[3];      // unsorted
  double vector[3][3];  // vector[k][i]: component k of eigenvector i (columns are eigenvectors)
};

// Reference solver: cyclic Jacobi to convergence (3-5 sweeps at machine precision).
inline SymEig3 symmetric_eigen3_jacobi(const double s[6]) {
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
      const double t =
          std::copysign(1.0, theta) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
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

namespace detail {

// Jacobi rotation zeroing g[p][q] of the symmetric g (o is the third index), accumulated into
// the columns p, q of v. t = tan(angle) is the smaller root of t^2 + 2 theta t - 1 = 0 with
// theta = (g_qq - g_pp) / (2 g_pq); c = cos, s = sin.
inline void apply_rotation(double g[3][3], double v[3][3], int p, int q, int o, double t, double c,
                           double s) {
  const double gpq = g[p][q];
  g[p][p] -= t * gpq;
  g[q][q] += t * gpq;
  g[p][q] = g[q][p] = 0.0;
  const double gop = g[o][p], goq = g[o][q];
  g[o][p] = g[p][o] = c * gop - s * goq;
  g[o][q] = g[q][o] = s * gop + c * goq;
  for (int k = 0; k < 3; ++k) {
    const double vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

// Any angle, branch-free. With h = (g_qq - g_pp)/2 and r = sqrt(h^2 + g_pq^2), the vector
// (r + |h|, sgn(h) g_pq) points along (c, s); its tiny floor (far below round-off of |C| ~ 1)
// keeps the exactly degenerate case (h = g_pq = 0) at the identity.
inline void jacobi_rotate(double g[3][3], double v[3][3], int p, int q, int o) {
  const double gpq = g[p][q];
  const double h = 0.5 * (g[q][q] - g[p][p]);
  const double x = std::fabs(h) + std::sqrt(h * h + gpq * gpq) + 1e-150;
  const double y = std::copysign(1.0, h) * gpq;
  const double in = 1.0 / std::sqrt(x * x + y * y);
  apply_rotation(g, v, p, q, o, y / x, x * in, y * in);
}

// Full cyclic sweeps until the off-diagonal is negligible (|C| ~ 1: below 1e-20, far under
// round-off). Out of line: the cold path, taken only if the closed form was not accurate.
[[gnu::noinline]] inline void jacobi_sweeps(double g[3][3], double v[3][3]) {
  for (int sweep = 0; sweep < 10; ++sweep) {
    jacobi_rotate(g, v, 0, 1, 2);
    jacobi_rotate(g, v, 0, 2, 1);
    jacobi_rotate(g, v, 1, 2, 0);
    if (g[0][1] * g[0][1] + g[0][2] * g[0][2] + g[1][2] * g[1][2] <= 1e-40) break;
  }
}

inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

}  // namespace detail

inline SymEig3 symmetric_eigen3(const double s[6]) {
  SymEig3 r;
  if (s[3] == 0.0 && s[4] == 0.0 && s[5] == 0.0) {  // already diagonal: exact, input order
    for (int i = 0; i < 3; ++i) {
      r.value[i] = s[i];
      for (int k = 0; k < 3; ++k) r.vector[k][i] = (k == i) ? 1.0 : 0.0;
    }
    return r;
  }
  // 1. C = (A - m I) / scale, entries in [-1, 1] with at least one of magnitude 1.
  // m rounds with an error of eps |m|, so A - m I keeps a trace of that size, which near A = I
  // is large relative to A - m I itself: a second shift by that trace makes it traceless to
  // round-off relative to A - m I, as the closed form assumes.
  const double m = (s[0] + s[1] + s[2]) * (1.0 / 3.0);
  double b[6] = {s[0] - m, s[1] - m, s[2] - m, s[3], s[4], s[5]};
  const double m2 = (b[0] + b[1] + b[2]) * (1.0 / 3.0);
  for (int i = 0; i < 3; ++i) b[i] -= m2;
  double scale = 0.0;
  for (int i = 0; i < 6; ++i) scale = std::fabs(b[i]) > scale ? std::fabs(b[i]) : scale;
  if (scale < DBL_MIN) [[unlikely]] {  // subnormal deviator: 1/scale would overflow
    for (int i = 0; i < 6; ++i) b[i] *= 0x1p600;
    scale *= 0x1p600;
    for (int i = 0; i < 6; ++i) b[i] /= scale;
    scale *= 0x1p-600;
  } else {
    const double inv = 1.0 / scale;
    for (int i = 0; i < 6; ++i) b[i] *= inv;
  }
  const double c[3][3] = {{b[0], b[3], b[5]}, {b[3], b[1], b[4]}, {b[5], b[4], b[2]}};

  // 2. Separated eigenvalue beta of C: roots are 2 p cos(acos(r)/3 + 2 pi k/3), r = det C/(2p^3).
  const double q = (c[0][0] * c[0][0] + c[1][1] * c[1][1] + c[2][2] * c[2][2] +
                    2.0 * (c[0][1] * c[0][1] + c[1][2] * c[1][2] + c[0][2] * c[0][2])) *
                   (1.0 / 6.0);  // >= 1/6 since some entry has magnitude 1
  const double p = std::sqrt(q);
  const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[1][2]) -
                     c[0][1] * (c[0][1] * c[2][2] - c[1][2] * c[0][2]) +
                     c[0][2] * (c[0][1] * c[1][2] - c[1][1] * c[0][2]);
  double rr = std::fabs(det) / (2.0 * q * p);
  rr = rr > 1.0 ? 1.0 : rr;
  // y = 2 cos(acos(rr)/3) on [0, 1]: analytic there (sqrt(3) at 0, 2 at 1). Degree-8 Chebyshev
  // fit, error 3.2e-9, evaluated by Estrin's scheme (short dependency chain), then one Newton
  // step on y^3 - 3y - 2rr = 0 (|y'| >= 6 there): error ~1e-17, i.e. round-off.
  const double rr2 = rr * rr, rr4 = rr2 * rr2;
  const double y01 = 0x1.bb67ae931e9d8p+0 + 0x1.5555317dcedb7p-2 * rr;
  const double y23 = -0x1.8a138ae366fb0p-4 + 0x1.9330ec1b63640p-5 * rr;
  const double y45 = -0x1.ef9bb59cecf00p-6 + 0x1.34ad5027c5c00p-6 * rr;
  const double y67 = -0x1.45e1d9b368000p-7 + 0x1.d57d542600000p-9 * rr;
  const double y = (y01 + y23 * rr2) + ((y45 + y67 * rr2) + -0x1.4458818600000p-11 * rr4) * rr4;
  const double yn = y - (y * (y * y - 3.0) - 2.0 * rr) / (3.0 * (y * y - 1.0));
  const double beta = std::copysign(p * yn, det);  // largest if det >= 0, else smallest

  // 3. Its eigenvector: the best-conditioned cross product of two rows of C - beta I.
  const double r0[3] = {c[0][0] - beta, c[0][1], c[0][2]};
  const double r1[3] = {c[0][1], c[1][1] - beta, c[1][2]};
  const double r2[3] = {c[0][2], c[1][2], c[2][2] - beta};
  double x01[3], x02[3], x12[3];
  detail::cross(r0, r1, x01);
  detail::cross(r0, r2, x02);
  detail::cross(r1, r2, x12);
  const double n01 = x01[0] * x01[0] + x01[1] * x01[1] + x01[2] * x01[2];
  const double n02 = x02[0] * x02[0] + x02[1] * x02[1] + x02[2] * x02[2];
  const double n12 = x12[0] * x12[0] + x12[1] * x12[1] + x12[2] * x12[2];
  const bool use02 = n02 > n01;
  double v[3], nv = use02 ? n02 : n01;
  for (int k = 0; k < 3; ++k) v[k] = use02 ? x02[k] : x01[k];
  const bool use12 = n12 > nv;
  nv = use12 ? n12 : nv;
  for (int k = 0; k < 3; ++k) v[k] = use12 ? x12[k] : v[k];
  // u orthogonal to v, from its two largest components (|u|^2 >= |v|^2 / 2; built before v is
  // normalised so that both square roots run in parallel); w = v x u.
  const bool xz = std::fabs(v[0]) > std::fabs(v[2]);
  double u[3] = {xz ? -v[1] : 0.0, xz ? v[0] : -v[2], xz ? 0.0 : v[1]};
  const double iu = 1.0 / std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double iv = 1.0 / std::sqrt(nv);  // nv >= 3 p^4 / 3 > 0 in exact arithmetic
  for (int k = 0; k < 3; ++k) {
    u[k] *= iu;
    v[k] *= iv;
  }
  double w[3];
  detail::cross(v, u, w);

  // 4. G = Q^T C Q, then the (u, w) rotation and the polish; more sweeps only if needed.
  double Q[3][3] = {{v[0], u[0], w[0]}, {v[1], u[1], w[1]}, {v[2], u[2], w[2]}};
  double CQ[3][3];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      CQ[k][j] = c[k][0] * Q[0][j] + c[k][1] * Q[1][j] + c[k][2] * Q[2][j];
  double g[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      g[i][j] = g[j][i] = Q[0][i] * CQ[0][j] + Q[1][i] * CQ[1][j] + Q[2][i] * CQ[2][j];
  detail::jacobi_rotate(g, Q, 1, 2, 0);
  {
    // Polish of the (v, u) and (v, w) couplings. Below 1e-8, t = rho (1 - rho^2 + ...) and
    // c = 1 - t^2/2 round to rho and 1, and taking both rotations at once (from the same G)
    // errs by O(t01 t02): the second-order terms dropped here are below 1e-16 of |C|. The fill
    // t01 g02 + t02 g01 of g12 is as small, so the (u, w) rotation above stays valid.
    const double t01 = g[0][1] / (g[1][1] - g[0][0]), t02 = g[0][2] / (g[2][2] - g[0][0]);
    if (std::fabs(t01) < 1e-8 && std::fabs(t02) < 1e-8) [[likely]] {
      g[0][0] -= t01 * g[0][1] + t02 * g[0][2];
      g[1][1] += t01 * g[0][1];
      g[2][2] += t02 * g[0][2];
      g[0][1] = g[1][0] = g[0][2] = g[2][0] = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double q0 = Q[k][0], q1 = Q[k][1], q2 = Q[k][2];
        Q[k][0] = q0 - t01 * q1 - t02 * q2;
        Q[k][1] = q1 + t01 * q0;
        Q[k][2] = q2 + t02 * q0;
      }
    } else {
      detail::jacobi_sweeps(g, Q);
    }
  }
  for (int i = 0; i < 3; ++i) {
    r.value[i] = m + (m2 + scale * g[i][i]);
    for (int k = 0; k < 3; ++k) r.vector[k][i] = Q[k][i];
  }
  return r;
}

// The largest eigenvalue only, in closed form (the trigonometric solution of the characteristic
// cubic): for output such as the largest principal stress, where no vectors are needed. Next to
// two equal eigenvalues acos loses half the digits: about 1e-8 of the matrix norm, ample for
// output and not used by any return mapping.
inline double largest_eigenvalue3(const double s[6]) {
  const double off = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  if (off == 0.0) return std::max(s[0], std::max(s[1], s[2]));
  const double q = (s[0] + s[1] + s[2]) / 3.0;
  const double a = s[0] - q, b = s[1] - q, c = s[2] - q;
  const double p2 = a * a + b * b + c * c + 2.0 * off;
  const double p = std::sqrt(p2 / 6.0);
  // det((S - q I) / p) / 2, clamped against round-off to the cosine's range
  const double det =
      a * (b * c - s[4] * s[4]) - s[3] * (s[3] * c - s[4] * s[5]) + s[5] * (s[3] * s[4] - b * s[5]);
  const double r = std::clamp(det / (2.0 * p * p * p), -1.0, 1.0);
  return q + 2.0 * p * std::cos(std::acos(r) / 3.0);
}

}  // namespace femdem
