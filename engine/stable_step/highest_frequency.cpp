// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/stable_step/highest_frequency.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "elements/tet10_elastic_action.hpp"
#include "engine/element_gather.hpp"
#include "engine/exact_sum.hpp"
#include "engine/parallel_threshold.hpp"

namespace femdem {
namespace {

// A start vector with every mode in it and the same bits everywhere: a hash of the index.
double start_entry(std::size_t i) {
  std::uint64_t z = (static_cast<std::uint64_t>(i) + 1) * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53 - 0.5;
}

// The fresh share of each start vector beside the last eigenvector (the hash entries are
// uniform in [-1/2, 1/2): their norm is sqrt(n / 12)).
constexpr double kFreshShare = 0.1;

}  // namespace

HighestFrequency::HighestFrequency(const Model& m, int max_iterations, double tolerance)
    : max_iterations_(std::max(3, max_iterations)), tolerance_(tolerance) {
  for (const MaterialParams& p : m.materials) {
    lambda_.push_back(p.lame_lambda());
    shear_.push_back(p.shear_modulus());
  }
  const std::size_t n = 3 * static_cast<std::size_t>(m.node_count);
  inv_sqrt_mass_.assign(n, 0.0);
  v_prev_.assign(n, 0.0);
  v_.assign(n, 0.0);
  w_.assign(n, 0.0);
  u_.assign(n, 0.0);
  f_.assign(n, 0.0);
  element_force_.assign(30 * static_cast<std::size_t>(m.element_count), 0.0);
}

void HighestFrequency::apply_stiffness(const Model& m, const std::vector<ContactSpring>& springs,
                                       const double* u, double* f) {
  const std::int32_t ne = m.element_count;
  const double* x = m.x.data();
#pragma omp parallel for schedule(static) if (ne > kParallelMinElements)
  for (std::int32_t e = 0; e < ne; ++e) {
    const std::size_t es = static_cast<std::size_t>(e);
    const Tet10& c = m.conn[e];
    double xe[30], ue[30];
    for (int a = 0; a < 10; ++a)
      for (int k = 0; k < 3; ++k) {
        xe[3 * a + k] = x[3 * c[a] + k];
        ue[3 * a + k] = u[3 * c[a] + k];
      }
    const int mat = m.element_material[e];
    tet10_elastic_action(xe, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es, lambda_[mat],
                         shear_[mat], ue, element_force_.data() + 30 * es);
  }
  gather_element_forces(m, element_force_.data(), f);
  for (const ContactSpring& sp : springs) {
    double d[3] = {0.0, 0.0, 0.0};
    for (int c = 0; c < sp.count; ++c)
      for (int k = 0; k < 3; ++k) d[k] += sp.weight[c] * u[3 * sp.node[c] + k];
    for (int c = 0; c < sp.count; ++c)
      for (int k = 0; k < 3; ++k) f[3 * sp.node[c] + k] += sp.k * sp.weight[c] * d[k];
  }
}

void HighestFrequency::apply(const Model& m, const std::vector<ContactSpring>& springs,
                             const double* v, double* y) {
  const auto n = static_cast<std::int64_t>(inv_sqrt_mass_.size());
#pragma omp parallel for schedule(static) if (n > 3 * kParallelMinNodes)
  for (std::int64_t i = 0; i < n; ++i) u_[i] = inv_sqrt_mass_[i] * v[i];
  apply_stiffness(m, springs, u_.data(), f_.data());
#pragma omp parallel for schedule(static) if (n > 3 * kParallelMinNodes)
  for (std::int64_t i = 0; i < n; ++i) y[i] = inv_sqrt_mass_[i] * f_[i];
  // (the ghosts' entries are incomplete sums: their owners have them whole)
  if (dist_) dist_->comm->exchange(dist_->part, y, 3);
}

double HighestFrequency::dot(const double* a, const double* b) {
  ExactSum s[1] = {exact_sum_of(
      static_cast<std::int64_t>(inv_sqrt_mass_.size()),
      [&](std::int64_t i) { return !dist_ || dist_->part.node_owned[i / 3] ? a[i] * b[i] : 0.0; })};
  if (dist_) dist_->comm->sum(s);
  return s[0].value();
}

FrequencyEstimate HighestFrequency::estimate(const Model& m,
                                             const std::vector<ContactSpring>& springs,
                                             const Distribution* dist) {
  FrequencyEstimate out;
  dist_ = dist;
  const std::size_t n = inv_sqrt_mass_.size();
  // the start vector's entries and size are the whole model's (the global dof numbering)
  auto global_dof = [&](std::size_t i) {
    return dist ? 3 * static_cast<std::size_t>(dist->part.nodes[i / 3]) + i % 3 : i;
  };
  const std::size_t n_global =
      dist ? 3 * static_cast<std::size_t>(dist->part.global_node_count) : n;
  for (std::size_t i = 0; i < n; ++i)
    inv_sqrt_mass_[i] =
        (m.dof_mode[i] == 0 && m.mass[i / 3] > 0.0) ? 1.0 / std::sqrt(m.mass[i / 3]) : 0.0;

  // start: the last eigenvector (the model has changed little since), else every mode
  if (start_.size() != n) {
    start_.resize(n);
    for (std::size_t i = 0; i < n; ++i) start_[i] = start_entry(global_dof(i));
  }
  for (std::size_t i = 0; i < n; ++i) v_[i] = inv_sqrt_mass_[i] > 0.0 ? start_[i] : 0.0;
  double norm = std::sqrt(dot(v_.data(), v_.data()));
  // plus a little of every mode, so that a mode that has risen since (an element being crushed
  // elsewhere) is in the start too: Lanczos brings a small component of the top mode up fast
  for (std::size_t i = 0; i < n; ++i)
    if (inv_sqrt_mass_[i] > 0.0)
      v_[i] = (norm > 0.0 ? v_[i] / norm : 0.0) +
              kFreshShare * start_entry(global_dof(i)) / std::sqrt(n_global / 12.0);
  norm = std::sqrt(dot(v_.data(), v_.data()));
  if (!(norm > 0.0)) return out;  // nothing moves
  for (double& a : v_) a /= norm;
  std::fill(v_prev_.begin(), v_prev_.end(), 0.0);
  basis_.resize(static_cast<std::size_t>(max_iterations_) * n);

  std::vector<double> alpha, beta;  // T's diagonal, and its off-diagonal (beta[j]: j, j+1)
  Eigen::VectorXd top;              // T's eigenvector of its largest eigenvalue
  double theta = 0.0, residual = 0.0, beta_prev = 0.0;
  for (int j = 0; j < max_iterations_; ++j) {
    float* b = basis_.data() + static_cast<std::size_t>(j) * n;
    for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<float>(v_[i]);
    apply(m, springs, v_.data(), w_.data());
    for (std::size_t i = 0; i < n; ++i) w_[i] -= beta_prev * v_prev_[i];
    const double a = dot(v_.data(), w_.data());
    for (std::size_t i = 0; i < n; ++i) w_[i] -= a * v_[i];
    const double bnext = std::sqrt(dot(w_.data(), w_.data()));
    alpha.push_back(a);
    out.iterations = j + 1;
    // the largest eigenvalue of T_j and its eigenvector's last entry give the Ritz pair and
    // its residual |beta_{j+1} s_j|
    const int k = j + 1;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    for (int r = 0; r < k; ++r) {
      T(r, r) = alpha[r];
      if (r + 1 < k) T(r, r + 1) = T(r + 1, r) = beta[r];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T);
    const int last = k - 1;
    theta = eig.eigenvalues()(last);
    top = eig.eigenvectors().col(last);
    residual = std::fabs(bnext * top(last));
    if (!(theta > 0.0)) break;
    if (residual <= tolerance_ * theta && j >= 2) {
      out.converged = true;
      break;
    }
    if (!(bnext > 1e-12 * std::fabs(theta))) {  // an invariant subspace: T's spectrum is exact
      out.converged = true;
      break;
    }
    beta.push_back(bnext);
    beta_prev = bnext;
    std::swap(v_prev_, v_);
    for (std::size_t i = 0; i < n; ++i) v_[i] = w_[i] / bnext;
  }
  if (!(theta > 0.0)) return out;
  // the Ritz vector: the next estimate's start
  std::fill(start_.begin(), start_.end(), 0.0);
  for (int j = 0; j < out.iterations; ++j) {
    const float* b = basis_.data() + static_cast<std::size_t>(j) * n;
    const double s = top(j);
    for (std::size_t i = 0; i < n; ++i) start_[i] += s * b[i];
  }
  out.ritz = std::sqrt(theta);
  out.omega = std::sqrt(theta + residual);
  return out;
}

}  // namespace femdem
