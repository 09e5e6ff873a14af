// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// TET10 shape functions in volume coordinates (L0..L3, L0 = 1 - xi - eta - zeta), the 4-point
// Gauss rule and HRZ lumped mass. Node order: see tet10_mesh.hpp.
#include <array>

#include "elements/tet10_mesh.hpp"

namespace femdem::tet10 {

inline constexpr int kNodes = 10;
inline constexpr int kGauss = 4;
// 4-point rule, exact for quadratics: one coordinate a, three b; each weight 1/4 of the volume.
inline constexpr double kGaussA = 0.58541019662496845446;
inline constexpr double kGaussB = 0.13819660112501051518;

// Volume coordinates of Gauss point g: L_g = a, the others b.
inline std::array<double, 4> gauss_point(int g) {
  std::array<double, 4> L{kGaussB, kGaussB, kGaussB, kGaussB};
  L[g] = kGaussA;
  return L;
}

// Shape function values at volume coordinates L.
inline std::array<double, kNodes> shape(const std::array<double, 4>& L) {
  std::array<double, kNodes> N{};
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2.0 * L[i] - 1.0);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4.0 * L[kTet10Edges[e][0]] * L[kTet10Edges[e][1]];
  return N;
}

// Derivatives dN/dxi_k (k = 0..2 for xi, eta, zeta with L1 = xi, L2 = eta, L3 = zeta).
inline std::array<std::array<double, 3>, kNodes> shape_derivatives(const std::array<double, 4>& L) {
  // dN/dL_j first, then chain rule with dL0/dxi_k = -1, dL_{k+1}/dxi_k = 1.
  std::array<std::array<double, 4>, kNodes> dL{};
  for (int i = 0; i < 4; ++i) dL[i][i] = 4.0 * L[i] - 1.0;
  for (int e = 0; e < 6; ++e) {
    const int a = kTet10Edges[e][0], b = kTet10Edges[e][1];
    dL[4 + e][a] = 4.0 * L[b];
    dL[4 + e][b] = 4.0 * L[a];
  }
  std::array<std::array<double, 3>, kNodes> d{};
  for (int n = 0; n < kNodes; ++n)
    for (int k = 0; k < 3; ++k) d[n][k] = dL[n][k + 1] - dL[n][0];
  return d;
}

// The 8 linear sub-tetrahedra of a TET10 cut at its mid-edge nodes (4 at the corners, 4 around
// the 6-8 diagonal of the inner octahedron), each positively oriented.
inline constexpr int kSubTets[8][4] = {{0, 4, 6, 7}, {1, 5, 4, 8}, {2, 6, 5, 9}, {3, 7, 9, 8},
                                       {6, 8, 4, 5}, {6, 8, 5, 9}, {6, 8, 9, 7}, {6, 8, 7, 4}};

// The edges u = b - a, v = c - a, w = d - a of sub-tetrahedron t = (a, b, c, d) of 10 nodes.
inline void subtet_edges(const double* x, const int (&t)[4], double u[3], double v[3],
                         double w[3]) {
  const double* a = x + 3 * t[0];
  const double* b = x + 3 * t[1];
  const double* c = x + 3 * t[2];
  const double* d = x + 3 * t[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
}

// Sum of the sub-tetrahedra volumes of 10 nodes (30 coordinates).
inline double subtet_volume(const double* x) {
  double v6 = 0.0;
  for (const auto& t : kSubTets) {
    double u[3], v[3], w[3];
    subtet_edges(x, t, u, v, w);
    v6 += u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0]);
  }
  return v6 / 6.0;
}

// fe += s * 6 d(subtet_volume)/dx: each sub-tetrahedron's volume gradient on its 4 nodes (the
// sub-tet F-bar's pressure forces; s carries the 1/6).
inline void add_subtet_volume_gradient(const double* x, double s, double* fe) {
  for (const auto& t : kSubTets) {
    double u[3], v[3], w[3];
    subtet_edges(x, t, u, v, w);
    const double gb[3] = {v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2],
                          v[0] * w[1] - v[1] * w[0]};
    const double gc[3] = {w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2],
                          w[0] * u[1] - w[1] * u[0]};
    const double gd[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                          u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k) {
      fe[3 * t[1] + k] += s * gb[k];
      fe[3 * t[2] + k] += s * gc[k];
      fe[3 * t[3] + k] += s * gd[k];
      fe[3 * t[0] + k] -= s * (gb[k] + gc[k] + gd[k]);
    }
  }
}

// HRZ lumping of the consistent mass of a straight-sided TET10: the consistent diagonal is
// 6/420 m (corner) and 32/420 m (mid-edge); scaled to sum to m this gives m/36 and 4m/27
// (row-sum lumping would give negative corner masses).
inline constexpr double kHrzCorner = 1.0 / 36.0;
inline constexpr double kHrzMidEdge = 4.0 / 27.0;

}  // namespace femdem::tet10
