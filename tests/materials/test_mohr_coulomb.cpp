// SPDX-License-Identifier: GPL-3.0-or-later
// Mohr-Coulomb at a material point (VALIDATION.md section 2; thesis tests 3.2.3 and 3.2.4, notes
// reference/seed002-part1.md sections 3.4-3.5 and 2.5).
//
// Material of the thesis' tests: E = 35 GPa, nu = 0.15 (the text says Table 3.1's 0.3, but every
// number printed needs 0.15: notes sec. 3.4), c = 15 MPa, phi = psi = 30 degrees. The driver
// prescribes the axial log strain with zero lateral strain; with the Hencky law the Kirchhoff
// stress is the small-strain stress of the log strain, so tau is compared with the thesis'
// small-strain numbers. Tension positive here; the thesis' compression test prints compression
// positive.
// Tolerance 2 % (the issue's): the thesis' table values are rounded to 0.1 MPa and its first
// point lies 0.3 % past yield (notes sec. 3.4); closed forms are checked to round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "materials/finite_strain_update.hpp"
#include "materials/material_point.hpp"
#include "materials/mohr_coulomb.hpp"
#include "support/principal_stress.hpp"
#include "support/test_material.hpp"

using namespace femdem;
using femdem::test::principal_sorted;

namespace {

using McMaterial = TestMaterial<MohrCoulombParams>;

constexpr double kMPa = 1e6;
constexpr double kDeg = M_PI / 180.0;

McMaterial thesis_mc(double psi = 30.0) {
  McMaterial p;
  p.name = "mc";
  p.density = 2500.0;
  p.youngs_modulus = 35e9;
  p.poisson_ratio = 0.15;
  p.cohesion = 15e6;
  p.friction_angle = 30.0;
  p.dilatancy_angle = psi;
  return p;
}

// Largest Mohr-Coulomb plane of a stress with cohesion c.
double mc_yield(const double tau[6], double phi_deg, double c) {
  const auto s = principal_sorted(tau);
  const double sp = std::sin(phi_deg * kDeg), cp = std::cos(phi_deg * kDeg);
  return (s[0] - s[2]) + (s[0] + s[2]) * sp - 2.0 * c * cp;
}

// The state (axial, radial) at the increment whose axial log strain is closest to e.
std::array<double, 2> at_strain(const std::vector<MaterialPointStep>& path, double total,
                                double e) {
  const std::size_t n = path.size();
  const std::size_t k = static_cast<std::size_t>(std::lround(e / total * n)) - 1;
  return {path[k].tau[2], path[k].tau[0]};
}

}  // namespace

// Thesis 3.2.3: uniaxial strain compression. Yield at sigma_a 110.42, sigma_r 19.49 MPa (eq.
// 3.16-3.17), then sigma_a = 51.96 + 3 sigma_r (eq. 3.18) and Table 3.3.
TEST(MohrCoulombUniaxialStrain, CompressionMatchesThesis) {
  const McMaterial mat = thesis_mc();
  const double total = -6e-3;
  const auto path = drive_mixed(mat, {{total, 0.0, 6000}}, LateralControl::ZeroStrain);
  std::size_t first = 0;
  while (!path[first].yielded) ++first;
  const MaterialPointStep& y = path[first - 1];
  std::printf("  yield at e_a %.4g: sigma_a %.3f sigma_r %.3f MPa (thesis 110.42 / 19.49)\n",
              -6e-3 * static_cast<double>(first) / 6000.0, -y.tau[2] / kMPa, -y.tau[0] / kMPa);
  EXPECT_NEAR(-y.tau[2] / kMPa, 110.42, 110.42 * 0.02);
  EXPECT_NEAR(-y.tau[0] / kMPa, 19.49, 19.49 * 0.02);
  // exact: 2 (1 - nu) cos(phi) c / (1 - 2 nu - sin(phi)), to the increment size (1e-6 strain)
  const double exact = 2.0 * 0.85 * std::cos(30 * kDeg) * 15.0 / (1.0 - 0.3 - 0.5);
  EXPECT_NEAR(-y.tau[2] / kMPa, exact, exact * 2e-3);
  for (std::size_t k = first; k < path.size(); ++k) {
    const double sa = -path[k].tau[2] / kMPa, sr = -path[k].tau[0] / kMPa;
    EXPECT_NEAR(sa, 2.0 * 15.0 * std::cos(30 * kDeg) / 0.5 + 3.0 * sr, 1e-7 * sa) << k;
    EXPECT_NEAR(path[k].tau[0], path[k].tau[1], 1e-9 * std::fabs(path[k].tau[0]));
  }
  const double table[3][3] = {{2.98e-3, 110.9, 19.6},
                              {4.46e-3, 163.3, 37.0},
                              {5.99e-3, 218.9, 55.5}};  // Table 3.3, L4586-4594
  for (const auto& row : table) {
    const auto s = at_strain(path, total, -row[0]);
    std::printf("  e_a %.2fe-3: sigma_a %.2f (%.1f)  sigma_r %.2f (%.1f) MPa\n", row[0] * 1e3,
                -s[0] / kMPa, row[1], -s[1] / kMPa, row[2]);
    EXPECT_NEAR(-s[0] / kMPa, row[1], row[1] * 0.02);
    EXPECT_NEAR(-s[1] / kMPa, row[2], row[2] * 0.02);
  }
}

// Thesis 3.2.4: uniaxial strain tension. Yield 18.40 / 3.25 MPa (eq. 3.20), then
// sigma_a = 17.32 + sigma_r / 3 (eq. 3.21) up to the apex c cot(phi) = 25.98 MPa; Table 3.4.
TEST(MohrCoulombUniaxialStrain, TensionReachesApex) {
  const McMaterial mat = thesis_mc();
  const double total = 3.75e-3;
  const auto path = drive_mixed(mat, {{total, 0.0, 3750}}, LateralControl::ZeroStrain);
  std::size_t first = 0;
  while (!path[first].yielded) ++first;
  const MaterialPointStep& y = path[first - 1];
  std::printf("  yield: sigma_a %.3f sigma_r %.3f MPa (thesis 18.40 / 3.25)\n", y.tau[2] / kMPa,
              y.tau[0] / kMPa);
  EXPECT_NEAR(y.tau[2] / kMPa, 18.40, 18.40 * 0.02);
  EXPECT_NEAR(y.tau[0] / kMPa, 3.25, 3.25 * 0.02);
  const double apex = 15.0 / std::tan(30 * kDeg);
  bool at_apex = false;
  for (std::size_t k = first; k < path.size(); ++k) {
    const double sa = path[k].tau[2] / kMPa, sr = path[k].tau[0] / kMPa;
    if (std::fabs(sa - apex) < 1e-9 * apex && std::fabs(sr - apex) < 1e-9 * apex) {
      at_apex = true;
      continue;
    }
    EXPECT_FALSE(at_apex) << "left the apex at " << k;
    EXPECT_NEAR(sa, 2.0 * 15.0 * std::cos(30 * kDeg) / 1.5 + sr / 3.0, 1e-7 * sa) << k;
  }
  EXPECT_TRUE(at_apex);
  // Table 3.4 (L4716-4725). The thesis rounds to 0.1 MPa; the radial stress at the first point
  // (3.8) is 3 % below the exact edge return (3.91; notes sec. 3.5 predict the same), so small
  // values are compared to 2 % of the apex stress, the scale of this test.
  const double table[4][3] = {
      {0.59e-3, 18.6, 3.8}, {2.24e-3, 22.6, 15.8}, {3.00e-3, 24.3, 21.2}, {3.75e-3, 26.0, 26.0}};
  for (const auto& row : table) {
    const auto s = at_strain(path, total, row[0]);
    std::printf("  e_a %.2fe-3: sigma_a %.2f (%.1f)  sigma_r %.2f (%.1f) MPa\n", row[0] * 1e3,
                s[0] / kMPa, row[1], s[1] / kMPa, row[2]);
    EXPECT_NEAR(s[0] / kMPa, row[1], std::max(row[1], apex) * 0.02);
    EXPECT_NEAR(s[1] / kMPa, row[2], std::max(row[2], apex) * 0.02);
  }
  EXPECT_NEAR(path.back().tau[2] / kMPa, 25.98, 25.98 * 0.02);
}

// Every plastic return ends on the surface, never outside any plane, with non-negative
// dissipation, for random trial strains far beyond yield (main plane, both edges and the apex),
// associated and not, with hardening and with softening to a residual cohesion.
TEST(MohrCoulombReturn, LandsOnSurfaceAndDissipates) {
  struct Case {
    double psi, H, residual;
  };
  for (const Case cs :
       {Case{30, 0, 0}, Case{10, 0, 0}, Case{0, 0, 0}, Case{15, 2e9, 0}, Case{15, -2e9, 5e6}}) {
    McMaterial mat = thesis_mc(cs.psi);
    mat.cohesion_hardening_modulus = cs.H;
    mat.residual_cohesion = cs.residual;
    ASSERT_EQ(mohr_coulomb_param_error(mat, mat), "");
    const MohrCoulomb mc = make_mohr_coulomb(mat, mat);
    femdem::test::TrialStrains gen;
    int kinds[4] = {0, 0, 0, 0};  // main, right edge (s2 = s3), left edge (s1 = s2), apex
    for (int n = 0; n < 20000; ++n) {
      const auto e = gen.next(n % 2 ? 3e-3 : 2e-2);
      const double kappa_n = (n % 3) * 1e-3;
      const PrincipalReturn r = mc.return_map(e.data(), kappa_n, 0.0);
      const double t6[6] = {r.tau[0], r.tau[1], r.tau[2], 0, 0, 0};
      const auto s = principal_sorted(t6);
      const double c = mc.cohesion.value(r.kappa);
      const double f = mc_yield(t6, 30.0, c);
      const double scale = std::fabs(s[0]) + std::fabs(s[2]) + c;
      EXPECT_LE(f, 1e-9 * scale);
      double diss = 0.0;
      for (int i = 0; i < 3; ++i) diss += r.tau[i] * (e[i] - r.e_el[i]);
      EXPECT_GE(diss, -1e-12 * scale * 1e-3);
      if (!r.yielded) continue;
      EXPECT_NEAR(f, 0.0, 1e-9 * scale);
      EXPECT_GE(r.kappa, kappa_n);
      const double tol = 1e-8 * scale;
      if (std::fabs(s[0] - s[2]) < tol)
        ++kinds[3];
      else if (std::fabs(s[1] - s[2]) < tol)
        ++kinds[1];
      else if (std::fabs(s[0] - s[1]) < tol)
        ++kinds[2];
      else
        ++kinds[0];
    }
    std::printf("  psi %g H %g: main %d, right edge %d, left edge %d, apex %d\n", cs.psi, cs.H,
                kinds[0], kinds[1], kinds[2], kinds[3]);
    for (int k = 0; k < 4; ++k) EXPECT_GT(kinds[k], 50) << "return type " << k << " not reached";
  }
}

// The return is continuous: trial states along a path that crosses from the main plane into
// each edge region and into the apex region give returned stresses that move by no more than a
// bounded multiple of the trial's own change.
TEST(MohrCoulombReturn, ContinuousAcrossEdgesAndApex) {
  const MohrCoulomb mc = make_mohr_coulomb(thesis_mc(10.0), thesis_mc(10.0));
  auto returned = [&](double t) {
    // a loop in trial space: deviatoric direction turning through all Lode angles at a radius
    // far beyond yield, with the mean strain rising into hydrostatic tension (apex) and back
    const double ang = 2.0 * M_PI * t;
    const double ev = 4e-3 * std::sin(M_PI * t);
    const double d0 = 2e-3 * std::cos(ang), d1 = 2e-3 * std::cos(ang - 2.0 * M_PI / 3.0);
    const double d2 = -d0 - d1;
    const double e[3] = {ev / 3 + d0, ev / 3 + d1, ev / 3 + d2};
    PrincipalReturn r = mc.return_map(e, 0.0, 0.0);
    return std::array<double, 3>{r.tau[0], r.tau[1], r.tau[2]};
  };
  const int n = 200000;
  double worst = 0.0;
  auto prev = returned(0.0);
  for (int k = 1; k <= n; ++k) {
    const auto cur = returned(static_cast<double>(k) / n);
    const double jump = std::max(
        {std::fabs(cur[0] - prev[0]), std::fabs(cur[1] - prev[1]), std::fabs(cur[2] - prev[2])});
    worst = std::max(worst, jump);
    prev = cur;
  }
  // the trial stress moves by at most ~2 (K + 4G/3) |de| per sample (~2.3e4 Pa here)
  std::printf("  largest change of the returned stress between neighbouring trials: %.3g Pa\n",
              worst);
  EXPECT_LT(worst, 1e5);
}

// Objectivity and the finite-strain path: the same principal stretches in rotated axes give the
// same principal stresses, and a uniaxial-strain path through the apex keeps det Cp^-1 finite.
TEST(MohrCoulombFiniteStrain, RotatedAxesGiveSamePrincipalStresses) {
  const MohrCoulomb mc = make_mohr_coulomb(thesis_mc(15.0), thesis_mc(15.0));
  const double e[3] = {-8e-3, 1e-3, 2e-3};
  double F[3][3];
  femdem::test::stretch_in_rotated_axes(e, F);
  GaussPointState s;
  const FiniteStrainResult r = finite_strain_update(F, s, mc, 0.0);
  const PrincipalReturn p = mc.return_map(e, 0.0, 0.0);
  const auto sr = principal_sorted(r.tau);
  std::array<double, 3> sp = {p.tau[0], p.tau[1], p.tau[2]};
  std::sort(sp.begin(), sp.end(), std::greater<>());
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(sr[i], sp[i], 1e-9 * std::fabs(sp[2]));
  EXPECT_TRUE(r.yielded);
  EXPECT_GT(r.dissipation, 0.0);
  EXPECT_GT(s.eps_p, 0.0);
}

// Cohesion softening: in uniaxial strain compression the axial stress at yield falls with the
// cohesion until the residual value is reached, after which the perfectly plastic line of the
// residual cohesion holds.
TEST(MohrCoulombHardening, SofteningReachesResidualCohesion) {
  McMaterial mat = thesis_mc(30.0);
  mat.cohesion_hardening_modulus = -5e9;
  mat.residual_cohesion = 5e6;
  const auto path = drive_mixed(mat, {{-2e-2, 0.0, 4000}}, LateralControl::ZeroStrain);
  const MohrCoulomb mc = make_mohr_coulomb(mat, mat);
  for (const MaterialPointStep& st : path) {
    if (!st.yielded) continue;
    EXPECT_NEAR(mc_yield(st.tau, 30.0, mc.cohesion.value(st.state.kappa)), 0.0,
                1e-8 * std::fabs(st.tau[2]));
  }
  EXPECT_NEAR(mc.cohesion.value(path.back().state.kappa), 5e6, 1.0);
  const double sa = -path.back().tau[2] / kMPa, sr = -path.back().tau[0] / kMPa;
  EXPECT_NEAR(sa, 2.0 * 5.0 * std::cos(30 * kDeg) / 0.5 + 3.0 * sr, 1e-7 * sa);
  std::printf("  final: c %.3f MPa, sigma_a %.2f sigma_r %.2f MPa\n",
              mc.cohesion.value(path.back().state.kappa) / kMPa, sa, sr);
}

// Softening steeper than the return can follow is refused with the key's name in the message.
TEST(MohrCoulombParams, RejectsSnapBackSoftening) {
  McMaterial mat = thesis_mc(30.0);
  mat.cohesion_hardening_modulus = -1e12;
  EXPECT_NE(mohr_coulomb_param_error(mat, mat).find("cohesion_hardening_modulus"),
            std::string::npos);
  mat.cohesion_hardening_modulus = 0.0;
  mat.dilatancy_angle = 40.0;
  EXPECT_NE(mohr_coulomb_param_error(mat, mat).find("dilatancy_angle"), std::string::npos);
}
