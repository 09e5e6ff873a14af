// SPDX-License-Identifier: GPL-3.0-or-later
// The assembled stable-step estimate (engine/stable_step/highest_frequency.hpp) and the elastic
// stiffness action it is built on (elements/tet10_elastic_action.hpp), each against a
// computation that does not share its code: the element eigenproblem of
// elements/tet10_frequency.cpp (its own dense K), the internal-force kernel differentiated
// numerically, and a dense eigen-solve of the assembled matrix.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "elements/tet10_elastic_action.hpp"
#include "elements/tet10_frequency.hpp"
#include "engine/simulation.hpp"
#include "engine/stable_step/highest_frequency.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

MaterialParams elastic(double E = 200e9, double nu = 0.3) {
  MaterialParams mat;
  mat.name = "steel";
  mat.density = 7800.0;
  mat.youngs_modulus = E;
  mat.poisson_ratio = nu;
  return mat;
}

ModelSpec box_spec(int nx, int ny, int nz, double jitter) {
  ModelSpec spec;
  spec.materials.push_back(elastic());
  BodySpec b;
  b.name = std::string("box");
  b.material = 0;
  b.mesh = test::kuhn_box(nx, ny, nz, Vec3(1e-2, 1e-2, 1e-2), jitter, 3);
  spec.bodies.push_back(b);
  return spec;
}

// The assembled M^-1/2 K M^-1/2 over the free dofs, column by column through the action.
Eigen::MatrixXd dense_operator(const Model& m, HighestFrequency& hf,
                               const std::vector<ContactSpring>& springs) {
  const std::size_t n = 3 * static_cast<std::size_t>(m.node_count);
  std::vector<double> u(n, 0.0), f(n, 0.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t j = 0; j < n; ++j) {
    if (m.dof_mode[j] != 0) continue;
    std::fill(u.begin(), u.end(), 0.0);
    u[j] = 1.0 / std::sqrt(m.mass[j / 3]);
    hf.apply_stiffness(m, springs, u.data(), f.data());
    for (std::size_t i = 0; i < n; ++i)
      if (m.dof_mode[i] == 0) A(i, j) = f[i] / std::sqrt(m.mass[i / 3]);
  }
  return A;
}

double dense_highest(const Eigen::MatrixXd& A) {
  const Eigen::MatrixXd S = 0.5 * (A + A.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S, Eigen::EigenvaluesOnly);
  return std::sqrt(eig.eigenvalues().maxCoeff());
}

}  // namespace

// One free element: the assembled system is the element, so the estimate must find the
// frequency of the element eigenproblem (its own dense stiffness and HRZ masses).
TEST(HighestFrequency, OneElementMatchesTheElementEigenproblem) {
  ModelSpec spec = box_spec(1, 1, 1, 0.0);
  spec.bodies[0].mesh.elements.resize(1);  // one of the six Kuhn tetrahedra
  Model m = build_model(spec);
  const MaterialParams& mat = m.materials[0];
  const double vol = m.gauss_weight[0] + m.gauss_weight[1] + m.gauss_weight[2] + m.gauss_weight[3];
  const double exact = tet10_max_frequency(m.dNdX.data(), m.gauss_weight.data(), mat.density * vol,
                                           mat.lame_lambda(), mat.shear_modulus());
  HighestFrequency hf(m, 40, 1e-10);
  const FrequencyEstimate est = hf.estimate(m, {});
  EXPECT_TRUE(est.converged);
  EXPECT_NEAR(est.ritz / exact, 1.0, 1e-8);
  EXPECT_GE(est.omega, est.ritz);
  EXPECT_NEAR(est.omega / exact, 1.0, 1e-6);
}

// K(x) u at the reference shape is the derivative of the internal force of the (Hencky) elastic
// element kernel: central differences of the forces at X +- eps u.
TEST(HighestFrequency, ActionIsTheDerivativeOfTheInternalForce) {
  const ModelSpec spec = box_spec(2, 1, 1, 0.0);
  const Model m0 = build_model(spec);
  HighestFrequency hf(m0);
  const std::size_t n = 3 * static_cast<std::size_t>(m0.node_count);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  std::vector<double> u(n), ku(n);
  for (double& a : u) a = r(rng);
  hf.apply_stiffness(m0, {}, u.data(), ku.data());
  const double eps = 1e-9;  // m, against a 5 mm element: strains of 1e-7, where Hencky is linear
  auto forces = [&](double s) {
    Model m = m0;
    for (std::size_t i = 0; i < n; ++i) m.x[i] = m.X[i] + s * eps * u[i];
    Simulation sim(std::move(m));
    return sim.model().f_int;
  };
  const std::vector<double> fp = forces(1.0), fm = forces(-1.0);
  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    err = std::max(err, std::fabs((fp[i] - fm[i]) / (2 * eps) - ku[i]));
    scale = std::max(scale, std::fabs(ku[i]));
  }
  EXPECT_LT(err, 1e-6 * scale);
}

// Elastic stiffness on the current shape: a rigidly rotated element has K(R X) = R K(X) R'.
TEST(HighestFrequency, ActionTurnsWithTheElement) {
  const ModelSpec spec = box_spec(1, 1, 1, 0.0);
  const Model m0 = build_model(spec);
  Model m1 = m0;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  for (std::int32_t a = 0; a < m1.node_count; ++a) {
    const Vec3 p = R * Vec3(m0.X[3 * a], m0.X[3 * a + 1], m0.X[3 * a + 2]);
    for (int k = 0; k < 3; ++k) m1.x[3 * a + k] = p[k];
  }
  HighestFrequency hf(m0);
  const std::size_t n = 3 * static_cast<std::size_t>(m0.node_count);
  std::vector<double> u(n), ru(n), f0(n), f1(n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  for (double& a : u) a = r(rng);
  for (std::int32_t a = 0; a < m0.node_count; ++a) {
    const Vec3 q = R * Vec3(u[3 * a], u[3 * a + 1], u[3 * a + 2]);
    for (int k = 0; k < 3; ++k) ru[3 * a + k] = q[k];
  }
  hf.apply_stiffness(m0, {}, u.data(), f0.data());
  hf.apply_stiffness(m1, {}, ru.data(), f1.data());
  double err = 0.0, scale = 0.0;
  for (std::int32_t a = 0; a < m0.node_count; ++a) {
    const Vec3 q = R * Vec3(f0[3 * a], f0[3 * a + 1], f0[3 * a + 2]);
    for (int k = 0; k < 3; ++k) {
      err = std::max(err, std::fabs(q[k] - f1[3 * a + k]));
      scale = std::max(scale, std::fabs(f1[3 * a + k]));
    }
  }
  EXPECT_LT(err, 1e-12 * scale);
}

// A jittered mesh with a held face, a wall spring and a body-pair spring: Lanczos against the
// dense eigen-solve of the same operator; the estimate on the safe side and within 1 %; and
// the assembled frequency below the element-by-element bound (Rayleigh: the bound is an upper
// bound for lumped masses).
TEST(HighestFrequency, LanczosFindsTheAssembledHighestFrequency) {
  ModelSpec spec = box_spec(3, 3, 2, 0.25);
  Model m = build_model(spec);
  for (std::int32_t a = 0; a < m.node_count; ++a)
    if (m.X[3 * a + 2] < 1e-9)
      for (int k = 0; k < 3; ++k) m.dof_mode[3 * a + k] = 1;
  std::vector<ContactSpring> springs(2);
  springs[0].count = 1;
  springs[0].node[0] = m.node_count - 1;
  springs[0].weight[0] = 1.0;
  springs[0].k = 5e9;
  springs[1].count = 2;
  springs[1].node = {0, 0, 0, 0, 0, 0, 0, 0};
  springs[1].node[0] = m.node_count - 2;
  springs[1].node[1] = m.node_count - 3;
  springs[1].weight[0] = 1.0;
  springs[1].weight[1] = -1.0;
  springs[1].k = 2e9;
  HighestFrequency hf(m);
  const double exact = dense_highest(dense_operator(m, hf, springs));
  const FrequencyEstimate est = hf.estimate(m, springs);
  EXPECT_TRUE(est.converged) << est.iterations << " iterations";
  EXPECT_LE(est.ritz, exact * (1 + 1e-12));
  EXPECT_GE(est.omega, exact * (1 - 1e-12)) << "ritz " << est.ritz << ", exact " << exact;
  EXPECT_LT(est.omega, 1.01 * exact);
  // a second estimate from the first's eigenvector converges in fewer steps
  const FrequencyEstimate again = hf.estimate(m, springs);
  EXPECT_LT(again.iterations, est.iterations);
  EXPECT_NEAR(again.ritz / exact, 1.0, 0.01);

  // without springs and supports, against the element bound
  Model free = build_model(spec);
  double bound = 0.0;
  const MaterialParams& mat = free.materials[0];
  for (std::int32_t e = 0; e < free.element_count; ++e) {
    const double* w = free.gauss_weight.data() + 4 * e;
    bound = std::max(bound, tet10_max_frequency(free.dNdX.data() + 120 * e, w,
                                                mat.density * (w[0] + w[1] + w[2] + w[3]),
                                                mat.lame_lambda(), mat.shear_modulus()));
  }
  HighestFrequency hf_free(free);
  const FrequencyEstimate est_free = hf_free.estimate(free, {});
  EXPECT_LE(est_free.ritz, bound);
  EXPECT_GT(est_free.ritz, 0.5 * bound);
}

// The same bits with 1 and 2 threads (a model above the parallel thresholds).
TEST(HighestFrequency, SameBitsForAnyThreadCount) {
  const Model m = build_model(box_spec(6, 6, 6, 0.2));  // 1,296 elements: the element pass splits
  ASSERT_GT(m.element_count, 512);
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    HighestFrequency hf(m);
    const FrequencyEstimate a = hf.estimate(m, {});
    const FrequencyEstimate b = hf.estimate(m, {});
    return std::array<double, 4>{a.omega, a.ritz, b.omega, static_cast<double>(b.iterations)};
  };
  const auto one = run(1), two = run(2);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(one[i], two[i]) << i;
}
