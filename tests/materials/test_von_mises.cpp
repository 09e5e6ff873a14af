// SPDX-License-Identifier: GPL-3.0-or-later
// von Mises at finite strain, material point level (VALIDATION.md section 2; thesis ch. 3 tests
// 3.2.1a/b, 3.2.2, 3.2.6; notes in reference/seed002-part1.md sections 3.1-3.3 and 3.7).
//
// Which stress is compared: the thesis' numbers are small-strain. The driver prescribes the
// axial LOG strain (stretch = exp(e)) and the Hencky law makes the Kirchhoff stress tau exactly
// the small-strain stress of the log strain while the principal axes stay fixed, so tau is
// compared with the thesis (tolerance 0.5 %, and with the closed forms to 1e-9). The Cauchy stress
// tau / J differs from it by the volume change J = exp(tr e) (at most 0.33 %, in uniaxial strain at
// 3.25e-3); it is also checked within the 0.5 % band where the thesis gives a number.
// Sign: tension positive here, compression positive in the thesis.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "materials/finite_strain_update.hpp"
#include "materials/hencky.hpp"
#include "materials/material_point.hpp"
#include "materials/von_mises.hpp"
#include "support/test_material.hpp"

using namespace femdem;

namespace {

constexpr double kMPa = 1e6;

// Table 3.1 of the thesis: E = 35 GPa, nu = 0.3, sigma_y = 35 MPa.
using VmMaterial = TestMaterial<VonMisesParams>;

VmMaterial table31(double H = 0.0) {
  VmMaterial p;
  p.name = "vm";
  p.density = 2500.0;
  p.youngs_modulus = 35e9;
  p.poisson_ratio = 0.3;
  p.yield_stress = 35e6;
  p.hardening_modulus = H;
  return p;
}

Eigen::Matrix3d sym(const double t[6]) {
  Eigen::Matrix3d m;
  m << t[0], t[3], t[5], t[3], t[1], t[4], t[5], t[4], t[2];
  return m;
}

Eigen::Matrix3d dev(const Eigen::Matrix3d& t) {
  return t - t.trace() / 3.0 * Eigen::Matrix3d::Identity();
}

// von Mises equivalent stress sqrt(3/2 s:s)
double q_of(const double t[6]) {
  const Eigen::Matrix3d s = dev(sym(t));
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

// Lode angle (thesis eq. 3.25) in degrees: cos 3 theta = (3 sqrt3 / 2) J3 / J2^(3/2).
double lode_deg(const double t[6]) {
  const Eigen::Matrix3d s = dev(sym(t));
  const double J2 = 0.5 * s.cwiseProduct(s).sum();
  const double J3 = s.determinant();
  const double c = std::clamp(1.5 * std::sqrt(3.0) * J3 / std::pow(J2, 1.5), -1.0, 1.0);
  return std::acos(c) / 3.0 * 180.0 / M_PI;
}

double det_sym(const double t[6]) {
  return sym(t).determinant();
}

// Checks every von Mises path must pass: each plastic increment ends on the yield surface
// (Kirchhoff q = sigma_y(eps_p)), each dissipation increment is >= 0, and eps_p never decreases.
void check_path_invariants(const VonMises& vm, const std::vector<MaterialPointStep>& path,
                           double tol = 1e-10) {
  double prev_d = 0.0, prev_ep = 0.0;
  int plastic = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const MaterialPointStep& st = path[k];
    double H;
    const double sy = vm.flow_stress(st.eps_p, &H);
    const double q = q_of(st.tau);
    if (st.yielded) {
      ++plastic;
      EXPECT_NEAR(q, sy, tol * std::fmax(sy, vm.G * 1e-6)) << "plastic step " << k;
    } else {
      EXPECT_LE(q, sy * (1.0 + 1e-11) + 1e-6) << "elastic step " << k << " outside the surface";
    }
    EXPECT_GE(st.dissipation - prev_d, 0.0) << "negative dissipation at step " << k;
    EXPECT_GE(st.eps_p, prev_ep) << "step " << k;
    prev_d = st.dissipation;
    prev_ep = st.eps_p;
  }
  EXPECT_GT(plastic, 0) << "the path never yielded: the checks above were vacuous";
}

// Last increment of each segment (the values at the targets).
std::vector<MaterialPointStep> segment_ends(const std::vector<MaterialPointStep>& p) {
  std::vector<MaterialPointStep> out;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (k + 1 == p.size() || p[k + 1].segment != p[k].segment) out.push_back(p[k]);
  return out;
}

// Thesis Table 3.2: cumulative axial strain 3.25e-3 -> -3.25e-3 -> 7e-3 (compression positive),
// 1e-5 per increment. Returned as tension-positive log strains.
std::vector<MixedTarget> cyclic_targets() {
  return {{-3.25e-3, 0.0, 325}, {3.25e-3, 0.0, 650}, {-7e-3, 0.0, 1025}};
}

// 1-D bilinear closed form (thesis eqs 3.3-3.6) for the same cycle: stress at each target,
// compression positive. Yield stress grows with the accumulated plastic strain (isotropic).
std::vector<double> bilinear_cycle(double E, double sy0, double H, const std::vector<double>& eps) {
  std::vector<double> out;
  double sigma = 0.0, e = 0.0, ep_bar = 0.0;
  for (double target : eps) {
    const double de = target - e;
    const double trial = sigma + E * de;
    const double sy = sy0 + H * ep_bar;
    if (std::fabs(trial) > sy) {
      const double dg = (std::fabs(trial) - sy) / (E + H);
      ep_bar += dg;
      sigma = std::copysign(sy + H * dg, trial);
    } else {
      sigma = trial;
    }
    e = target;
    out.push_back(sigma);
  }
  return out;
}

}  // namespace

// Thesis 3.2.1a (VALIDATION.md 2): perfectly plastic plateaus +-35 MPa, yield strain 1e-3.
TEST(VonMisesUniaxialStress, PerfectlyPlasticPlateaus) {
  const VmMaterial mat = table31();
  const auto path = drive_mixed(mat, cyclic_targets(), LateralControl::ZeroStress);
  check_path_invariants(make_von_mises(mat, mat), path);
  const auto ends = segment_ends(path);
  ASSERT_EQ(ends.size(), 3u);
  const double expect[3] = {35.0, -35.0, 35.0};  // compression positive
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(-ends[i].tau[2] / kMPa, expect[i], 35.0 * 1e-9) << "target " << i;
    EXPECT_NEAR(-ends[i].sigma[2] / kMPa, expect[i], 35.0 * 5e-3) << "Cauchy, target " << i;
    EXPECT_NEAR(ends[i].tau[0], 0.0, 1e-9 * 35e6);  // lateral stress held at zero
    EXPECT_NEAR(ends[i].tau[1], 0.0, 1e-9 * 35e6);
  }
  // Yield at the axial strain 1e-3 (increment 100 is exactly on the surface, 101 is plastic).
  EXPECT_FALSE(path[99].yielded);
  EXPECT_NEAR(-path[99].tau[2], 35e6, 35e6 * 1e-9);
  EXPECT_TRUE(path[100].yielded);
  // Plastic strain per segment: 2.25e-3, then 4.5e-3 (the thesis prints -1.25e-3 for step 2: a
  // misprint, seed002-part1.md 3.1), then 8.25e-3; the plastic work is 35 MPa times their sum.
  EXPECT_NEAR(ends[0].eps_p, 2.25e-3, 1e-12);
  EXPECT_NEAR(ends[1].eps_p - ends[0].eps_p, 4.5e-3, 1e-12);
  EXPECT_NEAR(ends[2].eps_p - ends[1].eps_p, 8.25e-3, 1e-12);
  EXPECT_NEAR(ends[2].dissipation, 35e6 * 15e-3, 35e6 * 15e-3 * 1e-9);
}

// Thesis 3.2.1b (VALIDATION.md 2): H = 3 GPa (the text says 3 MPa; eq. 3.4 uses 3e3 MPa).
TEST(VonMisesUniaxialStress, LinearHardeningCycle) {
  const VmMaterial mat = table31(3e9);
  const auto path = drive_mixed(mat, cyclic_targets(), LateralControl::ZeroStress);
  check_path_invariants(make_von_mises(mat, mat), path);
  const auto ends = segment_ends(path);
  ASSERT_EQ(ends.size(), 3u);
  const double thesis[3] = {41.22, -52.67, 72.67};  // thesis L4207, L4235-4240
  const std::vector<double> closed = bilinear_cycle(35e9, 35e6, 3e9, {3.25e-3, -3.25e-3, 7e-3});
  for (int i = 0; i < 3; ++i) {
    const double tau = -ends[i].tau[2] / kMPa, sigma = -ends[i].sigma[2] / kMPa;
    std::printf("  target %d: tau %.4f  sigma %.4f  closed form %.4f  thesis %.2f MPa\n", i, tau,
                sigma, closed[i] / kMPa, thesis[i]);
    EXPECT_NEAR(tau, thesis[i], 5e-3 * std::fabs(thesis[i]));
    EXPECT_NEAR(sigma, thesis[i], 5e-3 * std::fabs(thesis[i]));
    EXPECT_NEAR(tau, closed[i] / kMPa, 1e-9 * std::fabs(thesis[i]));
  }
}

// Thesis 3.2.2 (VALIDATION.md 2): uniaxial strain compression to 3.25e-3.
TEST(VonMisesUniaxialStrain, YieldPointAndSlope) {
  const VmMaterial mat = table31();
  const auto path = drive_mixed(mat, {{-3.25e-3, 0.0, 325}}, LateralControl::ZeroStrain);
  check_path_invariants(make_von_mises(mat, mat), path);
  // increment 130 is e_a = 1.3e-3: on the surface, not yet plastic; 131 is plastic
  const MaterialPointStep& y = path[129];
  EXPECT_FALSE(y.yielded);
  EXPECT_TRUE(path[130].yielded);
  std::printf("  yield: sigma_a %.4f sigma_r %.4f MPa (61.25 / 26.25)\n", -y.tau[2] / kMPa,
              -y.tau[0] / kMPa);
  EXPECT_NEAR(-y.tau[2] / kMPa, 61.25, 61.25 * 5e-3);  // thesis eq. 3.11
  EXPECT_NEAR(-y.tau[0] / kMPa, 26.25, 26.25 * 5e-3);  // thesis L4454-4461
  EXPECT_NEAR(-y.tau[2] / kMPa, 61.25, 1e-7);          // exact: (1-nu)/(1-2nu) sigma_y
  const MaterialPointStep& f = path.back();
  const double slope = (path.back().tau[2] - path[199].tau[2]) / (-3.25e-3 + 2e-3);
  std::printf("  final: tau_a %.4f sigma_a %.4f tau_r %.4f MPa, slope %.4f GPa\n", -f.tau[2] / kMPa,
              -f.sigma[2] / kMPa, -f.tau[0] / kMPa, slope / 1e9);
  EXPECT_NEAR(-f.tau[2] / kMPa, 118.1, 118.1 * 5e-3);    // thesis eq. 3.13
  EXPECT_NEAR(-f.sigma[2] / kMPa, 118.1, 118.1 * 5e-3);  // Cauchy: 0.33 % above tau
  EXPECT_NEAR(-f.tau[0] / kMPa, 83.1, 83.1 * 5e-3);      // 118.1 - 35 (notes, derived)
  EXPECT_NEAR(slope / 1e9, 29.17, 29.17 * 5e-3);         // K = E / (3 (1 - 2 nu))
  EXPECT_NEAR(slope, 35e9 / (3.0 * 0.4), 1.0);
}

// Thesis 3.2.6 (VALIDATION.md 2): compression past yield, then compression + shear. The
// deviatoric radius sqrt(2 J2) stays sqrt(2/3) sigma_y = 28.58 MPa while the Lode angle leaves 60
// degrees (the return goes along a new radial direction).
TEST(VonMisesMixed, CompressionThenShearStaysOnCircle) {
  const VmMaterial mat = table31();
  const VonMises vm = make_von_mises(mat, mat);
  const auto path =
      drive_mixed(mat, {{-2e-3, 0.0, 200}, {-3e-3, 1e-2, 200}}, LateralControl::ZeroStress);
  check_path_invariants(vm, path);
  const double radius = std::sqrt(2.0 / 3.0) * 35e6;
  EXPECT_NEAR(radius / kMPa, 28.58, 28.58 * 5e-3);
  double max_theta_change = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const MaterialPointStep& st = path[k];
    if (!st.yielded) continue;
    const Eigen::Matrix3d s = dev(sym(st.tau));
    const double rho = std::sqrt(s.cwiseProduct(s).sum());
    EXPECT_NEAR(rho, radius, radius * 1e-10) << "step " << k;
    if (st.segment == 0) {
      EXPECT_NEAR(lode_deg(st.tau), 60.0, 1e-4) << "compression runs along theta = 60";
    } else {
      max_theta_change = std::fmax(max_theta_change, std::fabs(lode_deg(st.tau) - 60.0));
    }
  }
  std::printf("  radius %.4f MPa, Lode angle moved by %.2f deg under shear\n", radius / kMPa,
              max_theta_change);
  EXPECT_GT(max_theta_change, 5.0);
  EXPECT_GT(std::fabs(path.back().tau[5]), 10e6);  // real shear stress develops
}

// F -> Q F with a large, changing rigid rotation gives tau -> Q tau Q^T, the same eps_p and
// dissipation, to round-off, on a large plastic path.
TEST(VonMisesFiniteStrain, Objectivity) {
  VmMaterial mat = table31(3e9);
  const VonMises vm = make_von_mises(mat, mat);
  const int n = 400;
  std::vector<F3> plain, rotated;
  std::vector<Eigen::Matrix3d> Qs;
  for (int k = 1; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    Eigen::Matrix3d F;
    F << 1.0 + 0.4 * t, 0.3 * std::sin(3 * t), 0.2 * t, 0.1 * t, 1.0 - 0.2 * t, -0.25 * t, 0.05 * t,
        0.15 * t, 1.0 / (1.0 + 0.3 * t);
    const Eigen::Matrix3d Q =
        Eigen::AngleAxisd(4.0 * t, Eigen::Vector3d(1.0, -2.0, 0.7).normalized()).toRotationMatrix();
    const Eigen::Matrix3d QF = Q * F;
    F3 a, b;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        a.m[i][j] = F(i, j);
        b.m[i][j] = QF(i, j);
      }
    plain.push_back(a);
    rotated.push_back(b);
    Qs.push_back(Q);
  }
  const auto p = drive_deformation(vm, plain);
  const auto r = drive_deformation(vm, rotated);
  check_path_invariants(vm, p);
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix3d expect = Qs[k] * sym(p[k].tau) * Qs[k].transpose();
    const double scale = sym(p[k].tau).norm();
    const double err = (sym(r[k].tau) - expect).norm() / scale;
    worst = std::fmax(worst, err);
    EXPECT_LT(err, 1e-11) << "step " << k;
    EXPECT_NEAR(r[k].eps_p, p[k].eps_p, 1e-12 * (1.0 + p[k].eps_p));
    EXPECT_EQ(r[k].yielded, p[k].yielded);
  }
  std::printf("  worst relative error of the rotated stress: %.2e; final eps_p %.4f\n", worst,
              p.back().eps_p);
  EXPECT_GT(p.back().eps_p, 0.1);
  EXPECT_NEAR(r.back().dissipation, p.back().dissipation, 1e-10 * p.back().dissipation);
}

// Large stretch-and-return cycles with rotations. Elastic (no yield reached, or Hencky):
// back at F = I the stress is exactly zero. Plastic: every plastic step on the surface, and the
// plastic flow keeps det Cp^-1 = 1 to 1e-12 through the whole history.
TEST(VonMisesFiniteStrain, StretchAndReturnCycles) {
  std::vector<F3> cycle;
  const int n = 200;
  for (int c = 0; c < 3; ++c)
    for (int k = 1; k <= n; ++k) {
      const double t = std::sin(M_PI * k / n);  // 0 -> 1 -> 0
      Eigen::Matrix3d U;
      U << 1.0 + 0.8 * t, 0.5 * t, 0.0, 0.0, 1.0 / (1.0 + 0.8 * t), 0.0, 0.0, 0.0, 1.0 - 0.1 * t;
      const Eigen::Matrix3d Q =
          Eigen::AngleAxisd(2.0 * t * (c + 1), Eigen::Vector3d(0.3, 1.0, 0.2).normalized())
              .toRotationMatrix();
      Eigen::Matrix3d F = Q * U;
      if (k == n) F.setIdentity();  // exactly back at the reference state
      F3 f;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) f.m[i][j] = F(i, j);
      cycle.push_back(f);
    }
  // elastic: Hencky model, and von Mises with a yield stress never reached
  MaterialParams el = table31();
  el.model = ElasticParams{};
  VmMaterial strong = table31();
  strong.yield_stress = 1e15;
  for (const MaterialParams& m : {el, MaterialParams(strong)}) {
    const auto path = drive_deformation(m, cycle);
    for (int c = 0; c < 3; ++c) {
      const MaterialPointStep& st = path[(c + 1) * n - 1];
      for (int i = 0; i < 6; ++i) EXPECT_EQ(st.tau[i], 0.0) << "cycle " << c;
      EXPECT_EQ(st.elastic_energy, 0.0);
      EXPECT_EQ(st.dissipation, 0.0);
    }
    // and the peak stress was large (the cycle is really large)
    EXPECT_GT(q_of(path[n / 2].tau), 1e9);
  }
  // plastic
  const VmMaterial pl = table31(3e9);
  const VonMises vm = make_von_mises(pl, pl);
  const auto path = drive_deformation(vm, cycle);
  check_path_invariants(vm, path);
  double worst = 0.0;
  for (const auto& st : path) worst = std::fmax(worst, std::fabs(det_sym(st.state.Cp_inv) - 1.0));
  std::printf("  plastic cycles: final eps_p %.4f, max |det Cp^-1 - 1| = %.2e\n", path.back().eps_p,
              worst);
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(path.back().eps_p, 0.5);
}

// ElasticModel through finite_strain_update equals hencky_stress on random deformations.
TEST(FiniteStrainUpdate, ElasticModelEqualsHencky) {
  const VmMaterial m = table31();
  const ElasticModel el{m.lame_lambda(), m.shear_modulus()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int trial = 0; trial < 200; ++trial) {
    double F[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F[i][j] = (i == j ? 1.0 : 0.0) + u(rng);
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Fm(&F[0][0]);
    if (Fm.determinant() < 0.2) continue;
    double b[6];
    b[0] = F[0][0] * F[0][0] + F[0][1] * F[0][1] + F[0][2] * F[0][2];
    b[1] = F[1][0] * F[1][0] + F[1][1] * F[1][1] + F[1][2] * F[1][2];
    b[2] = F[2][0] * F[2][0] + F[2][1] * F[2][1] + F[2][2] * F[2][2];
    b[3] = F[0][0] * F[1][0] + F[0][1] * F[1][1] + F[0][2] * F[1][2];
    b[4] = F[1][0] * F[2][0] + F[1][1] * F[2][1] + F[1][2] * F[2][2];
    b[5] = F[0][0] * F[2][0] + F[0][1] * F[2][1] + F[0][2] * F[2][2];
    const HenckyResult h = hencky_stress(b, m.lame_lambda(), m.shear_modulus());
    GaussPointState s;
    const FiniteStrainResult r = finite_strain_update(F, s, el, 1e-6);
    double scale = 0.0;
    for (int i = 0; i < 6; ++i) scale = std::fmax(scale, std::fabs(h.tau[i]));
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(r.tau[i], h.tau[i], 1e-14 * scale);
    EXPECT_NEAR(r.energy, h.energy, 1e-13 * h.energy);
    EXPECT_EQ(r.dissipation, 0.0);
    EXPECT_FALSE(r.yielded);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.Cp_inv[i], 1.0);
  }
}

// A two-point tabulated curve [[0, 35 MPa], [1, 35 MPa + 3 GPa]] is linear hardening H = 3 GPa.
TEST(VonMisesHardening, TwoPointCurveEqualsLinear) {
  const VmMaterial lin = table31(3e9);
  VmMaterial tab = table31();
  tab.hardening = HardeningLaw::Tabulated;
  tab.hardening_curve = {{0.0, 35e6}, {1.0, 35e6 + 3e9}};
  ASSERT_EQ(von_mises_param_error(tab), "");
  const auto a = drive_mixed(lin, cyclic_targets(), LateralControl::ZeroStress);
  const auto b = drive_mixed(tab, cyclic_targets(), LateralControl::ZeroStress);
  check_path_invariants(make_von_mises(tab, tab), b);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(b[k].tau[i], a[k].tau[i], 1e-9 * 35e6) << k;
    EXPECT_NEAR(b[k].eps_p, a[k].eps_p, 1e-13);
  }
}

// Tabulated curve with hardening then softening to zero: the safeguarded Newton return still
// ends every plastic step on the surface, and the stress follows the curve.
TEST(VonMisesHardening, TabulatedSofteningCurve) {
  VmMaterial m = table31();
  m.hardening = HardeningLaw::Tabulated;
  m.hardening_curve = {{0.0, 35e6}, {2e-3, 45e6}, {5e-3, 20e6}, {8e-3, 0.0}};
  ASSERT_EQ(von_mises_param_error(m), "");
  const VonMises vm = make_von_mises(m, m);
  const auto path = drive_mixed(m, {{-1.5e-2, 0.0, 300}}, LateralControl::ZeroStress);
  check_path_invariants(vm, path, 1e-9);
  double peak = 0.0;
  for (const auto& st : path) peak = std::fmax(peak, -st.tau[2]);
  EXPECT_NEAR(peak, 45e6, 0.5e6);             // reaches the curve's peak (up to the increment size)
  EXPECT_NEAR(path.back().tau[2], 0.0, 1.0);  // softened to zero
  // Large single increments that cross several segments at once.
  const auto big = drive_mixed(m, {{-4e-3, 0.0, 1}, {-2e-2, 0.0, 2}}, LateralControl::ZeroStress);
  check_path_invariants(vm, big, 1e-9);
}

// Swift sigma_y = K (eps0 + eps_p)^n, uniaxial stress, monotonic. With n = 1/2 the hand solution
// is a quadratic: tau = K sqrt(eps0 + e - tau/E)  =>  tau^2 + (K^2/E) tau - K^2 (eps0 + e) = 0.
TEST(VonMisesHardening, SwiftAgainstHandValue) {
  VmMaterial m = table31();
  m.youngs_modulus = 200e9;
  m.hardening = HardeningLaw::Swift;
  m.swift_K = 1000e6;
  m.swift_eps0 = 0.01;  // initial yield 100 MPa
  m.swift_n = 0.5;
  ASSERT_EQ(von_mises_param_error(m), "");
  const VonMises vm = make_von_mises(m, m);
  const double e = 0.05, E = 200e9, K = 1000e6;
  const double bq = K * K / E, cq = K * K * (0.01 + e);
  const double hand = 0.5 * (-bq + std::sqrt(bq * bq + 4.0 * cq));  // 242.46 MPa
  for (int incs : {1, 7, 100}) {
    const auto path = drive_mixed(m, {{e, 0.0, incs}}, LateralControl::ZeroStress);
    check_path_invariants(vm, path);
    std::printf("  Swift, %d increments: tau %.6f MPa, hand %.6f MPa\n", incs,
                path.back().tau[2] / kMPa, hand / kMPa);
    EXPECT_NEAR(path.back().tau[2], hand, 1e-9 * hand);
    EXPECT_NEAR(path.back().eps_p, e - hand / E, 1e-12);
  }
}

// Johnson-Cook factor, implicit: the returned q equals sigma_y(eps_p) (1 + C ln(rate / rate0))
// with the rate of this very increment; below the reference rate it has no effect.
TEST(VonMisesHardening, JohnsonCookRateFactor) {
  VmMaterial m = table31(3e9);
  m.jc_C = 0.025;
  m.jc_epsdot0 = 1.0;
  ASSERT_EQ(von_mises_param_error(m), "");
  const VonMises vm = make_von_mises(m, m);
  const VmMaterial slow_params = table31(3e9);
  const double e_trial[3] = {-2e-3, 1e-3, 0.5e-3};
  for (double dt : {1e-6, 1e-3, 1.0, 0.0}) {
    const PrincipalReturn r = vm.return_map(e_trial, 0.0, dt);
    const PrincipalReturn r0 =
        make_von_mises(slow_params, slow_params).return_map(e_trial, 0.0, dt);
    ASSERT_TRUE(r.yielded);
    const double dg = r.kappa;
    const double rate = (dt > 0.0) ? dg / dt : 0.0;
    const double R = 1.0 + 0.025 * std::log(std::fmax(1.0, rate / 1.0));
    double H;
    const double sy = vm.flow_stress(dg, &H) * R;
    const double q = q_of(std::array<double, 6>{r.tau[0], r.tau[1], r.tau[2], 0, 0, 0}.data());
    const double q0 = q_of(std::array<double, 6>{r0.tau[0], r0.tau[1], r0.tau[2], 0, 0, 0}.data());
    std::printf("  dt %g: rate %.3g 1/s, factor %.4f, q %.4f MPa (rate-free %.4f)\n", dt, rate, R,
                q / kMPa, q0 / kMPa);
    EXPECT_NEAR(q, sy, 1e-10 * sy);
    if (rate <= 1.0) {
      EXPECT_NEAR(r.kappa, r0.kappa, 1e-15);
    }
    if (rate > 10.0) {
      EXPECT_GT(q, 1.05 * q0);
    }
  }
}

TEST(VonMisesParams, Validation) {
  VmMaterial m = table31();
  EXPECT_EQ(von_mises_param_error(m), "");
  m.yield_stress = 0.0;
  EXPECT_NE(von_mises_param_error(m).find("yield_stress"), std::string::npos);
  m = table31();
  m.hardening = HardeningLaw::Tabulated;
  EXPECT_NE(von_mises_param_error(m).find("hardening_curve"), std::string::npos);  // empty
  m.hardening_curve = {{0.0, 35e6}, {0.2, 40e6}, {0.1, 50e6}};
  EXPECT_NE(von_mises_param_error(m).find("increase"), std::string::npos);
  m.hardening_curve = {{0.01, 35e6}, {0.2, 40e6}};
  EXPECT_NE(von_mises_param_error(m).find("start"), std::string::npos);
  m.hardening_curve = {{0.0, 35e6}, {0.2, -1.0}};
  EXPECT_NE(von_mises_param_error(m).find("negative"), std::string::npos);
  m = table31();
  m.hardening = HardeningLaw::Swift;
  m.swift_K = 1e9;
  m.swift_n = 0.3;
  EXPECT_NE(von_mises_param_error(m).find("swift_eps0"), std::string::npos);
  m.swift_eps0 = 1e-3;
  EXPECT_EQ(von_mises_param_error(m), "");
  m.jc_C = -1.0;
  EXPECT_NE(von_mises_param_error(m).find("jc_C"), std::string::npos);
  EXPECT_THROW(drive_mixed(m, {{-1e-3, 0.0, 1}}, LateralControl::ZeroStress), MaterialPointError);
}
