// SPDX-License-Identifier: GPL-3.0-or-later
// The thesis' piece-wise linear Drucker-Prager model (sec. 5.8; notes
// reference/seed002-part2.md section 3.7; VALIDATION.md sections 2 and 5).
// Pieces of Table 5.6 (A, B MPa): (0.42, 8), (0.30, 14), (0.14, 30), (0.07, 40.5), (0.035, 49.25);
// the concrete of the drop test, E = 40 GPa, nu = 0.17. Tension positive, p = tr/3,
// q = sqrt(J2).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "materials/drucker_prager.hpp"
#include "materials/material_point.hpp"
#include "materials/piecewise_drucker_prager.hpp"
#include "materials/von_mises.hpp"
#include "support/principal_stress.hpp"
#include "support/test_material.hpp"

using namespace femdem;
using femdem::test::mean_of;
using femdem::test::principal_sorted;
using femdem::test::sqrt_j2;

namespace {

using PwMaterial = TestMaterial<PiecewiseDruckerPragerParams>;

constexpr double kMPa = 1e6;

PwMaterial concrete(std::vector<std::pair<double, double>> pieces, double dilatancy) {
  PwMaterial p;
  p.name = "pwdp";
  p.density = 2700.0;
  p.youngs_modulus = 40e9;
  p.poisson_ratio = 0.17;
  p.pieces = std::move(pieces);
  p.pieces_dilatancy = dilatancy;
  return p;
}

const std::vector<std::pair<double, double>> kTable56 = {
    {0.42, 8e6}, {0.30, 14e6}, {0.14, 30e6}, {0.07, 40.5e6}, {0.035, 49.25e6}};

// The piece whose segment holds pressure p (0-based; the corner pressures of Table 5.6 are
// 0, -50, -100, -150 and -250 MPa).
int piece_at(const PiecewiseDruckerPrager& d, double p) {
  int k = 0;
  for (std::size_t i = 1; i < d.A.size(); ++i)
    if (d.B[i] - d.A[i] * p < d.B[k] - d.A[k] * p) k = static_cast<int>(i);
  return k;
}

}  // namespace

// The table's corners: the pieces meet where the thesis' points are, (p, q) = (-50, 29),
// (-100, 44), (-150, 51), (-250, 58) MPa (notes: the printed signs are flipped).
TEST(PiecewiseDruckerPrager, Table56CornersAreTheThesisPoints) {
  const auto d = make_piecewise_drucker_prager(concrete(kTable56, 0.0), concrete(kTable56, 0.0));
  const double p[4] = {-50, -100, -150, -250}, q[4] = {29, 44, 51, 58};
  for (int k = 0; k < 4; ++k) {
    const double pk = (d.B[k] - d.B[k + 1]) / (d.A[k] - d.A[k + 1]) / kMPa;
    EXPECT_NEAR(pk, p[k], 1e-9);
    EXPECT_NEAR(d.q_limit(pk * kMPa) / kMPa, q[k], 1e-9);
  }
  EXPECT_NEAR(d.p_apex / kMPa, 8.0 / 0.42, 1e-12);
}

// Random trials far beyond yield, with and without dilatancy: each return lands on the polyline
// (so on the piece it chose: a wrong piece would leave q off the polyline), every piece and the
// apex are reached, and the dissipation is non-negative.
TEST(PiecewiseDruckerPrager, ReturnsLandOnTheRightPiece) {
  for (const double dil : {0.0, 0.02, 0.035}) {
    const auto d = make_piecewise_drucker_prager(concrete(kTable56, dil), concrete(kTable56, dil));
    femdem::test::TrialStrains gen;
    std::set<int> pieces;
    int apex = 0;
    for (int n = 0; n < 40000; ++n) {
      const auto e = gen.next(n % 2 ? 2e-3 : 1.5e-2);
      const PrincipalReturn r = d.return_map(e.data(), 0.0, 0.0);
      const std::array<double, 3> s = {r.tau[0], r.tau[1], r.tau[2]};
      const double p = mean_of(s), q = sqrt_j2(s);
      EXPECT_LE(q - d.q_limit(p), 1e-9 * (std::fabs(p) + q + 1e6));
      double diss = 0.0;
      for (int i = 0; i < 3; ++i) diss += r.tau[i] * (e[i] - r.e_el[i]);
      EXPECT_GE(diss, -1e-6);
      if (!r.yielded) continue;
      if (q < 1e-6 * (std::fabs(p) + 1.0)) {
        EXPECT_NEAR(p, d.p_apex, 1e-9 * d.p_apex);
        ++apex;
        continue;
      }
      EXPECT_NEAR(q, d.q_limit(p), 1e-9 * (std::fabs(p) + q)) << "trial " << n;
      pieces.insert(piece_at(d, p));
    }
    std::printf("  dilatancy %.2f: pieces reached %zu of 5, apex returns %d\n", dil, pieces.size(),
                apex);
    EXPECT_EQ(pieces.size(), 5u);
    EXPECT_GT(apex, 10);
  }
}

// The return is continuous across the corners (constant dilatancy: no special corner treatment
// is needed, sec. 5.8.2): trials moving smoothly through every corner's wedge give returned
// stresses that move smoothly.
TEST(PiecewiseDruckerPrager, ContinuousAcrossCorners) {
  const auto d =
      make_piecewise_drucker_prager(concrete(kTable56, 0.035), concrete(kTable56, 0.035));
  const double K = d.K, G = d.G;
  const int n = 100000;
  double worst = 0.0;
  std::array<double, 3> prev{};
  std::set<int> seen;
  for (int k = 0; k <= n; ++k) {
    // trial pressure from +30 MPa (beyond the apex) to -400 MPa, q always 20 MPa above the
    // surface; the deviatoric direction fixed
    const double p_t = (30.0 - 430.0 * k / n) * kMPa;
    const double q_t = std::max(0.0, d.q_limit(p_t)) + 20e6;
    const double ed = q_t / (G * std::sqrt(2.0 * (1.0 + 1.0 / 4 + 1.0 / 4)));  // dir (1,-.5,-.5)
    const double e[3] = {p_t / (3 * K) + ed, p_t / (3 * K) - 0.5 * ed, p_t / (3 * K) - 0.5 * ed};
    const PrincipalReturn r = d.return_map(e, 0.0, 0.0);
    const std::array<double, 3> s = {r.tau[0], r.tau[1], r.tau[2]};
    if (sqrt_j2(s) > 1.0) seen.insert(piece_at(d, mean_of(s)));
    if (k > 0)
      for (int i = 0; i < 3; ++i) worst = std::max(worst, std::fabs(s[i] - prev[i]));
    prev = s;
  }
  // the trial moves by 4.3 kPa in p per sample; the return by a few times that
  std::printf("  largest change between neighbouring trials: %.3g Pa; pieces crossed %zu\n", worst,
              seen.size());
  EXPECT_LT(worst, 1e5);
  EXPECT_EQ(seen.size(), 5u);
}

// One piece is the plain Drucker-Prager cone with eta = A, xi c = B, eta_bar = A_bar.
TEST(PiecewiseDruckerPrager, OnePieceEqualsDruckerPrager) {
  for (const double dil : {0.0, 0.2, 0.42}) {
    const auto pw =
        make_piecewise_drucker_prager(concrete({{0.42, 8e6}}, dil), concrete({{0.42, 8e6}}, dil));
    DruckerPrager dp;
    dp.K = pw.K;
    dp.G = pw.G;
    dp.eta = 0.42;
    dp.eta_bar = dil;
    dp.xi = 1.0;
    dp.cohesion.c0 = 8e6;
    femdem::test::TrialStrains gen;
    for (int n = 0; n < 5000; ++n) {
      const auto e = gen.next(n % 2 ? 1e-3 : 1e-2);
      const PrincipalReturn a = pw.return_map(e.data(), 0.0, 0.0);
      const PrincipalReturn b = dp.return_map(e.data(), 0.0, 0.0);
      ASSERT_EQ(a.yielded, b.yielded);
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.tau[i], b.tau[i], 1e-9 * 8e6) << n;
        EXPECT_NEAR(a.e_el[i], b.e_el[i], 1e-15) << n;
      }
    }
  }
}

// One piece with A = 0 is von Mises with sigma_y = sqrt3 B.
TEST(PiecewiseDruckerPrager, ZeroSlopeIsVonMises) {
  const auto pw =
      make_piecewise_drucker_prager(concrete({{0.0, 20e6}}, 0.0), concrete({{0.0, 20e6}}, 0.0));
  const PwMaterial base = concrete({}, 0.0);
  VonMisesParams vmp;
  vmp.yield_stress = std::sqrt(3.0) * 20e6;
  const VonMises vm = make_von_mises(base, vmp);
  femdem::test::TrialStrains gen;
  for (int n = 0; n < 5000; ++n) {
    const auto e = gen.next(4e-3);
    const PrincipalReturn a = pw.return_map(e.data(), 0.0, 0.0),
                          b = vm.return_map(e.data(), 0.0, 0.0);
    ASSERT_EQ(a.yielded, b.yielded);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a.tau[i], b.tau[i], 1e-9 * 20e6);
  }
}

// Hydrostatic tension beyond B_1 / A_1 returns to the apex sigma = (B_1 / A_1) I.
TEST(PiecewiseDruckerPrager, HydrostaticTensionGoesToApex) {
  const auto d = make_piecewise_drucker_prager(concrete(kTable56, 0.03), concrete(kTable56, 0.03));
  const double e[3] = {1e-3, 1e-3, 1e-3};  // p_trial = 3 K e = 60 MPa > 19.05
  const PrincipalReturn r = d.return_map(e, 0.0, 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.tau[i] / kMPa, 8.0 / 0.42, 1e-9);
}

// The thesis' check of the calibration (Fig. 5.39): confined (uniaxial-strain) compression
// follows the polyline; with deviatoric flow the path climbs through every piece in order.
TEST(PiecewiseDruckerPrager, ConfinedCompressionFollowsThePolyline) {
  const PwMaterial mat = concrete(kTable56, 0.0);
  const auto d = make_piecewise_drucker_prager(mat, mat);
  const auto path = drive_mixed(mat, {{-2.5e-2, 0.0, 5000}}, LateralControl::ZeroStrain);
  int last_piece = 0;
  for (const MaterialPointStep& st : path) {
    if (!st.yielded) continue;
    const auto s = principal_sorted(st.tau);
    const double p = mean_of(s), q = sqrt_j2(s);
    EXPECT_NEAR(q, d.q_limit(p), 1e-9 * std::fabs(p));
    const int k = piece_at(d, p);
    EXPECT_GE(k, last_piece);
    last_piece = k;
  }
  const auto s = principal_sorted(path.back().tau);
  std::printf("  end: p %.1f MPa, q %.2f MPa, piece %d\n", mean_of(s) / kMPa, sqrt_j2(s) / kMPa,
              last_piece + 1);
  EXPECT_EQ(last_piece, 4);
}

// Pieces that do not make a convex surface are refused.
TEST(PiecewiseDruckerPrager, RejectsNonConvexPieces) {
  EXPECT_NE(piecewise_drucker_prager_param_error(concrete({{0.3, 8e6}, {0.42, 14e6}}, 0.0)), "");
  EXPECT_NE(piecewise_drucker_prager_param_error(concrete({{0.42, 8e6}, {0.3, 2e6}}, 0.0)), "");
  EXPECT_EQ(piecewise_drucker_prager_param_error(concrete({{0.42, 8e6}, {0.3, 7e6}}, 0.0)), "");
  EXPECT_NE(piecewise_drucker_prager_param_error(concrete({}, 0.0)), "");
  // dilatancy above the flattest piece's A dissipates negative work at high pressure
  EXPECT_NE(piecewise_drucker_prager_param_error(concrete(kTable56, 0.05)).find("dilatancy"),
            std::string::npos);
  EXPECT_EQ(piecewise_drucker_prager_param_error(concrete(kTable56, 0.0)), "");
}
