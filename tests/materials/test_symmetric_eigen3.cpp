// SPDX-License-Identifier: GPL-3.0-or-later
// symmetric_eigen3 (closed form + Jacobi polish) against Eigen's SelfAdjointEigenSolver::compute()
// on random and adversarial matrices: identity, diag(a, b, b), near-repeated spectra with relative
// splittings 1e-9..1e-15, stretch ratios up to 1e4, rotated and unrotated, b = F F^T from small
// and large deformations. Checked: principal log strains, eigenvalues, reconstruction
// V D V^T = A, orthonormality of V, and the Hencky stress built from the decomposition.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "materials/hencky.hpp"
#include "materials/symmetric_eigen3.hpp"

using namespace femdem;

namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

// worst errors seen, printed at the end of each test
struct Worst {
  double log_near1 = 0.0;   // |0.5 ln l - 0.5 ln l_ref|, all eigenvalues in [1/4, 4]
  double value_norm = 0.0;  // |l - l_ref| / max |l_ref|
  double value_rel = 0.0;   // |l - l_ref| / |l_ref| (informative: bounded by the conditioning)
  double recon = 0.0;       // ||V D V^T - A||_F / ||A||_F
  double ortho = 0.0;       // ||V^T V - I||_F
  double stress = 0.0;      // ||tau - tau_ref||_F / ||tau_ref||_F
  long cases = 0;
  void print(const char* name) const {
    std::printf(
        "[%s] %ld cases: log(near 1) %.2e, value/|A| %.2e, value rel %.2e, recon %.2e, "
        "ortho %.2e, stress %.2e\n",
        name, cases, log_near1, value_norm, value_rel, recon, ortho, stress);
  }
};

void to6(const Mat3& A, double s[6]) {
  s[0] = A(0, 0);
  s[1] = A(1, 1);
  s[2] = A(2, 2);
  s[3] = A(0, 1);
  s[4] = A(1, 2);
  s[5] = A(0, 2);
}

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// Checks one symmetric matrix (scaled by 1/unit before taking norms, so huge and tiny matrices
// are measured without overflow). spd: also compare principal log strains.
void check(const Mat3& A_in, bool spd, Worst& worst, double unit = 1.0) {
  const Mat3 A = 0.5 * (A_in + A_in.transpose());  // both solvers see the same numbers
  double s[6];
  to6(A, s);
  const SymEig3 r = symmetric_eigen3(s);
  Mat3 V;
  Vec3 d;
  for (int i = 0; i < 3; ++i) {
    d[i] = r.value[i];
    for (int k = 0; k < 3; ++k) V(k, i) = r.vector[k][i];
  }
  const Mat3 As = A / unit;
  const Mat3 R = V * (d / unit).asDiagonal() * V.transpose() - As;
  const double recon = R.norm() / As.norm();
  const double ortho = (V.transpose() * V - Mat3::Identity()).norm();
  Eigen::SelfAdjointEigenSolver<Mat3> ref;
  ref.compute(As);
  Vec3 got = d / unit;
  std::sort(got.data(), got.data() + 3);
  const Vec3 want = ref.eigenvalues();
  const double top = want.cwiseAbs().maxCoeff();
  double value_norm = 0.0, value_rel = 0.0, log_err = 0.0;
  bool near1 = true;
  for (int i = 0; i < 3; ++i) {
    const double e = std::fabs(got[i] - want[i]);
    value_norm = std::max(value_norm, e / top);
    value_rel = std::max(value_rel, e / std::fabs(want[i]));
    if (spd)
      log_err = std::max(log_err, std::fabs(0.5 * std::log(got[i]) - 0.5 * std::log(want[i])));
    near1 = near1 && want[i] >= 0.25 && want[i] <= 4.0;
  }
  ASSERT_LE(recon, 4e-15) << A;
  ASSERT_LE(ortho, 4e-15) << A;
  ASSERT_LE(value_norm, 1e-14) << A;
  worst.recon = std::max(worst.recon, recon);
  worst.ortho = std::max(worst.ortho, ortho);
  worst.value_norm = std::max(worst.value_norm, value_norm);
  worst.value_rel = std::max(worst.value_rel, value_rel);
  if (spd && near1 && unit == 1.0) {
    ASSERT_LE(log_err, 2e-15) << A;
    worst.log_near1 = std::max(worst.log_near1, log_err);
  }
  ++worst.cases;
}

// Hencky stress of b from our decomposition against the same law built from Eigen's compute().
double hencky_error(const Mat3& b_in) {
  const Mat3 b = 0.5 * (b_in + b_in.transpose());
  const double lambda = 121.15e9, G = 80.77e9;  // steel
  double s[6];
  to6(b, s);
  const HenckyResult h = hencky_stress(s, lambda, G);
  Eigen::SelfAdjointEigenSolver<Mat3> ref;
  ref.compute(b);
  const Vec3 e = 0.5 * ref.eigenvalues().array().log();
  const Vec3 t = (lambda * e.sum() + 2.0 * G * e.array()).matrix();
  const Mat3 tau_ref = ref.eigenvectors() * t.asDiagonal() * ref.eigenvectors().transpose();
  Mat3 tau;
  tau << h.tau[0], h.tau[3], h.tau[5], h.tau[3], h.tau[1], h.tau[4], h.tau[5], h.tau[4], h.tau[2];
  return (tau - tau_ref).norm() / tau_ref.norm();
}

// Spectrum generators for the adversarial cases: principal stretches squared.
Vec3 near_repeated_spectrum(std::mt19937_64& rng, int kind, double split) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> big(-1.0, 1.0);
  const double a = std::exp(0.3 * big(rng)), b = std::exp(0.3 * big(rng));
  switch (kind) {
    case 0:  // identity (plus splitting)
      return Vec3(1.0, 1.0 + split * u(rng), 1.0 + split * u(rng));
    case 1:  // diag(a, b, b): uniaxial stretch, double eigenvalue
      return Vec3(a, b, b * (1.0 + split * u(rng)));
    case 2:  // near-triple at a
      return Vec3(a, a * (1.0 + split * u(rng)), a * (1.0 + split * u(rng)));
    case 3:  // double eigenvalue below/above a separated one, ratio up to 1e4
    {
      const double ratio = std::pow(10.0, 4.0 * std::fabs(u(rng)));
      return Vec3(ratio, 1.0, 1.0 + split * u(rng)) * (u(rng) > 0 ? 1.0 : 1.0 / ratio);
    }
    default:  // three distinct with large ratios
    {
      const double r1 = std::pow(10.0, 2.0 * std::fabs(u(rng)));
      const double r2 = std::pow(10.0, 2.0 * std::fabs(u(rng)));
      return Vec3(1.0, r1, r1 * r2);
    }
  }
}

}  // namespace

TEST(SymmetricEigen3, ExactlyDiagonalInputIsReturnedExactly) {
  const double in[4][6] = {{2.0, 3.0, 1.0, 0.0, 0.0, 0.0},
                           {1.0, 1.0, 1.0, 0.0, 0.0, 0.0},
                           {1.5, 0.7, 0.7, 0.0, 0.0, 0.0},
                           {-2.0, 0.0, 5.0, 0.0, -0.0, 0.0}};
  for (const auto& s : in) {
    const SymEig3 r = symmetric_eigen3(s);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(r.value[i], s[i]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(r.vector[k][i], k == i ? 1.0 : 0.0);
    }
  }
}

// Two of the three off-diagonals zero: a 2x2 block plus a decoupled eigenvalue.
TEST(SymmetricEigen3, BlockDiagonalInput) {
  Worst w;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    Mat3 A = Mat3::Identity();
    const int o = trial % 3, p = (o + 1) % 3, q = (o + 2) % 3;
    A(o, o) = 1.0 + 0.3 * u(rng);
    A(p, p) = 1.0 + 0.3 * u(rng);
    A(q, q) = (trial % 2) ? A(p, p) : 1.0 + 0.3 * u(rng);
    A(p, q) = A(q, p) = std::pow(10.0, -15.0 * std::fabs(u(rng))) * u(rng);
    check(A, true, w);
  }
  w.print("block diagonal");
}

TEST(SymmetricEigen3, RandomSymmetricMatrices) {
  Worst w;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 30000; ++trial) {
    Mat3 X;
    for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
    const Mat3 A = X + X.transpose();
    check(A, false, w);
  }
  w.print("random symmetric");
}

// b = F F^T with F = R (I + h X): the element kernel's inputs at small and large strain.
TEST(SymmetricEigen3, LeftCauchyGreenTensors) {
  for (double h : {1e-8, 1e-3, 0.3}) {
    Worst w;
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 20000; ++trial) {
      Mat3 X;
      for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
      const Mat3 F = random_rotation(rng) * (Mat3::Identity() + h * X);
      check(F * F.transpose(), true, w);
    }
    char name[64];
    std::snprintf(name, sizeof name, "b = F F^T, h = %g", h);
    w.print(name);
  }
}

TEST(SymmetricEigen3, NearRepeatedAndLargeRatioSpectra) {
  Worst w;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double splits[] = {0.0, 1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-6};
  for (int trial = 0; trial < 45000; ++trial) {
    const double split = splits[trial % 9];
    const Vec3 lam = near_repeated_spectrum(rng, (trial / 9) % 5, split);
    Mat3 A;
    switch ((trial / 45) % 3) {
      case 0:  // rotated
      {
        const Mat3 R = random_rotation(rng);
        A = R * lam.asDiagonal() * R.transpose();
        break;
      }
      case 1:  // unrotated with tiny symmetric perturbation of the entries
      {
        A = lam.asDiagonal();
        const double eps = std::pow(10.0, -9.0 - 6.0 * std::fabs(u(rng))) * lam.maxCoeff();
        for (int i = 0; i < 3; ++i)
          for (int j = i; j < 3; ++j) A(i, j) = A(j, i) = A(i, j) + eps * u(rng);
        break;
      }
      default:  // rotated about a coordinate axis only (structured zeros in the matrix)
      {
        const Mat3 R = Eigen::AngleAxisd(3.0 * u(rng), Vec3::Unit(trial % 3)).toRotationMatrix();
        A = R * lam.asDiagonal() * R.transpose();
        break;
      }
    }
    check(A, lam.minCoeff() > 0, w);
  }
  w.print("near-repeated / large ratio");
}

// Scale invariance, including a subnormal deviatoric part and huge and tiny matrices.
TEST(SymmetricEigen3, ExtremeScales) {
  Worst w;
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double unit : {1e-280, 1e-100, 1e100, 1e280}) {
    for (int trial = 0; trial < 2000; ++trial) {
      Mat3 X;
      for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
      check((X + X.transpose()) * unit, false, w, unit);
    }
  }
  for (double tiny : {1e-200, 1e-305, 1e-310, 4.9e-324}) {
    Mat3 A = Mat3::Identity();
    A(0, 1) = A(1, 0) = tiny;
    A(1, 2) = A(2, 1) = -0.5 * tiny;
    check(A, true, w);
    double s[6];
    to6(A, s);
    const SymEig3 r = symmetric_eigen3(s);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.value[i], 1.0);
  }
  w.print("extreme scales");
}

// The Hencky stress from our decomposition matches the one built from Eigen's compute(), also
// where the principal directions themselves are ill-determined (near-repeated stretches).
// Finite stretches (principal log strains 0.05..0.4 in magnitude): at strain h the stress is only
// determined to about eps / h relative by the rounded b itself, whichever solver is used.
TEST(SymmetricEigen3, HenckyStressNearRepeated) {
  Worst w;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double splits[] = {0.0, 1e-15, 1e-13, 1e-11, 1e-9};
  for (int trial = 0; trial < 20000; ++trial) {
    const double split = splits[trial % 5];
    auto stretch = [&] {
      const double x = u(rng);
      return std::exp(std::copysign(0.05 + 0.35 * std::fabs(x), x));
    };
    const double a = stretch(), b = stretch();
    Vec3 lam;
    switch ((trial / 5) % 3) {
      case 0:
        lam = Vec3(a, b, b * (1.0 + split * u(rng)));
        break;
      case 1:
        lam = Vec3(a, a * (1.0 + split * u(rng)), a * (1.0 + split * u(rng)));
        break;
      default:
        lam = Vec3(a * a, b * (1.0 + split * u(rng)), b);
        break;
    }
    if (trial % 4 == 0 && (trial / 5) % 3 != 1) lam[0] = 1.0;  // one unstretched direction
    const Mat3 R = random_rotation(rng);
    const Mat3 B = R * lam.asDiagonal() * R.transpose();
    const double e = hencky_error(B);
    ASSERT_LE(e, 1e-13) << B;
    w.stress = std::max(w.stress, e);
    ++w.cases;
  }
  w.print("Hencky stress");
}

// The reference Jacobi solver is kept and agrees with the fast one.
TEST(SymmetricEigen3, AgreesWithReferenceJacobi) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5000; ++trial) {
    Mat3 X;
    for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
    const Mat3 F = Mat3::Identity() + 0.2 * X;
    double s[6];
    to6(F * F.transpose(), s);
    const SymEig3 a = symmetric_eigen3(s), b = symmetric_eigen3_jacobi(s);
    double va[3] = {a.value[0], a.value[1], a.value[2]};
    double vb[3] = {b.value[0], b.value[1], b.value[2]};
    std::sort(va, va + 3);
    std::sort(vb, vb + 3);
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(va[i], vb[i], 1e-14);
  }
}

// The cold path (full sweeps, taken only if the closed form left a large off-diagonal) on its own
// diagonalises any scaled symmetric matrix, degenerate or not.
TEST(SymmetricEigen3, FallbackSweepsDiagonalise) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    Mat3 A;
    if (trial % 3 == 0) {
      Mat3 X;
      for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
      A = X + X.transpose();
    } else {
      const Mat3 R = random_rotation(rng);
      const Vec3 lam(1.0, trial % 3 == 1 ? 1.0 : 1.0 + 1e-13 * u(rng), -0.5);
      A = R * lam.asDiagonal() * R.transpose();
      A = 0.5 * (A + A.transpose());
    }
    double g[3][3], v[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        g[i][j] = A(i, j);
        v[i][j] = i == j ? 1.0 : 0.0;
      }
    detail::jacobi_sweeps(g, v);
    Mat3 V, D = Mat3::Zero();
    for (int i = 0; i < 3; ++i) {
      D(i, i) = g[i][i];
      for (int k = 0; k < 3; ++k) V(k, i) = v[k][i];
    }
    ASSERT_LE(g[0][1] * g[0][1] + g[0][2] * g[0][2] + g[1][2] * g[1][2], 1e-40);
    ASSERT_LE((V * D * V.transpose() - A).norm(), 4e-15 * A.norm());
    ASSERT_LE((V.transpose() * V - Mat3::Identity()).norm(), 4e-15);
  }
}

// The closed-form largest eigenvalue (used for the largest principal stress output) against
// Eigen's solver: random matrices, near-repeated and exactly repeated spectra, diagonal input.
TEST(SymmetricEigen3, LargestEigenvalueMatchesTheSolver) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  auto check_one = [&](const Mat3& A) {
    double s[6];
    to6(A, s);
    const Eigen::SelfAdjointEigenSolver<Mat3> ref(A);
    const double scale = std::max(1.0, ref.eigenvalues().cwiseAbs().maxCoeff());
    const double err = std::fabs(largest_eigenvalue3(s) - ref.eigenvalues().maxCoeff()) / scale;
    worst = std::max(worst, err);
  };
  for (int trial = 0; trial < 20000; ++trial) {
    Mat3 X;
    for (int i = 0; i < 9; ++i) X.data()[i] = u(rng);
    check_one(X + X.transpose());
    // uniaxial, equibiaxial and hydrostatic states, rotated: two or three equal eigenvalues
    const Mat3 R = random_rotation(rng);
    const double a = u(rng), b = u(rng);
    check_one(R * Eigen::Vector3d(a, b, b).asDiagonal() * R.transpose());
    check_one(R * Eigen::Vector3d(a, a, a).asDiagonal() * R.transpose());
    check_one(R * Eigen::Vector3d(a, a * (1 + 1e-12), b).asDiagonal() * R.transpose());
  }
  check_one(Eigen::Vector3d(-3.0, 2.0, 1.0).asDiagonal().toDenseMatrix());
  std::printf("largest eigenvalue: worst error / |A| %.2e\n", worst);
  EXPECT_LT(worst, 1e-7);
}
