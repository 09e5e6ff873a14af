// SPDX-License-Identifier: GPL-3.0-or-later
// The Hencky strain by series (materials/log_strain_series.hpp), used by the elastic update for
// small strains, against strains known exactly: b is built from chosen principal log strains and
// a random rotation (in long double, then rounded), so the reference does not come from the
// code under test or from its eigen route.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "materials/finite_strain_update.hpp"
#include "materials/hencky.hpp"
#include "materials/log_strain_series.hpp"

using namespace femdem;

namespace {

using Mat3L = Eigen::Matrix<long double, 3, 3>;

struct Case {
  double b[6];
  double e[6];  // exact 0.5 ln b, rounded once
};

Case make_case(std::mt19937_64& rng, double strain) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Quaternion<long double> q(n(rng), n(rng), n(rng), n(rng));
  const Mat3L Q = q.normalized().toRotationMatrix();
  Mat3L B = Mat3L::Zero(), E = Mat3L::Zero();
  for (int i = 0; i < 3; ++i) {
    const long double ei = strain * u(rng);
    B += std::exp(2.0L * ei) * Q.col(i) * Q.col(i).transpose();
    E += ei * Q.col(i) * Q.col(i).transpose();
  }
  Case c;
  const int r[6] = {0, 1, 2, 0, 1, 0}, k[6] = {0, 1, 2, 1, 2, 2};
  for (int i = 0; i < 6; ++i) {
    c.b[i] = static_cast<double>(B(r[i], k[i]));
    c.e[i] = static_cast<double>(E(r[i], k[i]));
  }
  return c;
}

double max_abs(const double a[6]) {
  double m = 0.0;
  for (int i = 0; i < 6; ++i) m = std::max(m, std::fabs(a[i]));
  return m;
}

}  // namespace

// Strains from 1e-9 to 5 %: the absolute error is that of rounding b to double, whatever the
// strain (the series' truncation and products add nothing visible).
TEST(LogStrainSeries, RecoversKnownStrainsToRoundOff) {
  std::mt19937_64 rng(11);
  for (const double strain : {1e-9, 1e-6, 1e-4, 1e-3, 1e-2, 3e-2, 5e-2}) {
    double worst = 0.0;
    int used = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Case c = make_case(rng, strain);
      double e[6];
      if (!log_strain_by_series(c.b, e)) continue;
      ++used;
      double err[6];
      for (int i = 0; i < 6; ++i) err[i] = e[i] - c.e[i];
      worst = std::max(worst, max_abs(err));
    }
    std::printf("strain %.0e: %d of 2000 by series, worst absolute error %.2e\n", strain, used,
                worst);
    if (strain <= 3e-2) {
      EXPECT_EQ(used, 2000) << strain;  // |y| <= sqrt(3) 0.03 < 0.06
    }
    EXPECT_GT(used, 0);
    // b's own rounding (half an ulp of 1) alone makes 5.55e-17
    EXPECT_LT(worst, 1e-16) << strain;
  }
}

// Outside its radius the series declines and leaves the strain to the eigen route; so does a b
// for which b + I is not positive definite.
TEST(LogStrainSeries, DeclinesOutsideItsRange) {
  std::mt19937_64 rng(3);
  double e[6] = {7, 7, 7, 7, 7, 7};
  const Case big = make_case(rng, 0.5);
  EXPECT_FALSE(log_strain_by_series(big.b, e));
  const double inverted[6] = {-3.0, -3.0, -3.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(log_strain_by_series(inverted, e));
  const double nan[6] = {NAN, 1.0, 1.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(log_strain_by_series(nan, e));
  for (double v : e) EXPECT_EQ(v, 7.0);
  const double identity[6] = {1, 1, 1, 0, 0, 0};
  ASSERT_TRUE(log_strain_by_series(identity, e));
  for (double v : e) EXPECT_EQ(v, 0.0);
}

// The elastic update takes the series for small strains and the eigen route for large ones: both
// give the Hencky stress, so the switch between them is seamless. Against hencky_stress (always
// the eigen route) on rotated deformations F = R (I + h X): near the switch (h 0.03) the two
// agree to 1e-14; at small strain the eigen route's own error (1e-16 / h) dominates.
TEST(LogStrainSeries, ElasticUpdateEqualsTheEigenRoute) {
  const double lambda = 121.15e9, G = 80.77e9;  // steel
  const ElasticModel model{lambda, G};
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double h : {1e-5, 1e-3, 0.03, 0.2}) {
    double worst = 0.0;
    for (int trial = 0; trial < 500; ++trial) {
      const Eigen::Matrix3d R =
          Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
      Eigen::Matrix3d X;
      for (int k = 0; k < 9; ++k) X.data()[k] = u(rng);
      const Eigen::Matrix3d Fm = R * (Eigen::Matrix3d::Identity() + h * X);
      double F[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F[i][j] = Fm(i, j);
      const Eigen::Matrix3d Bm = Fm * Fm.transpose();
      const double b[6] = {Bm(0, 0), Bm(1, 1), Bm(2, 2), Bm(0, 1), Bm(1, 2), Bm(0, 2)};
      GaussPointState s;
      const FiniteStrainResult r = finite_strain_update(F, s, model, 1e-6);
      const HenckyResult ref = hencky_stress(b, lambda, G);
      double d[6];
      for (int i = 0; i < 6; ++i) d[i] = r.tau[i] - ref.tau[i];
      worst = std::max(worst, max_abs(d) / max_abs(ref.tau));
      EXPECT_NEAR(r.energy, ref.energy, (h < 1e-4 ? 1e-9 : 1e-12) * ref.energy);
      EXPECT_FALSE(r.yielded);
      EXPECT_EQ(r.dissipation, 0.0);
    }
    std::printf("h %.0e: worst |tau - tau_eigen| / |tau| = %.2e\n", h, worst);
    // the eigen route errs by about 1e-16 / h relative (its logarithms of 1 + h)
    EXPECT_LT(worst, 1e-13 + 1e-15 / h) << h;
  }
}
