// SPDX-License-Identifier: GPL-3.0-or-later
// Per-instruction-set header (see materials/lanes/lanes8-inl.h): the SIMD update of a pair of
// TET10 elements (element_update.hpp), included by the generated per-variant sources
// (element_update_variant.cpp.in), one per F-bar mode and gradient kind, so that the compiler
// works on them in parallel.
#if defined(FEMDEM_ELEMENT_PAIRS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef FEMDEM_ELEMENT_PAIRS_INL_H_
#undef FEMDEM_ELEMENT_PAIRS_INL_H_
#else
#define FEMDEM_ELEMENT_PAIRS_INL_H_
#endif

#include <cmath>
#include <type_traits>
#include <variant>

#include "elements/tet10_shape.hpp"
#include "engine/element_kernel.hpp"
#include "engine/element_update/element_update.hpp"
#include "materials/lanes/material_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace femdem::HWY_NAMESPACE {
namespace element_pairs_detail {

// dN_a/dxi_k at the 4 Gauss points, as packs: lanes g0..g3 twice (both elements of a pair).
struct NaturalGradients {
  alignas(64) double d[10][3][8];
};
inline const NaturalGradients& natural_gradients() {
  static const NaturalGradients table = [] {
    NaturalGradients t{};
    for (int g = 0; g < 4; ++g) {
      const auto dxi = tet10::shape_derivatives(tet10::gauss_point(g));
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) t.d[a][k][g] = t.d[a][k][g + 4] = dxi[a][k];
    }
    return t;
  }();
  return table;
}

HWY_INLINE Lanes8 det3(const Lanes8 A[3][3]) {
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

// cof = det(A) A^-T
HWY_INLINE void cofactor3(const Lanes8 F[3][3], Lanes8 cof[3][3]) {
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

// Each element's smallest corner-tetrahedron altitude, 3 V / largest face area (as
// corner_tet_min_altitude in element_kernel.hpp, which the scalar pass uses), from the two
// elements' corner positions (12 each): the 4 faces' cross products as the lanes.
HWY_INLINE PairOf corner_altitudes(const double* xe0, const double* xe1) {
  // face f spans edges a_f and b_f from one corner: (01, 02), (01, 03), (02, 03), (12, 13)
  constexpr int kFrom[4] = {0, 0, 0, 1}, kToA[4] = {1, 1, 2, 2}, kToB[4] = {2, 3, 3, 3};
  alignas(64) double a[3][8], b[3][8];
  const double* xs[2] = {xe0, xe1};
  for (int el = 0; el < 2; ++el)
    for (int f = 0; f < 4; ++f)
      for (int k = 0; k < 3; ++k) {
        a[k][4 * el + f] = xs[el][3 * kToA[f] + k] - xs[el][3 * kFrom[f] + k];
        b[k][4 * el + f] = xs[el][3 * kToB[f] + k] - xs[el][3 * kFrom[f] + k];
      }
  const Lanes8 a0 = load8(a[0]), a1 = load8(a[1]), a2 = load8(a[2]);
  const Lanes8 b0 = load8(b[0]), b1 = load8(b[1]), b2 = load8(b[2]);
  const Lanes8 c0 = a1 * b2 - a2 * b1, c1 = a2 * b0 - a0 * b2, c2 = a0 * b1 - a1 * b0;
  const PairOf area2 = max4(sqrt(c0 * c0 + c1 * c1 + c2 * c2));
  // 6 V = e03 . (e01 x e02): lane 1's b with lane 0's c. With explicit fused multiply-adds, so
  // that both elements of the pair round alike (left to the compiler, the two copies of an
  // expression may be contracted differently: an element's bits would then depend on its place
  // in the pair, which a distributed run's renumbering changes)
  alignas(64) double c[3][8];
  store8(c0, c[0]);
  store8(c1, c[1]);
  store8(c2, c[2]);
  auto vol6 = [&](int el) {
    const int l = 4 * el;
    return std::fma(b[0][l + 1], c[0][l], std::fma(b[1][l + 1], c[1][l], b[2][l + 1] * c[2][l]));
  };
  return {vol6(0) / area2.first, vol6(1) / area2.second};
}

// The pair's gradients: either J0^-1 with the natural derivatives (straight-sided) or the
// table, and the Gauss weights.
struct PairGradients {
  Lanes8 jinv[3][3];  // straight-sided
  Lanes8 weight;
  const double* table0 = nullptr;  // curved: [3a+j][g] of each element
  const double* table1 = nullptr;
};

// F = I + sum_a u_a (x) dN_a/dX at the pair's 8 points, u = x - X (the scalar kernel's form:
// rounding relative to the displacements, not to the positions), and the gradients it used.
template <bool kStraight>
HWY_INLINE void deformation_gradient(const ElementUpdateArrays& in, std::size_t e0, std::size_t e1,
                                     PairGradients& grad, Lanes8 F[3][3]) {
  const Tet10& c0 = in.conn[e0];
  const Tet10& c1 = in.conn[e1];
  const NaturalGradients& nat = natural_gradients();
  Lanes8 U[10][3];
  for (int a = 0; a < 10; ++a)
    for (int i = 0; i < 3; ++i) {
      const std::size_t n0 = 3 * static_cast<std::size_t>(c0[a]) + i;
      const std::size_t n1 = 3 * static_cast<std::size_t>(c1[a]) + i;
      U[a][i] = pair(in.x[n0] - in.X[n0], in.x[n1] - in.X[n1]);
    }
  grad.weight = load_pair(in.gauss_weight + 4 * e0, in.gauss_weight + 4 * e1);
  if constexpr (kStraight) {
    const double* j0 = in.inverse_jacobian + 9 * e0;
    const double* j1 = in.inverse_jacobian + 9 * e1;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) grad.jinv[k][j] = pair(j0[3 * k + j], j1[3 * k + j]);
    Lanes8 Jc[3][3];  // du/dxi
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        Lanes8 s = U[0][i] * load8(nat.d[0][k]);
        for (int a = 1; a < 10; ++a) s = mul_add(U[a][i], load8(nat.d[a][k]), s);
        Jc[i][k] = s;
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        F[i][j] = Jc[i][0] * grad.jinv[0][j] + Jc[i][1] * grad.jinv[1][j] +
                  Jc[i][2] * grad.jinv[2][j] + Lanes8(i == j ? 1.0 : 0.0);
  } else {
    grad.table0 = in.dNdX_lanes + 120 * e0;
    grad.table1 = in.dNdX_lanes + 120 * e1;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Lanes8 s = U[0][i] * load_pair(grad.table0 + j * 4, grad.table1 + j * 4);
        for (int a = 1; a < 10; ++a)
          s = mul_add(U[a][i],
                      load_pair(grad.table0 + (3 * a + j) * 4, grad.table1 + (3 * a + j) * 4), s);
        F[i][j] = s + Lanes8(i == j ? 1.0 : 0.0);
      }
  }
}

// f_a = sum_g P_g dN_a/dX|_g for the pair: per element, the sum of its 4 lanes (f1 not written
// for a single element).
template <bool kStraight>
HWY_INLINE void node_sums(const Lanes8 P[3][3], const PairGradients& grad, double* f0, double* f1,
                          bool single) {
  if constexpr (kStraight) {
    const NaturalGradients& nat = natural_gradients();
    Lanes8 Q[3][3];  // P J0^-T: f_a,i = sum_g sum_k Q_ik dN_a/dxi_k
    for (int i = 0; i < 3; ++i)
      for (int kk = 0; kk < 3; ++kk)
        Q[i][kk] =
            P[i][0] * grad.jinv[kk][0] + P[i][1] * grad.jinv[kk][1] + P[i][2] * grad.jinv[kk][2];
    for (int a = 0; a < 10; ++a) {
      const Lanes8 n0 = load8(nat.d[a][0]), n1 = load8(nat.d[a][1]), n2 = load8(nat.d[a][2]);
      for (int i = 0; i < 3; ++i) {
        const PairOf s = sum4(mul_add(Q[i][0], n0, mul_add(Q[i][1], n1, Q[i][2] * n2)));
        f0[3 * a + i] = s.first;
        if (!single) f1[3 * a + i] = s.second;
      }
    }
  } else {
    for (int a = 0; a < 10; ++a) {
      Lanes8 d[3];
      for (int j = 0; j < 3; ++j)
        d[j] = load_pair(grad.table0 + (3 * a + j) * 4, grad.table1 + (3 * a + j) * 4);
      for (int i = 0; i < 3; ++i) {
        const PairOf s = sum4(mul_add(P[i][0], d[0], mul_add(P[i][1], d[1], P[i][2] * d[2])));
        f0[3 * a + i] = s.first;
        if (!single) f1[3 * a + i] = s.second;
      }
    }
  }
}

// Each element's current volume, sum_g w_g det F_g (as tet10_current_volume): the nodal F-bar's
// input, before the update.
template <bool kStraight>
HWY_NOINLINE void pair_volumes(const ElementUpdateArrays& in, const ElementPair* pairs,
                               std::size_t count, double* volume) {
  for (std::size_t p = 0; p < count; ++p) {
    const std::size_t e0 = static_cast<std::size_t>(pairs[p].first),
                      e1 = static_cast<std::size_t>(pairs[p].second);
    PairGradients grad;
    Lanes8 F[3][3];
    deformation_gradient<kStraight>(in, e0, e1, grad, F);
    const PairOf v = sum4(grad.weight * det3(F));
    volume[e0] = v.first;
    if (e1 != e0) volume[e1] = v.second;
  }
}

template <FbarMode kFbar, bool kStraight, class Model>
HWY_INLINE void update_pair(const Model& model, const ElementUpdateArrays& in, ElementPair pr,
                            double dt) {
  constexpr bool kElastic = std::is_same_v<Model, ElasticModel>;
  const std::size_t e0 = static_cast<std::size_t>(pr.first),
                    e1 = static_cast<std::size_t>(pr.second);
  const Tet10& c0 = in.conn[e0];
  const Tet10& c1 = in.conn[e1];

  // 1. F at the 8 points
  PairGradients grad;
  Lanes8 F[3][3];
  deformation_gradient<kStraight>(in, e0, e1, grad, F);
  // the current positions the per-element geometry needs: the corners (the stable step's
  // altitude) or all 10 nodes (the sub-tet volume)
  constexpr int kPositions = kFbar == FbarMode::SubTet ? 10 : 4;
  double xe0[3 * kPositions], xe1[3 * kPositions];
  for (int a = 0; a < kPositions; ++a)
    for (int i = 0; i < 3; ++i) {
      xe0[3 * a + i] = in.x[3 * static_cast<std::size_t>(c0[a]) + i];
      xe1[3 * a + i] = in.x[3 * static_cast<std::size_t>(c1[a]) + i];
    }
  const Lanes8 J = det3(F);
  Lanes8 cof[3][3];
  cofactor3(F, cof);
  const Lanes8 w = grad.weight;

  // 2. F-bar: the material sees (J0 / J)^(1/3) F
  Lanes8 J0 = J, vol0(0.0);
  Lanes8 cof_c[3][3];  // Centroid: cof of the mean F
  double subtet_V0[2] = {1.0, 1.0}, subtet_J0[2] = {1.0, 1.0};
  if constexpr (kFbar == FbarMode::SubTet) {
    // J0 from the volume of the 8 linear sub-tetrahedra (element_kernel.hpp)
    subtet_V0[0] = in.subtet_volume0[e0];
    subtet_V0[1] = in.subtet_volume0[e1];
    subtet_J0[0] = tet10::subtet_volume(xe0) / subtet_V0[0];
    subtet_J0[1] = tet10::subtet_volume(xe1) / subtet_V0[1];
    J0 = pair(subtet_J0[0], subtet_J0[1]);
  } else if constexpr (kFbar == FbarMode::Nodal) {
    // J0_g = sum_c L_c(g) Jbar_c from the corner nodes' averaged volume ratios: kGaussA for the
    // corner the point is nearest, kGaussB for the other three
    alignas(64) double corner[8];
    for (int c = 0; c < 4; ++c) {
      corner[c] = in.node_J[c0[c]];
      corner[4 + c] = in.node_J[c1[c]];
    }
    const Lanes8 cj = load8(corner);
    J0 = mul_add(Lanes8(tet10::kGaussA - tet10::kGaussB), cj,
                 Lanes8(tet10::kGaussB) * sum4_broadcast(cj));
  } else if constexpr (kFbar == FbarMode::VolumeAverage) {
    vol0 = sum4_broadcast(w);
    J0 = sum4_broadcast(w * J) / vol0;
  } else if constexpr (kFbar == FbarMode::Centroid) {
    Lanes8 Fc[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Fc[i][j] = Lanes8(0.25) * sum4_broadcast(F[i][j]);
    J0 = det3(Fc);
    cofactor3(Fc, cof_c);
  }
  Lanes8 Fm[3][3], Fm_inv_T[3][3];
  {
    const Lanes8 scale = kFbar == FbarMode::Off ? Lanes8(1.0) : cbrt_positive(J0 / J);
    const Lanes8 inv = Lanes8(1.0) / (J * scale);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Fm[i][j] = kFbar == FbarMode::Off ? F[i][j] : scale * F[i][j];
        Fm_inv_T[i][j] = cof[i][j] * inv;
      }
  }

  // 3. the material
  GaussPointLanes st;
  ElementStates& s0 = in.state[e0];
  ElementStates& s1 = in.state[e1];
  if constexpr (!kElastic) {
    for (int c = 0; c < 6; ++c) st.Cp_inv[c] = load_pair(s0.Cp_inv[c], s1.Cp_inv[c]);
    st.eps_p = load_pair(s0.eps_p, s1.eps_p);
    st.kappa = load_pair(s0.kappa, s1.kappa);
  } else {
    st.eps_p = Lanes8(0.0);
  }
  const FiniteStrainLanes r = finite_strain_update(Fm, Fm_inv_T, st, model, dt);
  if constexpr (!kElastic) {
    for (int c = 0; c < 6; ++c) store_pair(st.Cp_inv[c], s0.Cp_inv[c], s1.Cp_inv[c]);
    store_pair(st.eps_p, s0.eps_p, s1.eps_p);
    store_pair(st.kappa, s0.kappa, s1.kappa);
  }
  {
    const Lanes8 inv_Jm = Lanes8(1.0) / J0;  // J without F-bar
    double* sig0 = in.stress + 24 * e0;
    double* sig1 = in.stress + 24 * e1;
    for (int c = 0; c < 6; ++c) store_pair(r.tau[c] * inv_Jm, sig0 + 4 * c, sig1 + 4 * c);
  }

  // 4. first Piola-Kirchhoff stress times the weight: P = (w / J) S cof(F) (+ F-bar pressure)
  Lanes8 S[6];
  Lanes8 P[3][3];
  PairOf subtet_pressure_work{0.0, 0.0};  // SubTet: sum_g w_g p_g per element
  const Lanes8 k = w / J;
  if constexpr (kFbar == FbarMode::Off) {
    for (int c = 0; c < 6; ++c) S[c] = r.tau[c];
  } else {
    const Lanes8 p = (r.tau[0] + r.tau[1] + r.tau[2]) * Lanes8(1.0 / 3.0);
    for (int c = 0; c < 3; ++c) S[c] = r.tau[c] - p;
    for (int c = 3; c < 6; ++c) S[c] = r.tau[c];
    if constexpr (kFbar == FbarMode::SubTet) subtet_pressure_work = sum4(w * p);
    if constexpr (kFbar == FbarMode::Nodal) {
      // the element's share of dW/dJbar_c per corner: sum_g w_g p_g L_c(g) / J0_g
      const Lanes8 q = w * p / J0;
      const Lanes8 share = mul_add(Lanes8(tet10::kGaussA - tet10::kGaussB), q,
                                   Lanes8(tet10::kGaussB) * sum4_broadcast(q));
      store_pair(share, in.pressure_weight + 4 * e0, in.pressure_weight + 4 * e1);
    }
    if constexpr (kFbar == FbarMode::VolumeAverage) {
      const Lanes8 pressure_work = sum4_broadcast(w * p);
      // the pressure acts through each point's J: + (pw w / (V J0)) cof = (w / J) (pw J / (V J0))
      // cof
      const Lanes8 extra = pressure_work * J / (vol0 * J0);
      for (int c = 0; c < 3; ++c) S[c] = S[c] + extra;
    }
    if constexpr (kFbar == FbarMode::Centroid) {
      const Lanes8 kc = Lanes8(0.25) * sum4_broadcast(w * p) / J0;
      const Lanes8 Sm[3][3] = {{S[0], S[3], S[5]}, {S[3], S[1], S[4]}, {S[5], S[4], S[2]}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          P[i][j] = k * (Sm[i][0] * cof[0][j] + Sm[i][1] * cof[1][j] + Sm[i][2] * cof[2][j]) +
                    kc * cof_c[i][j];
    }
  }
  if constexpr (kFbar != FbarMode::Centroid) {
    const Lanes8 Sm[3][3] = {{S[0], S[3], S[5]}, {S[3], S[1], S[4]}, {S[5], S[4], S[2]}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        P[i][j] = k * (Sm[i][0] * cof[0][j] + Sm[i][1] * cof[1][j] + Sm[i][2] * cof[2][j]);
  }

  // 5. f_a = sum_g P_g dN_a/dX|_g: per element, the sum of its 4 lanes
  double* f0 = in.force + 30 * e0;
  double* f1 = in.force + 30 * e1;
  const bool single = e0 == e1;
  node_sums<kStraight>(P, grad, f0, f1, single);
  if constexpr (kFbar == FbarMode::Nodal) {
    // the gradient of the element's volume, sum_g w_g cof(F_g) dN/dX|_g: the nodal F-bar's
    // pressure forces are this times a per-element factor known after the pass
    Lanes8 Pv[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Pv[i][j] = w * cof[i][j];
    node_sums<kStraight>(Pv, grad, in.volume_gradient + 30 * e0, in.volume_gradient + 30 * e1,
                         single);
  }

  if constexpr (kFbar == FbarMode::SubTet) {
    // the mean pressure through dJ0 = d(sum_s V_s) / V0 (element_kernel.hpp)
    tet10::add_subtet_volume_gradient(
        xe0, subtet_pressure_work.first / (subtet_J0[0] * subtet_V0[0] * 6.0), f0);
    if (!single)
      tet10::add_subtet_volume_gradient(
          xe1, subtet_pressure_work.second / (subtet_J0[1] * subtet_V0[1] * 6.0), f1);
  }

  // 6. the elements' sums
  const PairOf energy = sum4(w * r.energy);
  const PairOf dissipation = sum4(w * r.dissipation);
  PairOf min_J = min4(J);
  if constexpr (kFbar == FbarMode::Centroid || kFbar == FbarMode::SubTet) {
    const PairOf j0 = min4(J0);
    min_J = {std::fmin(min_J.first, j0.first), std::fmin(min_J.second, j0.second)};
  }
  const PairOf eps = max4(st.eps_p);
  const PairOf altitude = corner_altitudes(xe0, xe1);
  in.result[e0] = {energy.first, dissipation.first, min_J.first, eps.first, altitude.first};
  if (!single)
    in.result[e1] = {energy.second, dissipation.second, min_J.second, eps.second, altitude.second};
}

template <FbarMode kFbar, bool kStraight, class Model>
HWY_NOINLINE void update_pairs(const Model& model, const ElementUpdateArrays& in,
                               const ElementPair* pairs, std::size_t count, double dt) {
  for (std::size_t p = 0; p < count; ++p) update_pair<kFbar, kStraight>(model, in, pairs[p], dt);
}

}  // namespace element_pairs_detail

// Updates `count` pairs of elements with one material, F-bar mode kFbar and gradient kind.
template <FbarMode kFbar, bool kStraight>
HWY_INLINE void update_pairs_of_any_model(const MaterialKernel& material,
                                          const ElementUpdateArrays& in, const ElementPair* pairs,
                                          std::size_t count, double dt) {
  std::visit(
      [&](const auto& model) {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (has_lanes_return<Model>)
          element_pairs_detail::update_pairs<kFbar, kStraight>(model, in, pairs, count, dt);
      },
      material);
}

}  // namespace femdem::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // FEMDEM_ELEMENT_PAIRS_INL_H_
