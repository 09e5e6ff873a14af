// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/body_contact.hpp"

#include "contact/centroid_line.hpp"
#include "contact/tet_distance_bound.hpp"
#include "engine/contact_stiffness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace femdem {
namespace {

// The buffer as a fraction of the smallest contact sub-tet edge: larger means fewer broadphase
// runs but more candidate pairs to reject every step.
constexpr double kBufferPerEdge = 0.3;

// Below this many candidate pairs (contact sub-tets) a parallel region costs more than it saves.
constexpr std::size_t kParallelMinPairs = 256;
constexpr std::int64_t kParallelMinTets = 4096;

double buffer_for(const Model& m) {
  return m.contact_tet_min_edge > 0.0 ? kBufferPerEdge * m.contact_tet_min_edge : 1.0;
}

// A node held in all three directions (a fixed body's) does not oscillate: its contact
// stiffness does not limit the step.
bool held(const Model& m, std::int32_t n) {
  return m.dof_mode[3 * n] != 0 && m.dof_mode[3 * n + 1] != 0 && m.dof_mode[3 * n + 2] != 0;
}

// A touching pair as the stable step sees it: a spring of stiffness r.stiffness on the weighted
// motion sum_c w_c u_c of its 8 corners, w_c the corner's share of the normal force (+ on one
// side, - on the other). Its share of the largest eigenvalue of M^-1/2 K M^-1/2 is bounded node
// by node: by Cauchy-Schwarz, k (sum_c w_c u_c)^2 <= k W sum_c |w_c| u_c^2 with W = sum_c |w_c|,
// so lambda_max of all the pairs' springs is at most max over nodes of
// (sum over its pairs of k W |w_c|) / m_node. An upper bound, unlike a node's k / m alone, which
// a spring between two light nodes exceeds.
struct SpringWeights {
  std::array<double, 8> corner{};  // the 4 corners of sub-tet i, then those of j
  double sum = 0.0;                // W
};

SpringWeights spring_weights(const PairOutcome& r) {
  SpringWeights w;
  const Vec3 fb(r.normal_force_b[0], r.normal_force_b[1], r.normal_force_b[2]);
  const double N = fb.norm();
  if (!(N > 0.0)) return w;  // (then k = N^2 / 2E = 0 too)
  const Vec3 n = fb / N;
  for (int c = 0; c < 8; ++c) {
    w.corner[c] = Vec3(r.force[3 * c], r.force[3 * c + 1], r.force[3 * c + 2]).dot(n) / N;
    w.sum += std::fabs(w.corner[c]);
  }
  return w;
}

// The gap between two tetrahedra along the line through their centroids (fixed at the call).
// While every node moves less than buffer / 2 the gap along that fixed axis shrinks by less
// than buffer, so a pair with a gap over the buffer cannot touch before the list is rebuilt:
// the broadphase's boxes of slanted surface tetrahedra overlap far more often.
double centroid_line_gap(const TetPositions& a, const TetPositions& b) {
  double length = 0.0;
  const double separation = contact::centroid_line_separation(a, b, &length);
  return length > 0.0 ? separation / length : -HUGE_VAL;
}

}  // namespace

BodyContact::BodyContact(const Model& m, const Distribution* dist)
    : dist_(dist), verlet_(buffer_for(m)) {
  const std::optional<BodyPairLaw> law = body_pair_law_named(m.contact.law);
  if (!law) throw std::invalid_argument("unknown contact law '" + std::string(m.contact.law) + "'");
  law_ = *law;
  // the whole model's sub-tets (a rank's part holds some of them)
  if (dist_) {
    const LocalPart& part = dist_->part;
    corners_ = part.contact_tets;
    tet_body_ = part.contact_tet_body;
    tet_depth_ = part.contact_tet_depth;
    here_.assign(corners_.size(), 0);
    for (std::size_t t = 0; t < corners_.size(); ++t)
      if (const std::int32_t lt = part.contact_tet_local[t]; lt >= 0) {
        corners_[t] = m.contact_tets[lt];
        here_[t] = 1;
      }
  } else {
    corners_ = m.contact_tets;
    tet_body_ = m.contact_tet_body;
    tet_depth_ = m.contact_tet_depth;
    here_.assign(corners_.size(), 1);
  }
  // two bodies that can move towards each other
  int with_tets = 0, movable = 0;
  std::vector<char> has_tets(m.bodies.size(), 0);
  for (std::int32_t b : tet_body_) has_tets[b] = 1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    with_tets += has_tets[b];
    movable += has_tets[b] && !m.bodies[b].fixed;
  }
  active_ = with_tets >= 2 && movable >= 1;
  if (!active_) return;
  const std::size_t nt = corners_.size();
  mine_.assign(nt, 0);
  is_present_.assign(nt, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    if (!here_[t]) continue;
    held_.push_back(static_cast<std::uint32_t>(t));
    for (std::int32_t n : corners_[t]) mine_[t] = mine_[t] || owns(n);
  }
  std::vector<char> used(m.node_count, 0);
  for (const auto& t : m.contact_tets)
    for (std::int32_t n : t) used[n] = 1;
  for (std::int32_t n = 0; n < m.node_count; ++n)
    if (used[n]) nodes_.push_back(n);
  node_positions_.resize(nodes_.size());
  tet_boxes_.resize(nt);
  tet_positions_.resize(nt);
  tet_travel_.assign(nt, 0.0);
  node_stiffness_.assign(m.node_count, 0.0);
  node_flat_stiffness_per_penalty_.assign(m.node_count, 0.0);
  for (const SurfaceNode& s : m.surface)
    node_flat_stiffness_per_penalty_[s.node] = 16.0 * s.area / s.depth;
  if (dist_) {
    // the sub-tets around each global node (which foreign sub-tets have all their corners)
    const LocalPart& part = dist_->part;
    node_tet_offset_.assign(static_cast<std::size_t>(part.global_node_count) + 1, 0);
    for (const auto& t : part.contact_tets)
      for (std::int32_t n : t) ++node_tet_offset_[n + 1];
    for (std::size_t n = 0; n + 1 < node_tet_offset_.size(); ++n)
      node_tet_offset_[n + 1] += node_tet_offset_[n];
    node_tets_.resize(node_tet_offset_.back());
    std::vector<std::int32_t> at(node_tet_offset_.begin(), node_tet_offset_.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (std::int32_t n : part.contact_tets[t])
        node_tets_[at[n]++] = static_cast<std::int32_t>(t);
  }
}

void BodyContact::update_candidates(const Model& m) {
  // the margin boxes of the sub-tets present (from this step's corners: update_tet_boxes)
  const double margin = verlet_.margin();
  if (!dist_) present_ = held_;
  boxes_.resize(present_.size());
  groups_.resize(present_.size());
  const std::size_t nb = m.bodies.size();
  body_boxes_.assign(nb, Aabb{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}});
  for (std::size_t q = 0; q < present_.size(); ++q) {
    const std::uint32_t t = present_[q];
    Aabb& b = boxes_[q];
    b.lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    b.hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto& c : tet_positions_[t])
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(b.lo[k], c[k] - margin);
        b.hi[k] = std::max(b.hi[k], c[k] + margin);
      }
    groups_[q] = tet_body_[t];
    Aabb& body = body_boxes_[static_cast<std::size_t>(tet_body_[t])];
    for (int k = 0; k < 3; ++k) {
      body.lo[k] = std::min(body.lo[k], b.lo[k]);
      body.hi[k] = std::max(body.hi[k], b.hi[k]);
    }
  }
  keep_near_other_bodies(m);
  broadphase_.find_pairs(near_boxes_, near_groups_, found_);
  ++broadphase_runs_;
  verlet_.record(node_positions_);

  // the new list, carrying each surviving pair's friction spring over (both lists are sorted;
  // present_ is ascending, so the found pairs are in the whole model's order)
  std::swap(pairs_, old_pairs_);
  pairs_.clear();
  std::size_t o = 0;
  const double buffer = verlet_.buffer();
  for (const CandidatePair& found : found_) {
    const CandidatePair c{present_[near_[found.i]], present_[near_[found.j]]};
    if (!mine_[c.i] && !mine_[c.j]) continue;  // (a rank's: no node of it is owned here)
    const int ba = tet_body_[c.i], bb = tet_body_[c.j];
    if (m.bodies[ba].fixed && m.bodies[bb].fixed) continue;
    while (o < old_pairs_.size() &&
           (old_pairs_[o].i < c.i || (old_pairs_[o].i == c.i && old_pairs_[o].j < c.j)))
      ++o;
    const bool kept = o < old_pairs_.size() && old_pairs_[o].i == c.i && old_pairs_[o].j == c.j;
    const bool spring = kept && old_pairs_[o].spring.stretched();
    if (!spring && centroid_line_gap(tet_positions_[c.i], tet_positions_[c.j]) > buffer) continue;
    Pair p;
    p.i = c.i;
    p.j = c.j;
    p.penalty = pair_penalty(m, ba, bb);
    p.friction = m.contact.friction_between(ba, bb);
    if (kept) p.spring = old_pairs_[o].spring;
    pairs_.push_back(p);
  }
  // A pair that drops out of the list is far apart: its spring was released when it stopped
  // touching (evaluate() zeroes it then), so nothing is lost here.
  list_pair_tets();
}

void BodyContact::keep_near_other_bodies(const Model& m) {
  // Body boxes first: the pairs of bodies whose boxes (the union of their sub-tets' margin boxes)
  // meet, two fixed bodies excepted, as each body's list of partners.
  // (bodies with no sub-tet present have no box and no partner)
  const std::size_t nb = m.bodies.size();
  boxed_bodies_.clear();
  boxed_boxes_.clear();
  for (std::size_t b = 0; b < nb; ++b)
    if (body_boxes_[b].lo[0] <= body_boxes_[b].hi[0]) {
      boxed_bodies_.push_back(static_cast<std::int32_t>(b));
      boxed_boxes_.push_back(body_boxes_[b]);
    }
  body_broadphase_.find_pairs(boxed_boxes_, boxed_bodies_, body_pairs_);
  auto pairs_up = [&](const CandidatePair& p) {
    return !(m.bodies[static_cast<std::size_t>(boxed_bodies_[p.i])].fixed &&
             m.bodies[static_cast<std::size_t>(boxed_bodies_[p.j])].fixed);
  };
  partner_offset_.assign(nb + 1, 0);
  for (const CandidatePair& p : body_pairs_)
    if (pairs_up(p))
      ++partner_offset_[boxed_bodies_[p.i] + 1], ++partner_offset_[boxed_bodies_[p.j] + 1];
  for (std::size_t b = 0; b < nb; ++b) partner_offset_[b + 1] += partner_offset_[b];
  partners_.resize(partner_offset_[nb]);
  partner_fill_.assign(partner_offset_.begin(), partner_offset_.end() - 1);
  for (const CandidatePair& p : body_pairs_)
    if (pairs_up(p)) {
      const std::int32_t a = boxed_bodies_[p.i], b = boxed_bodies_[p.j];
      partners_[partner_fill_[static_cast<std::size_t>(a)]++] = b;
      partners_[partner_fill_[static_cast<std::size_t>(b)]++] = a;
    }
  // Then the sub-tets whose box meets a partner's box. Two sub-tet boxes of different bodies
  // that overlap each lie in their own body's box, so each meets the other's body box: the
  // broadphase finds the same pairs among these, and in the same order (near_ keeps present_'s
  // ascending order). Left out: a body's far side, and fixed bodies away from moving ones.
  near_.clear();
  near_boxes_.clear();
  near_groups_.clear();
  for (std::size_t q = 0; q < present_.size(); ++q) {
    const auto body = static_cast<std::size_t>(groups_[q]);
    for (std::uint32_t k = partner_offset_[body]; k < partner_offset_[body + 1]; ++k)
      if (boxes_overlap(boxes_[q], body_boxes_[static_cast<std::size_t>(partners_[k])])) {
        near_.push_back(static_cast<std::uint32_t>(q));
        near_boxes_.push_back(boxes_[q]);
        near_groups_.push_back(groups_[q]);
        break;
      }
  }
}

void BodyContact::list_pair_tets() {
  results_.resize(pairs_.size());
  evaluated_.assign(pairs_.size(), 0);
  pair_clearance_.assign(pairs_.size(), -HUGE_VAL);
  remote_.assign(pairs_.size(), 0);  // (a rank's: set by list_shared_pairs)
  active_tets_.clear();
  for (const Pair& p : pairs_) {
    active_tets_.push_back(p.i);
    active_tets_.push_back(p.j);
  }
  std::sort(active_tets_.begin(), active_tets_.end());
  active_tets_.erase(std::unique(active_tets_.begin(), active_tets_.end()), active_tets_.end());
}

void BodyContact::update_tet_boxes(const Model& m, const std::vector<std::uint32_t>& tets) {
  const auto nt = static_cast<std::int64_t>(tets.size());
#pragma omp parallel for schedule(static) if (nt > kParallelMinTets)
  for (std::int64_t q = 0; q < nt; ++q) {
    const std::uint32_t t = tets[q];
    Aabb& b = tet_boxes_[t];
    TetPositions& p = tet_positions_[t];
    const auto& c = corners_[t];
    const double* x = here_[t] ? m.x.data() : foreign_x_.data();
    double moved2 = 0.0;  // the largest squared displacement of a corner since the last update
    for (int k = 0; k < 4; ++k) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double xk = x[3 * c[k] + d];
        d2 += (xk - p[k][d]) * (xk - p[k][d]);
        p[k][d] = xk;
      }
      moved2 = std::max(moved2, d2);
    }
    tet_travel_[t] += std::sqrt(moved2);
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(std::min(p[0][d], p[1][d]), std::min(p[2][d], p[3][d]));
      b.hi[d] = std::max(std::max(p[0][d], p[1][d]), std::max(p[2][d], p[3][d]));
    }
  }
}

template <class Law>
void BodyContact::evaluate_pairs(const Model& m, double step_dt) {
  PairInput in;
  in.step_dt = step_dt;
  const auto np = static_cast<std::int64_t>(pairs_.size());
  std::int64_t here = 0;
#pragma omp parallel for schedule(dynamic, 256) if (pairs_.size() > kParallelMinPairs) \
    firstprivate(in) reduction(+ : here)
  for (std::int64_t q = 0; q < np; ++q) {
    if (remote_[q]) continue;  // (another rank evaluates it: share_outcomes brings it)
    ++here;
    Pair& p = pairs_[q];
    // Most candidates are apart: the kernel's own first test (the corners' boxes overlap, on
    // the same numbers) on the boxes of this step, without gathering the corners. A pair that
    // fails it and holds no friction spring has nothing to report.
    const Aabb& a = tet_boxes_[p.i];
    const Aabb& b = tet_boxes_[p.j];
    const bool apart = a.hi[0] <= b.lo[0] || b.hi[0] <= a.lo[0] || a.hi[1] <= b.lo[1] ||
                       b.hi[1] <= a.lo[1] || a.hi[2] <= b.lo[2] || b.hi[2] <= a.lo[2];
    // Nor does a pair a lower bound of whose distance, found at an earlier step
    // (omega_squared_bound), its sub-tets have not travelled since: kClearance of its size
    // (far above the bound's and the sums' round-off) keeps it evaluated near touching.
    constexpr double kClearance = 1e-6;
    if ((apart ||
         pair_clearance_[q] - tet_travel_[p.i] - tet_travel_[p.j] > kClearance * tet_depth_[p.i]) &&
        !p.spring.stretched()) {
      evaluated_[q] = 0;
      continue;
    }
    in.corners_a = &tet_positions_[p.i];
    in.corners_b = &tet_positions_[p.j];
    in.v_a = here_[p.i] ? m.v.data() : foreign_v_.data();
    in.v_b = here_[p.j] ? m.v.data() : foreign_v_.data();
    in.tet_a = corners_[p.i];
    in.tet_b = corners_[p.j];
    in.penalty = p.penalty;
    in.friction = p.friction;
    PairOutcome& r = results_[q];
    Law::evaluate(in, p.spring, r);
    evaluated_[q] = r.touching || r.dissipated != 0.0;
  }
  evaluated_here_ = here;
}

void BodyContact::gather_patches() {
  // Sorted by body pair, then by the pairs' own order: the sums do not depend on threads.
  patches_.clear();
  patch_keys_.clear();
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q] || !results_[q].touching) continue;
    std::uint64_t a = static_cast<std::uint32_t>(tet_body_[pairs_[q].i]);
    std::uint64_t b = static_cast<std::uint32_t>(tet_body_[pairs_[q].j]);
    patch_keys_.emplace_back(std::min(a, b) << 32 | std::max(a, b), static_cast<std::uint32_t>(q));
  }
  std::sort(patch_keys_.begin(), patch_keys_.end());
  for (std::size_t k = 0; k < patch_keys_.size(); ++k) {
    const auto [key, q] = patch_keys_[k];
    if (k == 0 || key != patch_keys_[k - 1].first) {
      ContactPatch p;
      p.body_a = static_cast<std::int32_t>(key >> 32);
      p.body_b = static_cast<std::int32_t>(key & 0xffffffffu);
      patches_.push_back(p);
    }
    ContactPatch& p = patches_.back();
    const PairOutcome& r = results_[q];
    const Vec3 fb(r.normal_force_b[0], r.normal_force_b[1], r.normal_force_b[2]);
    // tet j's body receives fb; the patch's body a is the smaller index
    const bool j_is_a = tet_body_[pairs_[q].j] == p.body_a;
    p.force_on_a += j_is_a ? fb : Vec3(-fb);
    const double w = fb.norm();
    p.weighted_point += w * Vec3(r.centroid[0], r.centroid[1], r.centroid[2]);
    p.weight += w;
    p.stiffness += r.secant;
  }
}

void BodyContact::compute(const Model& m, double step_dt, std::vector<double>& f) {
  energy_ = dissipated_ = max_penetration_ = max_penetration_per_size_ = 0.0;
  touching_ = 0;
  deepest_bodies_ = {-1, -1};
  if (!active_) return;
  if (dist_) refresh_foreign(m);
  for (std::size_t q = 0; q < nodes_.size(); ++q) {
    const std::int32_t n = nodes_[q];
    node_positions_[q] = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
  }
  // (on every rank when on any: each rank's list stays the one process's pairs of its nodes)
  bool rebuild = verlet_.needs_rebuild(node_positions_);
  if (dist_) rebuild = !dist_->comm->all(!rebuild);
  // every sub-tet's corners when the list is rebuilt (its filter needs them), else only those
  // of the listed pairs
  if (rebuild) {
    update_tet_boxes(m, held_);
    if (dist_) fetch_near(m);
    update_candidates(m);
    if (dist_) subscribe(m);
  } else {
    update_tet_boxes(m, active_tets_);
  }

  std::visit([&]<class Law>(const Law&) { evaluate_pairs<Law>(m, step_dt); }, law_);
  if (dist_) share_outcomes();

  // forces summed in pair order: the same bits with any number of threads (and, on a rank,
  // for the nodes it owns, which are in every pair they are in)
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q] || !results_[q].touching) continue;
    const PairOutcome& r = results_[q];
    const SpringWeights w = spring_weights(r);
    for (int side = 0; side < 2; ++side) {
      const std::uint32_t t = side == 0 ? pairs_[q].i : pairs_[q].j;
      if (!here_[t]) continue;
      const auto& c = corners_[t];
      for (int k = 0; k < 4; ++k) {
        for (int d = 0; d < 3; ++d) f[3 * c[k] + d] += r.force[12 * side + 3 * k + d];
        node_stiffness_[c[k]] += r.stiffness * w.sum * std::fabs(w.corner[4 * side + k]);
      }
    }
  }
  sum_outcomes(m);
  if (collect_patches_) gather_patches();
}

void BodyContact::sum_outcomes(const Model& m) {
  enum {
    kEnergy,
    kFriction,
    kTouching,
    kListed,
    kForeign,
    kEvaluatedHere,
    kShared,
    kSharedBytes,
    kSums
  };
  ExactSum sums[kSums];
  sums[kForeign].add(static_cast<double>(foreign_nodes_.size()));
  sums[kEvaluatedHere].add(static_cast<double>(evaluated_here_));
  sums[kShared].add(static_cast<double>(shared_records_));
  sums[kSharedBytes].add(static_cast<double>(shared_bytes_));
  // the deepest pair per element size; among equals the lowest pair of bodies
  auto body_key = [](int a, int b) { return static_cast<double>(a) * 0x1p26 + b; };
  double deepest_key = HUGE_VAL;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const Pair& p = pairs_[q];
    if (!counts(p)) continue;
    sums[kListed].add(1.0);
    if (!evaluated_[q]) continue;
    const PairOutcome& r = results_[q];
    sums[kFriction].add(r.dissipated);
    if (!r.touching) continue;
    sums[kTouching].add(1.0);
    sums[kEnergy].add(r.energy);
    max_penetration_ = std::max(max_penetration_, r.penetration);
    const double per_size = r.penetration / std::min(tet_depth_[p.i], tet_depth_[p.j]);
    const double key = body_key(tet_body_[p.i], tet_body_[p.j]);
    if (per_size > max_penetration_per_size_ ||
        (per_size > 0.0 && per_size == max_penetration_per_size_ && key < deepest_key)) {
      max_penetration_per_size_ = per_size;
      deepest_key = key;
    }
  }
  // the stable step's k / m over the nodes this rank owns (their stiffness is whole here)
  max_k_over_m_ = 0.0;
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q] || !results_[q].touching) continue;
    for (std::uint32_t t : {pairs_[q].i, pairs_[q].j}) {
      if (!here_[t]) continue;
      for (std::int32_t n : corners_[t]) {
        if (node_stiffness_[n] > 0.0 && owns(n) && m.mass[n] > 0.0 && !held(m, n))
          max_k_over_m_ = std::max(max_k_over_m_, node_stiffness_[n] / m.mass[n]);
        node_stiffness_[n] = 0.0;
      }
    }
  }
  if (dist_) {
    const Communicator& comm = *dist_->comm;
    comm.sum(sums);
    double maxima[3] = {-max_k_over_m_, -max_penetration_, -max_penetration_per_size_};
    comm.min(maxima);
    const double mine = max_penetration_per_size_;
    max_k_over_m_ = -maxima[0];
    max_penetration_ = -maxima[1];
    max_penetration_per_size_ = -maxima[2];
    deepest_key = comm.min(mine == max_penetration_per_size_ ? deepest_key : HUGE_VAL);
  }
  energy_ = sums[kEnergy].value();
  dissipated_ = sums[kFriction].value();
  touching_ = static_cast<std::size_t>(sums[kTouching].value());
  pair_evaluations_ += static_cast<std::int64_t>(sums[kListed].value());
  touching_evaluations_ += static_cast<std::int64_t>(touching_);
  foreign_received_ += static_cast<std::int64_t>(sums[kForeign].value());
  evaluations_on_ranks_ += static_cast<std::int64_t>(sums[kEvaluatedHere].value());
  listed_since_start_ += static_cast<std::int64_t>(sums[kListed].value());
  shared_sent_ += static_cast<std::int64_t>(sums[kShared].value());
  shared_bytes_sent_ += static_cast<std::int64_t>(sums[kSharedBytes].value());
  ++computes_;
  if (max_penetration_per_size_ > 0.0 && deepest_key < HUGE_VAL) {
    const auto a = static_cast<std::int64_t>(deepest_key * 0x1p-26);
    deepest_bodies_ = {static_cast<int>(a), static_cast<int>(deepest_key - a * 0x1p26)};
  }
}

namespace {

// A box sent between ranks at a rebuild: the margin box of a rank's sub-tets of one body.
struct Region {
  std::int32_t body = 0;
  Aabb box;
};

template <class T>
void append_bytes(std::vector<std::byte>& out, const T* data, std::size_t count) {
  const auto* b = reinterpret_cast<const std::byte*>(data);
  out.insert(out.end(), b, b + count * sizeof(T));
}

template <class T>
std::vector<T> read_bytes(const std::vector<std::byte>& in, std::size_t& at, std::size_t count) {
  std::vector<T> v(count);
  if (count > 0) std::memcpy(v.data(), in.data() + at, count * sizeof(T));
  at += count * sizeof(T);
  return v;
}

Aabb grown(const Aabb& b, double margin) {
  Aabb g = b;
  for (int k = 0; k < 3; ++k) g.lo[k] -= margin, g.hi[k] += margin;
  return g;
}

}  // namespace

void BodyContact::fetch_near(const Model& m) {
  const Communicator& comm = *dist_->comm;
  const LocalPart& part = dist_->part;
  const int ranks = comm.size(), me = comm.rank();
  const double margin = verlet_.margin();
  // 1. this rank's regions: per body, the margin box of its sub-tets with an owned node
  std::vector<Region> mine;
  std::vector<std::int32_t> region_of(m.bodies.size(), -1);
  for (std::uint32_t t : held_) {
    if (!mine_[t]) continue;
    const Aabb b = grown(tet_boxes_[t], margin);
    std::int32_t& r = region_of[tet_body_[t]];
    if (r < 0) {
      r = static_cast<std::int32_t>(mine.size());
      mine.push_back({tet_body_[t], b});
      continue;
    }
    Aabb& box = mine[r].box;
    for (int k = 0; k < 3; ++k)
      box.lo[k] = std::min(box.lo[k], b.lo[k]), box.hi[k] = std::max(box.hi[k], b.hi[k]);
  }
  std::vector<std::byte> bytes;
  append_bytes(bytes, mine.data(), mine.size());
  const std::vector<std::vector<std::byte>> regions = comm.all_gather(bytes);
  // 2. to each rank, the owned corners of this rank's sub-tets that reach one of its regions
  // of another body, with their positions and velocities
  std::vector<std::vector<std::byte>> to(ranks);
  std::vector<std::int32_t> ids;
  for (int r = 0; r < ranks; ++r) {
    if (r == me || regions[r].empty()) continue;
    std::size_t at = 0;
    const auto theirs = read_bytes<Region>(regions[r], at, regions[r].size() / sizeof(Region));
    Aabb all = theirs.front().box;
    for (const Region& g : theirs)
      for (int k = 0; k < 3; ++k)
        all.lo[k] = std::min(all.lo[k], g.box.lo[k]), all.hi[k] = std::max(all.hi[k], g.box.hi[k]);
    ids.clear();
    for (std::uint32_t t : held_) {
      if (!mine_[t]) continue;
      const Aabb b = grown(tet_boxes_[t], margin);
      if (!boxes_overlap(b, all)) continue;
      const bool near = std::any_of(theirs.begin(), theirs.end(), [&](const Region& g) {
        return g.body != tet_body_[t] && boxes_overlap(b, g.box);
      });
      if (!near) continue;
      for (std::int32_t n : corners_[t])
        if (owns(n)) ids.push_back(n);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<std::int32_t> global(ids.size());
    std::vector<double> xv(6 * ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) {
      global[k] = part.nodes[ids[k]];
      for (int d = 0; d < 3; ++d) {
        xv[6 * k + d] = m.x[3 * ids[k] + d];
        xv[6 * k + 3 + d] = m.v[3 * ids[k] + d];
      }
    }
    const std::uint64_t count = ids.size();
    append_bytes(to[r], &count, 1);
    append_bytes(to[r], global.data(), global.size());
    append_bytes(to[r], xv.data(), xv.size());
  }
  const std::vector<std::vector<std::byte>> from = comm.all_to_all(to);
  // 3. the foreign nodes: all that came (each from its owner), by global id
  std::vector<std::pair<std::int32_t, std::array<double, 6>>> got;
  for (int r = 0; r < ranks; ++r) {
    if (from[r].empty()) continue;
    std::size_t at = 0;
    const auto count = read_bytes<std::uint64_t>(from[r], at, 1)[0];
    const auto global = read_bytes<std::int32_t>(from[r], at, count);
    const auto xv = read_bytes<double>(from[r], at, 6 * count);
    for (std::size_t k = 0; k < count; ++k) {
      std::array<double, 6> row;
      std::copy_n(xv.begin() + static_cast<std::ptrdiff_t>(6 * k), 6, row.begin());
      got.emplace_back(global[k], row);
    }
  }
  std::sort(got.begin(), got.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  foreign_nodes_.resize(got.size());
  foreign_x_.resize(3 * got.size());
  foreign_v_.resize(3 * got.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    foreign_nodes_[k] = got[k].first;
    for (int d = 0; d < 3; ++d) {
      foreign_x_[3 * k + d] = got[k].second[d];
      foreign_v_[3 * k + d] = got[k].second[3 + d];
    }
  }
  // 4. the foreign sub-tets all of whose corners came: present, with their boxes
  for (std::uint32_t t : present_) is_present_[t] = 0;
  present_ = held_;
  for (std::uint32_t t : held_) is_present_[t] = 1;
  std::vector<std::uint32_t> foreign;
  auto slot = [&](std::int32_t g) {
    const auto it = std::lower_bound(foreign_nodes_.begin(), foreign_nodes_.end(), g);
    return it != foreign_nodes_.end() && *it == g
               ? static_cast<std::int32_t>(it - foreign_nodes_.begin())
               : -1;
  };
  for (std::int32_t g : foreign_nodes_)
    for (std::int32_t k = node_tet_offset_[g]; k < node_tet_offset_[g + 1]; ++k) {
      const auto t = static_cast<std::uint32_t>(node_tets_[k]);
      if (here_[t] || is_present_[t]) continue;
      std::array<std::int32_t, 4> c;
      bool all = true;
      for (int a = 0; a < 4; ++a) all = all && (c[a] = slot(part.contact_tets[t][a])) >= 0;
      if (!all) continue;
      corners_[t] = c;
      is_present_[t] = 1;
      foreign.push_back(t);
    }
  update_tet_boxes(m, foreign);
  present_.insert(present_.end(), foreign.begin(), foreign.end());
  std::sort(present_.begin(), present_.end());
}

void BodyContact::subscribe(const Model& m) {
  const Communicator& comm = *dist_->comm;
  const LocalPart& part = dist_->part;
  const int ranks = comm.size();
  // the foreign sub-tets of the pairs, and their corners by global id
  std::vector<std::uint32_t> tets;
  for (const Pair& p : pairs_)
    for (std::uint32_t t : {p.i, p.j})
      if (!here_[t]) tets.push_back(t);
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  std::vector<std::int32_t> wanted;
  for (std::uint32_t t : tets)
    for (std::int32_t g : part.contact_tets[t]) wanted.push_back(g);
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  for (std::uint32_t t : present_)
    if (!here_[t]) is_present_[t] = 0;
  for (std::uint32_t t : tets) {
    for (int a = 0; a < 4; ++a)
      corners_[t][a] = static_cast<std::int32_t>(
          std::lower_bound(wanted.begin(), wanted.end(), part.contact_tets[t][a]) - wanted.begin());
    is_present_[t] = 1;
  }
  foreign_nodes_ = wanted;
  foreign_x_.assign(3 * wanted.size(), 0.0);
  foreign_v_.assign(3 * wanted.size(), 0.0);
  // ask each owner for its nodes (ascending: the order both lists keep)
  std::vector<std::vector<std::byte>> ask(ranks);
  contact_lists_.clear();
  std::vector<LocalPart::Neighbour> lists(ranks);
  for (std::size_t k = 0; k < wanted.size(); ++k) {
    const int owner = part.node_rank[wanted[k]];
    append_bytes(ask[owner], &wanted[k], 1);
    lists[owner].receive.push_back(static_cast<std::int32_t>(k));
  }
  const std::vector<std::vector<std::byte>> asked = comm.all_to_all(ask);
  for (int r = 0; r < ranks; ++r) {
    std::size_t at = 0;
    for (std::int32_t g : read_bytes<std::int32_t>(asked[r], at, asked[r].size() / 4)) {
      const auto it = std::lower_bound(part.nodes.begin(), part.nodes.end(), g);
      lists[r].send.push_back(static_cast<std::int32_t>(it - part.nodes.begin()));
    }
    lists[r].rank = r;
    if (!lists[r].send.empty() || !lists[r].receive.empty())
      contact_lists_.push_back(std::move(lists[r]));
  }
  present_ = held_;
  present_.insert(present_.end(), tets.begin(), tets.end());
  std::sort(present_.begin(), present_.end());
  comm.exchange(contact_lists_, m.x.data(), foreign_x_.data(), 3);
  comm.exchange(contact_lists_, m.v.data(), foreign_v_.data(), 3);
  list_shared_pairs();
}

void BodyContact::refresh_foreign(const Model& m) {
  if (resubscribe_) {
    resubscribe_ = false;
    subscribe(m);
    return;
  }
  const Communicator& comm = *dist_->comm;
  comm.exchange(contact_lists_, m.x.data(), foreign_x_.data(), 3);
  comm.exchange(contact_lists_, m.v.data(), foreign_v_.data(), 3);
}

// What a pair's evaluation leaves, sent to the other ranks that list the pair: a flag byte (bit
// 0: the friction spring is not all zeros, bit 1: the pair has something to report), then in
// the message's second part, pair after pair, the spring (4 doubles) if flagged and the outcome
// (36 doubles: touching, forces (24), energy, dissipated, stiffness, penetration, normal force
// on b (3), centroid (3), secant) if flagged. Most shared pairs are apart: one byte each.
namespace {
constexpr int kSpringDoubles = 4;
constexpr int kOutcomeDoubles = 36;

void pack_spring(const PairSpring& s, double* o) {
  o[0] = s.stick[0], o[1] = s.stick[1], o[2] = s.stick[2], o[3] = s.stick_stiffness;
}
void unpack_spring(const double* o, PairSpring& s) {
  s.stick[0] = o[0], s.stick[1] = o[1], s.stick[2] = o[2], s.stick_stiffness = o[3];
}
void pack_outcome(const PairOutcome& r, double* o) {
  o[0] = r.touching;
  std::copy_n(r.force, 24, o + 1);
  o[25] = r.energy, o[26] = r.dissipated, o[27] = r.stiffness, o[28] = r.penetration;
  std::copy_n(r.normal_force_b, 3, o + 29);
  std::copy_n(r.centroid, 3, o + 32);
  o[35] = r.secant;
}
void unpack_outcome(const double* o, PairOutcome& r) {
  r.touching = o[0] != 0.0;
  std::copy_n(o + 1, 24, r.force);
  r.energy = o[25], r.dissipated = o[26], r.stiffness = o[27], r.penetration = o[28];
  std::copy_n(o + 29, 3, r.normal_force_b);
  std::copy_n(o + 32, 3, r.centroid);
  r.secant = o[35];
}
}  // namespace

void BodyContact::list_shared_pairs() {
  const Communicator& comm = *dist_->comm;
  const LocalPart& part = dist_->part;
  const int ranks = comm.size(), me = comm.rank();
  // A pair is listed on every rank that owns a corner of its sub-tets (update_candidates) and
  // evaluated by the one that counts it; to each other one it sends what the evaluation left.
  std::vector<LocalPart::Neighbour> lists(ranks);
  std::vector<std::vector<std::byte>> keys(ranks);
  outbox_pairs_.clear();
  inbox_pairs_.clear();
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const Pair& p = pairs_[q];
    const std::uint32_t key[2] = {p.i, p.j};
    if (!counts(p)) {
      remote_[q] = 1;
      const int from = part.node_rank[part.contact_tets[p.i][0]];
      lists[from].receive.push_back(static_cast<std::int32_t>(inbox_pairs_.size()));
      inbox_pairs_.push_back(static_cast<std::int32_t>(q));
      continue;
    }
    int to[8], n_to = 0;  // the other ranks owning a corner (each once)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t g : part.contact_tets[t]) {
        const int r = part.node_rank[g];
        if (r != me && std::find(to, to + n_to, r) == to + n_to) to[n_to++] = r;
      }
    for (int k = 0; k < n_to; ++k) {
      lists[to[k]].send.push_back(static_cast<std::int32_t>(outbox_pairs_.size()));
      append_bytes(keys[to[k]], key, 2);
    }
    const bool sent = n_to > 0;
    if (sent) outbox_pairs_.push_back(static_cast<std::int32_t>(q));
  }
  shared_lists_.clear();
  shared_ranks_.clear();
  for (int r = 0; r < ranks; ++r) {
    lists[r].rank = r;
    if (!lists[r].send.empty() || !lists[r].receive.empty()) {
      shared_lists_.push_back(std::move(lists[r]));
      shared_ranks_.push_back(r);
    }
  }
  // Both sides must name the same pairs in the same order, or a step would wait for records
  // never sent: checked here, where a collective cannot hang.
  const std::vector<std::vector<std::byte>> got = comm.all_to_all(keys);
  for (int r = 0; r < ranks; ++r) {
    std::vector<std::byte> expected;
    for (const LocalPart::Neighbour& n : shared_lists_)
      if (n.rank == r)
        for (std::int32_t slot : n.receive) {
          const Pair& p = pairs_[inbox_pairs_[slot]];
          const std::uint32_t key[2] = {p.i, p.j};
          append_bytes(expected, key, 2);
        }
    if (got[r] != expected)
      throw std::logic_error("contact pairs listed differently on ranks " + std::to_string(me) +
                             " and " + std::to_string(r));
  }
}

void BodyContact::share_outcomes() {
  const std::size_t nb = shared_lists_.size();
  outboxes_.resize(nb);
  double record[kSpringDoubles + kOutcomeDoubles];
  shared_records_ = shared_bytes_ = 0;
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = shared_lists_[k];
    std::vector<std::byte>& out = outboxes_[k];
    out.resize(n.send.size());  // the flags, then the records
    for (std::size_t s = 0; s < n.send.size(); ++s) {
      const std::size_t q = static_cast<std::size_t>(outbox_pairs_[n.send[s]]);
      const PairSpring& spring = pairs_[q].spring;
      const bool has_spring = spring.stretched() || spring.stick_stiffness != 0.0;
      out[s] = static_cast<std::byte>((has_spring ? 1 : 0) | (evaluated_[q] ? 2 : 0));
      int w = 0;
      if (has_spring) pack_spring(spring, record), w = kSpringDoubles;
      if (evaluated_[q]) pack_outcome(results_[q], record + w), w += kOutcomeDoubles;
      append_bytes(out, record, static_cast<std::size_t>(w));
    }
    shared_records_ += n.send.size();
    shared_bytes_ += out.size();
  }
  const std::vector<std::vector<std::byte>> in =
      dist_->comm->exchange_bytes(shared_ranks_, outboxes_);
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = shared_lists_[k];
    const std::vector<std::byte>& got = in[k];
    std::size_t at = n.receive.size();
    if (got.size() < at)
      throw std::logic_error("contact pair outcomes from rank " + std::to_string(n.rank) +
                             " cut short");
    for (std::size_t s = 0; s < n.receive.size(); ++s) {
      const std::size_t q = static_cast<std::size_t>(inbox_pairs_[n.receive[s]]);
      const auto flags = static_cast<unsigned>(got[s]);
      const int w = ((flags & 1u) ? kSpringDoubles : 0) + ((flags & 2u) ? kOutcomeDoubles : 0);
      if (at + w * sizeof(double) > got.size())
        throw std::logic_error("contact pair outcomes from rank " + std::to_string(n.rank) +
                               " cut short");
      std::memcpy(record, got.data() + at, w * sizeof(double));
      at += w * sizeof(double);
      PairSpring& spring = pairs_[q].spring;
      if (flags & 1u)
        unpack_spring(record, spring);
      else
        spring = PairSpring{};
      evaluated_[q] = (flags & 2u) != 0;
      if (evaluated_[q]) unpack_outcome(record + ((flags & 1u) ? kSpringDoubles : 0), results_[q]);
    }
  }
}

double BodyContact::omega_squared_bound(const Model& m, double step) {
  // The pairs not touching that may touch within `step` with faces flush: a lower bound of their
  // distance (their boxes' gap, then contact/tet_distance_bound.hpp, both on this step's
  // corners) within kNearReach times what their relative speed covers in it, and a face of each
  // nearly parallel across that reach (a pair that no axis separates counts too). A corner or an
  // edge that closes first starts from no stiffness, which the next step's bound counts. The
  // relative speed of any two points of two linear tetrahedra is at most that of their
  // centroids plus each one's largest corner speed about its centroid; kNearReach leaves room
  // for its growth within the step.
  constexpr double kNearReach = 2.0;
  // Each sub-tet's centroid velocity and corner spread once (a sub-tet is in about ten pairs).
  tet_motion_.resize(tet_boxes_.size());
  const auto nt = static_cast<std::int64_t>(active_tets_.size());
#pragma omp parallel for schedule(static) if (nt > kParallelMinTets)
  for (std::int64_t q = 0; q < nt; ++q) {
    const std::uint32_t t = active_tets_[q];
    const double* v = here_[t] ? m.v.data() : foreign_v_.data();
    Vec3 c[4];
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < 4; ++k) {
      const std::int32_t n = corners_[t][k];
      c[k] = Vec3(v[3 * n], v[3 * n + 1], v[3 * n + 2]);
      centre += 0.25 * c[k];
    }
    double spread = 0.0;
    for (int k = 0; k < 4; ++k) spread = std::max(spread, (c[k] - centre).norm());
    tet_motion_[t] = {centre, spread};
  }
  double near = 0.0;
  const auto np = static_cast<std::int64_t>(pairs_.size());
#pragma omp parallel for schedule(static) reduction(max \
                                                    : near) if (pairs_.size() > kParallelMinPairs)
  for (std::int64_t q = 0; q < np; ++q) {
    if (evaluated_[q] && results_[q].touching) continue;
    const Pair& p = pairs_[q];
    const TetMotion& mi = tet_motion_[p.i];
    const TetMotion& mj = tet_motion_[p.j];
    const double reach =
        kNearReach * ((mi.centre_velocity - mj.centre_velocity).norm() + mi.spread + mj.spread) *
        step;
    const Aabb& a = tet_boxes_[p.i];
    const Aabb& b = tet_boxes_[p.j];
    double gap2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double g = std::max(a.lo[d] - b.hi[d], b.lo[d] - a.hi[d]);
      if (g > 0.0) gap2 += g * g;
    }
    const double travelled = tet_travel_[p.i] + tet_travel_[p.j];
    if (gap2 > reach * reach) {
      pair_clearance_[q] = std::sqrt(gap2) + travelled;
      continue;
    }
    double bound = 0.0;
    const bool may_close =
        contact::may_close_flush_within(tet_positions_[p.i], tet_positions_[p.j], reach, bound);
    pair_clearance_[q] = bound + travelled;
    if (!may_close) continue;
    for (std::uint32_t t : {p.i, p.j}) {
      if (!here_[t]) continue;
      for (std::int32_t n : corners_[t])
        if (owns(n) && m.mass[n] > 0.0 && !held(m, n))
          near = std::max(near, p.penalty * node_flat_stiffness_per_penalty_[n] / m.mass[n]);
    }
  }
  double k_over_m = std::max(max_k_over_m_, near);
  if (dist_) k_over_m = -dist_->comm->min(-k_over_m);
  return m.settings.contact_stiffness_margin() * k_over_m;
}

void BodyContact::exchange_state(StateArchive& a) {
  using L = StateArchive::Length;
  const StateArchive::Scope scope(a, "body_contact");
  // A rank saves the pairs it counts (every pair once over the ranks, merged by key when
  // gathered) and, loading the whole list, keeps those of its nodes.
  std::vector<Pair> counted;
  if (dist_ && a.saving())
    for (const Pair& p : pairs_)
      if (counts(p)) counted.push_back(p);
  a.array("pairs", dist_ && a.saving() ? counted : pairs_, L::variable);
  a.array("active_tets", active_tets_, L::variable);
  std::vector<Vec3> reference = verlet_.recorded_positions();
  a.array("verlet_reference", reference, L::variable);
  a.value("max_k_over_m", max_k_over_m_);
  a.value("energy", energy_);
  a.value("dissipated", dissipated_);
  a.value("max_penetration", max_penetration_);
  a.value("max_penetration_per_size", max_penetration_per_size_);
  a.value("touching", touching_);
  a.value("broadphase_runs", broadphase_runs_);
  a.value("pair_evaluations", pair_evaluations_);
  a.value("touching_evaluations", touching_evaluations_);
  if (a.saving()) return;
  if (!reference.empty()) verlet_.record(reference);
  if (dist_ && active_) {
    std::erase_if(pairs_, [&](const Pair& p) { return !mine_[p.i] && !mine_[p.j]; });
    resubscribe_ = true;  // (the foreign sub-tets' lists, at the next step: every rank loads)
  }
  // the sub-tets of the pairs, and the per-pair slots of the next step, as a rebuild leaves them
  list_pair_tets();
}

}  // namespace femdem
