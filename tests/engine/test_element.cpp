// SPDX-License-Identifier: GPL-3.0-or-later
// Element and kinematics tests (VALIDATION.md section 1): patch tests, rigid rotation,
// mass = rho V, the eigen-solver against Eigen's iterative solver, and the stable-step bound.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "engine/element_kernel.hpp"
#include "engine/simulation.hpp"
#include "materials/symmetric_eigen3.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

MaterialParams steel() {
  MaterialParams p;
  p.name = "steel";
  p.density = 7850.0;
  p.youngs_modulus = 210e9;
  p.poisson_ratio = 0.3;
  return p;
}

ModelSpec one_body(Tet10Mesh mesh, MaterialParams mat = steel()) {
  ModelSpec s;
  s.simulation.end_time = 1.0;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "box";
  b.material = 0;
  b.mesh = std::move(mesh);
  s.bodies.push_back(std::move(b));
  return s;
}

// Hencky Kirchhoff stress by an independent route: Eigen's matrix logarithm of b.
Eigen::Matrix3d reference_kirchhoff(const Eigen::Matrix3d& F, double lambda, double G) {
  const Eigen::Matrix3d b = F * F.transpose();
  const Eigen::Matrix3d eps = 0.5 * b.log();
  return lambda * eps.trace() * Eigen::Matrix3d::Identity() + 2.0 * G * eps;
}

Eigen::Matrix3d rotation(double angle_rad, Vec3 axis) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
}

// Apply x = F0 X + c to the model and evaluate every element.
struct Evaluated {
  std::vector<double> force;   // 3 per node
  std::vector<double> stress;  // 24 per element
  double energy = 0.0;
};

Evaluated evaluate(const Model& m, const Eigen::Matrix3d& F0, FbarMode mode = FbarMode::Off) {
  Evaluated out;
  out.force.assign(3 * m.node_count, 0.0);
  out.stress.assign(24 * m.element_count, 0.0);
  const MaterialParams& mat = m.materials[0];
  for (int e = 0; e < m.element_count; ++e) {
    double xe[30], fe[30];
    for (int a = 0; a < 10; ++a) {
      const int n = m.conn[e][a];
      const Vec3 x = F0 * Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]) + Vec3(0.3, -0.2, 0.1);
      for (int k = 0; k < 3; ++k) xe[3 * a + k] = x[k];
    }
    GaussPointState st[4];
    const auto r =
        tet10_internal_forces(xe, &m.dNdX[120 * e], &m.gauss_weight[4 * e],
                              ElasticModel{mat.lame_lambda(), mat.shear_modulus()}, mode, st, 0.0,
                              fe, &out.stress[24 * e], nullptr, nullptr, m.subtet_volume0[e]);
    out.energy += r.energy;
    for (int a = 0; a < 10; ++a)
      for (int k = 0; k < 3; ++k) out.force[3 * m.conn[e][a] + k] += fe[3 * a + k];
  }
  return out;
}

}  // namespace

TEST(Tet10, MassSumsToDensityTimesVolume) {
  const Vec3 size(0.3, 0.2, 0.5);
  const Model m = build_model(one_body(test::kuhn_box(3, 2, 4, size, 0.2)));
  double total = 0.0;
  for (double mi : m.mass) {
    EXPECT_GT(mi, 0.0);  // HRZ: no negative or zero corner masses
    total += mi;
  }
  const double exact = 7850.0 * size.prod();
  EXPECT_NEAR(total, exact, 1e-12 * exact);
  EXPECT_NEAR(m.bodies[0].reference_volume, size.prod(), 1e-14);
}

// Patch test: any homogeneous deformation is reproduced exactly: uniform stress equal to the
// analytic Hencky stress, zero force on interior nodes, on a distorted mesh.
class PatchTest : public ::testing::TestWithParam<FbarMode> {};

TEST_P(PatchTest, HomogeneousFiniteDeformation) {
  const Model m = build_model(one_body(test::kuhn_box(3, 3, 3, Vec3(1, 1, 1), 0.25)));
  const MaterialParams mat = m.materials[0];
  Eigen::Matrix3d F0;
  F0 << 1.08, 0.05, -0.02, 0.03, 0.93, 0.04, -0.01, 0.06, 1.02;
  F0 = rotation(0.7, Vec3(1, 2, 3)) * F0;
  const Evaluated ev = evaluate(m, F0, GetParam());
  const Eigen::Matrix3d sigma_ref =
      reference_kirchhoff(F0, mat.lame_lambda(), mat.shear_modulus()) / F0.determinant();
  const double scale = sigma_ref.norm();
  for (int e = 0; e < m.element_count; ++e)
    for (int g = 0; g < 4; ++g) {
      const double* s = &ev.stress[24 * e + 6 * g];
      const double got[6] = {s[0], s[1], s[2], s[3], s[4], s[5]};
      const double want[6] = {sigma_ref(0, 0), sigma_ref(1, 1), sigma_ref(2, 2),
                              sigma_ref(0, 1), sigma_ref(1, 2), sigma_ref(0, 2)};
      for (int k = 0; k < 6; ++k) ASSERT_NEAR(got[k], want[k], 1e-11 * scale);
    }
  // interior nodes: no net force
  double fmax = 0.0, finterior = 0.0;
  for (int n = 0; n < m.node_count; ++n) {
    const Vec3 X(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    const double f = Vec3(ev.force[3 * n], ev.force[3 * n + 1], ev.force[3 * n + 2]).norm();
    fmax = std::max(fmax, f);
    const bool interior = (X.array() > 1e-9).all() && (X.array() < 1 - 1e-9).all();
    if (interior) finterior = std::max(finterior, f);
  }
  EXPECT_LT(finterior, 1e-9 * fmax);
  // boundary forces add up to the traction resultant: zero in total
  Vec3 sum = Vec3::Zero();
  for (int n = 0; n < m.node_count; ++n)
    sum += Vec3(ev.force[3 * n], ev.force[3 * n + 1], ev.force[3 * n + 2]);
  EXPECT_LT(sum.norm(), 1e-9 * fmax);
}

// Every F-bar variant passes the patch test on the assembled mesh (the sub-tet variant spreads
// the pressure differently over an element's nodes, but the sub-tets tile the mesh, so interior
// nodes still balance).
INSTANTIATE_TEST_SUITE_P(Tet10, PatchTest,
                         ::testing::Values(FbarMode::Off, FbarMode::VolumeAverage,
                                           FbarMode::Centroid, FbarMode::SubTet),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// A rigid rotation by 90 degrees, taken in 200 increments, leaves no stress and no energy; a
// stretch followed by the rotation gives the rotated stress (objectivity).
TEST(Tet10, RigidRotationGivesNoStress) {
  const Model m = build_model(one_body(test::kuhn_box(2, 2, 2, Vec3(1, 2, 1), 0.2)));
  const double E = m.materials[0].youngs_modulus;
  for (int i = 1; i <= 200; ++i) {
    const Eigen::Matrix3d R = rotation(0.5 * M_PI * i / 200.0, Vec3(1, 1, 0.3));
    const Evaluated ev = evaluate(m, R);
    double smax = 0.0;
    for (double s : ev.stress) smax = std::max(smax, std::fabs(s));
    ASSERT_LT(smax, 1e-12 * E) << "increment " << i;
    ASSERT_LT(std::fabs(ev.energy), 1e-12 * E);
  }
  Eigen::Matrix3d U;
  U << 1.05, 0.02, 0.0, 0.02, 0.97, 0.01, 0.0, 0.01, 1.01;
  const Eigen::Matrix3d R = rotation(0.5 * M_PI, Vec3(0, 0, 1));
  const Evaluated a = evaluate(m, U), b = evaluate(m, R * U);
  auto mat = [](const double* s) {
    Eigen::Matrix3d S;
    S << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    return S;
  };
  const Eigen::Matrix3d Sa = mat(&a.stress[0]), Sb = mat(&b.stress[0]);
  EXPECT_LT((R * Sa * R.transpose() - Sb).norm(), 1e-12 * Sa.norm());
  EXPECT_NEAR(a.energy, b.energy, 1e-12 * a.energy);
}

// The Jacobi eigen-solver against Eigen's iterative solver, including exactly and nearly
// repeated eigenvalues (where closed-form cubic solvers lose accuracy).
TEST(SymmetricEigen3, MatchesEigenIncludingRepeatedEigenvalues) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Eigen::Vector3d lam(1.0 + 0.3 * u(rng), 1.0 + 0.3 * u(rng), 1.0 + 0.3 * u(rng));
    if (trial % 3 == 1) lam[1] = lam[0] * (1.0 + 1e-9 * u(rng));            // nearly double
    if (trial % 3 == 2) lam[1] = lam[2] = lam[0] * (1.0 + 1e-12 * u(rng));  // nearly triple
    const Eigen::Matrix3d Q =
        Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    const Eigen::Matrix3d A = Q * lam.asDiagonal() * Q.transpose();
    const double s[6] = {A(0, 0), A(1, 1), A(2, 2), A(0, 1), A(1, 2), A(0, 2)};
    const SymEig3 r = symmetric_eigen3(s);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ref(A);
    Eigen::Vector3d got(r.value[0], r.value[1], r.value[2]);
    std::sort(got.data(), got.data() + 3);
    // log strains, the quantity the materials use, to round-off
    for (int i = 0; i < 3; ++i)
      ASSERT_NEAR(0.5 * std::log(got[i]), 0.5 * std::log(ref.eigenvalues()[i]), 2e-15);
    // reconstruction A = V diag V^T and orthonormal V
    Eigen::Matrix3d V;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) V(k, i) = r.vector[k][i];
    const Eigen::Matrix3d D = Eigen::Vector3d(r.value[0], r.value[1], r.value[2]).asDiagonal();
    ASSERT_LT((V * D * V.transpose() - A).norm(), 4e-15 * A.norm());
    ASSERT_LT((V.transpose() * V - Eigen::Matrix3d::Identity()).norm(), 4e-15);
    ++cases;
  }
  EXPECT_EQ(cases, 3000);
  const double diag[6] = {2.0, 3.0, 1.0, 0.0, 0.0, 0.0};  // already diagonal
  const SymEig3 r = symmetric_eigen3(diag);
  EXPECT_EQ(r.value[0], 2.0);
  EXPECT_EQ(r.value[1], 3.0);
  EXPECT_EQ(r.value[2], 1.0);
}

// The per-element frequency bound is an upper bound of the assembled mesh's highest frequency
// (power iteration on M^-1 K of the whole mesh), and not a loose one.
TEST(Tet10, ElementFrequencyBoundsTheMesh) {
  const Model m = build_model(one_body(test::kuhn_box(3, 3, 3, Vec3(1, 1, 1), 0.2)));
  const MaterialParams& mat = m.materials[0];
  const double cd = std::sqrt(mat.p_wave_modulus() / mat.density);
  double omega_bound = 0.0;
  for (int e = 0; e < m.element_count; ++e) {
    double xe[30];
    for (int a = 0; a < 10; ++a)
      for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.X[3 * m.conn[e][a] + k];
    omega_bound = std::max(omega_bound, m.frequency_factor[e] * cd / corner_tet_min_altitude(xe));
  }
  // linearised K u by central differences of the internal force about the reference state
  const int nd = 3 * m.node_count;
  auto Ku = [&](const std::vector<double>& u) {
    std::vector<double> f(nd, 0.0);
    const double eps = 1e-7;
    for (int e = 0; e < m.element_count; ++e) {
      double xp[30], xm[30], fp[30], fm[30], sig[24];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) {
          const int i = 3 * m.conn[e][a] + k;
          xp[3 * a + k] = m.X[i] + eps * u[i];
          xm[3 * a + k] = m.X[i] - eps * u[i];
        }
      tet10_elastic_forces(xp, &m.dNdX[120 * e], &m.gauss_weight[4 * e], mat.lame_lambda(),
                           mat.shear_modulus(), fp, sig);
      tet10_elastic_forces(xm, &m.dNdX[120 * e], &m.gauss_weight[4 * e], mat.lame_lambda(),
                           mat.shear_modulus(), fm, sig);
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k)
          f[3 * m.conn[e][a] + k] += (fp[3 * a + k] - fm[3 * a + k]) / (2 * eps);
    }
    return f;
  };
  // power iteration on M^-1/2 K M^-1/2
  std::vector<double> y(nd);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& yi : y) yi = u(rng);
  double lambda = 0.0;
  for (int it = 0; it < 400; ++it) {
    std::vector<double> z(nd);
    for (int i = 0; i < nd; ++i) z[i] = y[i] / std::sqrt(m.mass[i / 3]);
    std::vector<double> kz = Ku(z);
    double norm = 0.0, dot = 0.0;
    for (int i = 0; i < nd; ++i) {
      kz[i] /= std::sqrt(m.mass[i / 3]);
      dot += kz[i] * y[i];
      norm += kz[i] * kz[i];
    }
    lambda = dot;
    norm = std::sqrt(norm);
    for (int i = 0; i < nd; ++i) y[i] = kz[i] / norm;
  }
  const double omega_mesh = std::sqrt(lambda);
  EXPECT_LE(omega_mesh, omega_bound * (1 + 1e-6));
  EXPECT_GT(omega_mesh, 0.5 * omega_bound) << "bound too loose to be useful";
  RecordProperty("omega_mesh_over_bound", std::to_string(omega_mesh / omega_bound));
  std::printf("omega_mesh / omega_bound = %.4f\n", omega_mesh / omega_bound);
}

// F-bar (both variants): under a homogeneous deformation J is the same at every Gauss point, so
// F-bar changes nothing; and its forces are the exact gradient of its energy (the energy
// balance relies on it): central differences of the energy against the forces.
TEST(Tet10, FbarIsExactUnderHomogeneousDeformationAndConservative) {
  const Model m = build_model(one_body(test::kuhn_box(1, 1, 1, Vec3(1, 1, 1))));
  const MaterialParams& mat = m.materials[0];
  const ElasticModel elastic{mat.lame_lambda(), mat.shear_modulus()};
  const int e = 2;
  const double* dN = &m.dNdX[120 * e];
  const double* w = &m.gauss_weight[4 * e];
  Eigen::Matrix3d F0;
  F0 << 1.05, 0.02, 0.01, -0.03, 0.96, 0.02, 0.01, 0.04, 1.03;
  double xe[30];
  for (int a = 0; a < 10; ++a) {
    const int n = m.conn[e][a];
    const Vec3 x = F0 * Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    for (int k = 0; k < 3; ++k) xe[3 * a + k] = x[k];
  }
  double f_off[30], s_off[24];
  GaussPointState st[4];
  tet10_internal_forces(xe, dN, w, elastic, FbarMode::Off, st, 0.0, f_off, s_off);
  const double V0 = m.subtet_volume0[e];
  for (FbarMode mode : {FbarMode::VolumeAverage, FbarMode::Centroid, FbarMode::SubTet}) {
    double f[30], s[24];
    GaussPointState st2[4];
    tet10_internal_forces(xe, dN, w, elastic, mode, st2, 0.0, f, s, nullptr, nullptr, V0);
    if (mode != FbarMode::SubTet) {
      for (int i = 0; i < 30; ++i) EXPECT_NEAR(f[i], f_off[i], 1e-12 * 210e9);
    } else {
      // the pressure acts through the sub-tet volumes: other nodal forces for the same uniform
      // stress (corners carry pressure too), but still self-equilibrated
      for (int k = 0; k < 3; ++k) {
        double sum = 0.0;
        for (int a = 0; a < 10; ++a) sum += f[3 * a + k];
        EXPECT_NEAR(sum, 0.0, 1e-6);
      }
    }
    for (int i = 0; i < 24; ++i) EXPECT_NEAR(s[i], s_off[i], 1e-12 * 210e9);
    // a non-homogeneous state: forces = dW/dx
    double y[30];
    for (int i = 0; i < 30; ++i) y[i] = xe[i] + 0.01 * std::sin(1.7 * i + 0.3);
    double fy[30], sy[24];
    tet10_internal_forces(y, dN, w, elastic, mode, st2, 0.0, fy, sy, nullptr, nullptr, V0);
    double fmax = 0.0;
    for (int i = 0; i < 30; ++i) fmax = std::max(fmax, std::fabs(fy[i]));
    for (int i = 0; i < 30; ++i) {
      const double h = 1e-6;
      double yp[30], ym[30], ft[30], st_[24];
      std::copy(y, y + 30, yp);
      std::copy(y, y + 30, ym);
      yp[i] += h;
      ym[i] -= h;
      const double Wp =
          tet10_internal_forces(yp, dN, w, elastic, mode, st2, 0.0, ft, st_, nullptr, nullptr, V0)
              .energy;
      const double Wm =
          tet10_internal_forces(ym, dN, w, elastic, mode, st2, 0.0, ft, st_, nullptr, nullptr, V0)
              .energy;
      EXPECT_NEAR((Wp - Wm) / (2 * h), fy[i], 2e-6 * fmax)
          << "dof " << i << " mode " << to_string(mode);
    }
  }
}
