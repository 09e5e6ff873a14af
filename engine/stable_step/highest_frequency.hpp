// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The highest natural frequency of the whole model as it is now, by Lanczos iterations on
// M^-1/2 K M^-1/2, matrix-free: K is the elements' elastic stiffness at their current shape
// (elements/tet10_elastic_action.hpp) plus the given springs (the walls' near their nodes), M
// the lumped masses (mass scaling included), and held or driven dofs are left out (they do not
// oscillate).
//
// Why: the element-by-element bound max_e omega_e (elements/tet10_frequency.hpp) is safe but
// counts every element as if its nodes carried only its own share of mass, and contact springs
// as if they added to the element's stiffest mode; the assembled system's own highest frequency
// is what the central-difference step must resolve (dt <= 2 / omega_max). Lanczos converges to
// it from below in a few iterations from the last estimate's eigenvector (the model changes
// little between estimates); the estimate returned adds the residual of the Ritz pair, which
// bounds the distance to the nearest eigenvalue, so that it errs on the high (safe) side.
//
// Deterministic: the element pass writes per-element buffers gathered in the fixed CSR order
// and every dot product is an exact sum, so the result has the same bits for any thread count;
// and for any split among the ranks of a distributed run (engine/distributed): each rank sums
// its owned dofs, takes its ghosts' entries of each new vector from their owners, and numbers
// the start vector by the global dofs.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/distributed/distribution.hpp"
#include "engine/model.hpp"
#include "engine/state_archive.hpp"

namespace femdem {

// A contact's stiffness as the estimate sees it: a spring of stiffness k (N/m, in every
// direction) on the weighted motion sum_c weight_c u_c of up to 8 nodes (a wall's: one node
// with weight 1; the springs between bodies are bounded every step instead,
// BodyContact::omega_squared_bound).
struct ContactSpring {
  std::array<std::int32_t, 8> node{};
  std::array<double, 8> weight{};
  int count = 0;
  double k = 0.0;
};

struct FrequencyEstimate {
  double omega = 0.0;      // rad/s, the estimate (Ritz value + residual), 0 when nothing moves
  double ritz = 0.0;       // rad/s, the Ritz value alone (a lower bound of the true one)
  int iterations = 0;      // Lanczos steps (each one application of K)
  bool converged = false;  // residual below the tolerance within the iteration limit
};

class HighestFrequency {
 public:
  // max_iterations: Lanczos steps per estimate (their vectors are kept, as floats, for the next
  // estimate's start); tolerance: the residual relative to the Ritz value at which to stop.
  explicit HighestFrequency(const Model& m, int max_iterations = 24, double tolerance = 0.01);

  // `dist`: this rank's part of a distributed run (the estimate is then the whole model's); the
  // springs' nodes are this rank's.
  FrequencyEstimate estimate(const Model& m, const std::vector<ContactSpring>& springs,
                             const Distribution* dist = nullptr);

  // Applies K (elements at the current shape and the springs) to u, 3 per node: for tests.
  void apply_stiffness(const Model& m, const std::vector<ContactSpring>& springs, const double* u,
                       double* f);

  // Saves or loads the warm start (the last estimate's eigenvector): the next estimate after a
  // restart starts where it would have.
  void exchange_state(StateArchive& a) { a.array("start", start_, StateArchive::Length::variable); }

 private:
  void apply(const Model& m, const std::vector<ContactSpring>& springs, const double* v, double* y);
  double dot(const double* a, const double* b);
  const Distribution* dist_ = nullptr;  // of the estimate under way

  int max_iterations_;
  double tolerance_;
  std::vector<double> lambda_, shear_;  // per material
  std::vector<double> inv_sqrt_mass_;   // per dof, 0 where the dof does not move
  std::vector<double> start_;           // the last estimate's eigenvector (empty: none yet)
  std::vector<float> basis_;            // Lanczos vectors of the current estimate
  std::vector<double> v_prev_, v_, w_, u_, f_, element_force_;
};

}  // namespace femdem
