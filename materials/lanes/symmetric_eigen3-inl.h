// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the eigen-decomposition of a
// symmetric 3x3 matrix in every lane, the algorithm of materials/symmetric_eigen3.hpp without
// its branches: the separated eigenvalue from the closed form (Chebyshev fit + Newton step),
// its vector from the best cross product, an exact Jacobi rotation in the plane orthogonal to
// it and a first-order polish of the remaining couplings. The scalar solver's two rare paths
// become lane selects: a deviator below DBL_MIN (zero included) keeps the input's diagonal and
// the identity frame, and when some lane's polish angle is not small (the closed form was not
// accurate; not seen in practice) all lanes take full Jacobi sweeps.
#if defined(FEMDEM_SYMMETRIC_EIGEN3_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_SYMMETRIC_EIGEN3_LANES_INL_H_
#undef FEMDEM_SYMMETRIC_EIGEN3_LANES_INL_H_
#else
#define FEMDEM_SYMMETRIC_EIGEN3_LANES_INL_H_
#endif

#include <cfloat>

#include "materials/lanes/lanes8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {

// Symmetric 3x3 as xx yy zz xy yz xz, eigenvalues unsorted, vector[k][i] component k of the
// eigenvector i.
struct SymEig3Lanes {
  Lanes8 value[3];
  Lanes8 vector[3][3];
};

namespace eigen3_lanes_detail {

HWY_INLINE void cross(const Lanes8 a[3], const Lanes8 b[3], Lanes8 out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// As materials/symmetric_eigen3.hpp's detail::jacobi_rotate, lane by lane.
HWY_INLINE void jacobi_rotate(Lanes8 g[3][3], Lanes8 v[3][3], int p, int q, int o) {
  const Lanes8 gpq = g[p][q];
  const Lanes8 h = Lanes8(0.5) * (g[q][q] - g[p][p]);
  const Lanes8 x = abs(h) + sqrt(h * h + gpq * gpq) + Lanes8(1e-150);
  const Lanes8 y = select(h < Lanes8(0.0), -gpq, gpq);
  const Lanes8 in = Lanes8(1.0) / sqrt(x * x + y * y);
  const Lanes8 t = y / x, c = x * in, s = y * in;
  g[p][p] = g[p][p] - t * gpq;
  g[q][q] = g[q][q] + t * gpq;
  g[p][q] = g[q][p] = Lanes8(0.0);
  const Lanes8 gop = g[o][p], goq = g[o][q];
  g[o][p] = g[p][o] = c * gop - s * goq;
  g[o][q] = g[q][o] = s * gop + c * goq;
  for (int k = 0; k < 3; ++k) {
    const Lanes8 vkp = v[k][p], vkq = v[k][q];
    v[k][p] = c * vkp - s * vkq;
    v[k][q] = s * vkp + c * vkq;
  }
}

}  // namespace eigen3_lanes_detail

HWY_INLINE SymEig3Lanes symmetric_eigen3(const Lanes8 s[6]) {
  namespace d = eigen3_lanes_detail;
  // 1. C = (A - m I) / scale, twice shifted so that it is traceless to round-off.
  const Lanes8 third(1.0 / 3.0);
  const Lanes8 m = (s[0] + s[1] + s[2]) * third;
  Lanes8 b[6] = {s[0] - m, s[1] - m, s[2] - m, s[3], s[4], s[5]};
  const Lanes8 m2 = (b[0] + b[1] + b[2]) * third;
  for (int i = 0; i < 3; ++i) b[i] = b[i] - m2;
  Lanes8 scale = abs(b[0]);
  for (int i = 1; i < 6; ++i) scale = max(scale, abs(b[i]));
  const Mask8 tiny = scale < Lanes8(DBL_MIN);
  const Lanes8 inv = Lanes8(1.0) / select(tiny, Lanes8(1.0), scale);
  for (int i = 0; i < 6; ++i) b[i] = select(tiny, Lanes8(0.0), b[i] * inv);
  // a tiny lane is given C = diag(1, 0, -1) to keep its arithmetic finite; its result is
  // replaced at the end
  b[0] = select(tiny, Lanes8(1.0), b[0]);
  b[2] = select(tiny, Lanes8(-1.0), b[2]);
  const Lanes8 c[3][3] = {{b[0], b[3], b[5]}, {b[3], b[1], b[4]}, {b[5], b[4], b[2]}};

  // 2. The separated eigenvalue beta = sign(det) p y, y = 2 cos(acos(rr)/3).
  const Lanes8 q = (c[0][0] * c[0][0] + c[1][1] * c[1][1] + c[2][2] * c[2][2] +
                    Lanes8(2.0) * (c[0][1] * c[0][1] + c[1][2] * c[1][2] + c[0][2] * c[0][2])) *
                   Lanes8(1.0 / 6.0);
  const Lanes8 p = sqrt(q);
  const Lanes8 det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[1][2]) -
                     c[0][1] * (c[0][1] * c[2][2] - c[1][2] * c[0][2]) +
                     c[0][2] * (c[0][1] * c[1][2] - c[1][1] * c[0][2]);
  const Lanes8 rr = min(abs(det) / (Lanes8(2.0) * q * p), Lanes8(1.0));
  const Lanes8 rr2 = rr * rr, rr4 = rr2 * rr2;
  const Lanes8 y01 = Lanes8(0x1.bb67ae931e9d8p+0) + Lanes8(0x1.5555317dcedb7p-2) * rr;
  const Lanes8 y23 = Lanes8(-0x1.8a138ae366fb0p-4) + Lanes8(0x1.9330ec1b63640p-5) * rr;
  const Lanes8 y45 = Lanes8(-0x1.ef9bb59cecf00p-6) + Lanes8(0x1.34ad5027c5c00p-6) * rr;
  const Lanes8 y67 = Lanes8(-0x1.45e1d9b368000p-7) + Lanes8(0x1.d57d542600000p-9) * rr;
  const Lanes8 y =
      (y01 + y23 * rr2) + ((y45 + y67 * rr2) + Lanes8(-0x1.4458818600000p-11) * rr4) * rr4;
  const Lanes8 yn =
      y - (y * (y * y - Lanes8(3.0)) - Lanes8(2.0) * rr) / (Lanes8(3.0) * (y * y - Lanes8(1.0)));
  const Lanes8 py = p * yn;
  const Lanes8 beta = select(det < Lanes8(0.0), -py, py);

  // 3. Its eigenvector v; u orthogonal to it from v's two largest components; w = v x u.
  const Lanes8 r0[3] = {c[0][0] - beta, c[0][1], c[0][2]};
  const Lanes8 r1[3] = {c[0][1], c[1][1] - beta, c[1][2]};
  const Lanes8 r2[3] = {c[0][2], c[1][2], c[2][2] - beta};
  Lanes8 x01[3], x02[3], x12[3];
  d::cross(r0, r1, x01);
  d::cross(r0, r2, x02);
  d::cross(r1, r2, x12);
  const Lanes8 n01 = x01[0] * x01[0] + x01[1] * x01[1] + x01[2] * x01[2];
  const Lanes8 n02 = x02[0] * x02[0] + x02[1] * x02[1] + x02[2] * x02[2];
  const Lanes8 n12 = x12[0] * x12[0] + x12[1] * x12[1] + x12[2] * x12[2];
  const Mask8 use02 = n02 > n01;
  Lanes8 v[3], nv = select(use02, n02, n01);
  for (int k = 0; k < 3; ++k) v[k] = select(use02, x02[k], x01[k]);
  const Mask8 use12 = n12 > nv;
  nv = select(use12, n12, nv);
  for (int k = 0; k < 3; ++k) v[k] = select(use12, x12[k], v[k]);
  const Mask8 xz = abs(v[0]) > abs(v[2]);
  const Lanes8 zero(0.0);
  Lanes8 u[3] = {select(xz, -v[1], zero), select(xz, v[0], -v[2]), select(xz, zero, v[1])};
  const Lanes8 iu = Lanes8(1.0) / sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const Lanes8 iv = Lanes8(1.0) / sqrt(nv);
  for (int k = 0; k < 3; ++k) {
    u[k] = u[k] * iu;
    v[k] = v[k] * iv;
  }
  Lanes8 w[3];
  d::cross(v, u, w);

  // 4. G = Q^T C Q, the (u, w) rotation and the polish.
  Lanes8 Q[3][3] = {{v[0], u[0], w[0]}, {v[1], u[1], w[1]}, {v[2], u[2], w[2]}};
  Lanes8 CQ[3][3];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      CQ[k][j] = c[k][0] * Q[0][j] + c[k][1] * Q[1][j] + c[k][2] * Q[2][j];
  Lanes8 g[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      g[i][j] = g[j][i] = Q[0][i] * CQ[0][j] + Q[1][i] * CQ[1][j] + Q[2][i] * CQ[2][j];
  d::jacobi_rotate(g, Q, 1, 2, 0);
  const Lanes8 t01 = g[0][1] / (g[1][1] - g[0][0]), t02 = g[0][2] / (g[2][2] - g[0][0]);
  const Mask8 small = (abs(t01) < Lanes8(1e-8)) & (abs(t02) < Lanes8(1e-8));
  if (!any(!small)) [[likely]] {
    g[0][0] = g[0][0] - (t01 * g[0][1] + t02 * g[0][2]);
    g[1][1] = g[1][1] + t01 * g[0][1];
    g[2][2] = g[2][2] + t02 * g[0][2];
    for (int k = 0; k < 3; ++k) {
      const Lanes8 q0 = Q[k][0], q1 = Q[k][1], q2 = Q[k][2];
      Q[k][0] = q0 - t01 * q1 - t02 * q2;
      Q[k][1] = q1 + t01 * q0;
      Q[k][2] = q2 + t02 * q0;
    }
  } else {
    for (int sweep = 0; sweep < 10; ++sweep) {
      d::jacobi_rotate(g, Q, 0, 1, 2);
      d::jacobi_rotate(g, Q, 0, 2, 1);
      d::jacobi_rotate(g, Q, 1, 2, 0);
      const Lanes8 off = g[0][1] * g[0][1] + g[0][2] * g[0][2] + g[1][2] * g[1][2];
      if (!any(off > Lanes8(1e-40))) break;
    }
  }
  SymEig3Lanes r;
  const Lanes8 one(1.0);
  for (int i = 0; i < 3; ++i) {
    r.value[i] = select(tiny, s[i], m + (m2 + scale * g[i][i]));
    for (int k = 0; k < 3; ++k) r.vector[k][i] = select(tiny, k == i ? one : zero, Q[k][i]);
  }
  return r;
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_SYMMETRIC_EIGEN3_LANES_INL_H_
