// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/body_contact.hpp"

#include "contact/centroid_line.hpp"
#include "engine/contact_stiffness.hpp"

#include <algorithm>
#include <cmath>
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

BodyContact::BodyContact(const Model& m) : verlet_(buffer_for(m)) {
  const std::optional<BodyPairLaw> law = body_pair_law_named(m.contact.law);
  if (!law) throw std::invalid_argument("unknown contact law '" + std::string(m.contact.law) + "'");
  law_ = *law;
  // two bodies that can move towards each other
  int with_tets = 0, movable = 0;
  std::vector<char> has_tets(m.bodies.size(), 0);
  for (std::int32_t b : m.contact_tet_body) has_tets[b] = 1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    with_tets += has_tets[b];
    movable += has_tets[b] && !m.bodies[b].fixed;
  }
  active_ = with_tets >= 2 && movable >= 1;
  if (!active_) return;
  std::vector<char> used(m.node_count, 0);
  for (const auto& t : m.contact_tets)
    for (std::int32_t n : t) used[n] = 1;
  for (std::int32_t n = 0; n < m.node_count; ++n)
    if (used[n]) nodes_.push_back(n);
  node_positions_.resize(nodes_.size());
  boxes_.resize(m.contact_tets.size());
  tet_boxes_.resize(m.contact_tets.size());
  tet_positions_.resize(m.contact_tets.size());
  groups_.assign(m.contact_tet_body.begin(), m.contact_tet_body.end());
  node_stiffness_.assign(m.node_count, 0.0);
  node_flat_stiffness_per_penalty_.assign(m.node_count, 0.0);
  node_contact_stiffness_.assign(m.node_count, 0.0);
  for (const SurfaceNode& s : m.surface)
    node_flat_stiffness_per_penalty_[s.node] = 16.0 * s.area / s.depth;
}

void BodyContact::update_candidates(const Model& m) {
  const double margin = verlet_.margin();
  for (std::size_t t = 0; t < m.contact_tets.size(); ++t) {
    Aabb& b = boxes_[t];
    b.lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    b.hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::int32_t n : m.contact_tets[t])
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(b.lo[k], m.x[3 * n + k] - margin);
        b.hi[k] = std::max(b.hi[k], m.x[3 * n + k] + margin);
      }
  }
  broadphase_.find_pairs(boxes_, groups_, found_);
  ++broadphase_runs_;
  verlet_.record(node_positions_);

  // the new list, carrying each surviving pair's friction spring over (both lists are sorted)
  std::swap(pairs_, old_pairs_);
  pairs_.clear();
  std::size_t o = 0;
  const double buffer = verlet_.buffer();
  for (const CandidatePair& c : found_) {
    const int ba = m.contact_tet_body[c.i], bb = m.contact_tet_body[c.j];
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
  // each candidate node's flat-contact stiffness, with the stiffest penalty of its pairs
  for (const Pair& p : old_pairs_)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t n : m.contact_tets[t]) node_contact_stiffness_[n] = 0.0;
  for (const Pair& p : pairs_)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t n : m.contact_tets[t])
        node_contact_stiffness_[n] =
            std::max(node_contact_stiffness_[n], p.penalty * node_flat_stiffness_per_penalty_[n]);
  near_k_over_m_ = 0.0;
  for (const Pair& p : pairs_)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t n : m.contact_tets[t])
        if (m.mass[n] > 0.0 && !held(m, n))
          near_k_over_m_ = std::max(near_k_over_m_, node_contact_stiffness_[n] / m.mass[n]);
  // A pair that drops out of the list is far apart: its spring was released when it stopped
  // touching (evaluate() zeroes it then), so nothing is lost here.
  results_.resize(pairs_.size());
  evaluated_.assign(pairs_.size(), 0);
  active_tets_.clear();
  for (const Pair& p : pairs_) {
    active_tets_.push_back(p.i);
    active_tets_.push_back(p.j);
  }
  std::sort(active_tets_.begin(), active_tets_.end());
  active_tets_.erase(std::unique(active_tets_.begin(), active_tets_.end()), active_tets_.end());
}

void BodyContact::update_tet_boxes(const Model& m, bool all) {
  const auto nt = static_cast<std::int64_t>(all ? m.contact_tets.size() : active_tets_.size());
#pragma omp parallel for schedule(static) if (nt > kParallelMinTets)
  for (std::int64_t q = 0; q < nt; ++q) {
    const std::size_t t = all ? static_cast<std::size_t>(q) : active_tets_[q];
    Aabb& b = tet_boxes_[t];
    TetPositions& p = tet_positions_[t];
    const auto& c = m.contact_tets[t];
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) p[k][d] = m.x[3 * c[k] + d];
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(std::min(p[0][d], p[1][d]), std::min(p[2][d], p[3][d]));
      b.hi[d] = std::max(std::max(p[0][d], p[1][d]), std::max(p[2][d], p[3][d]));
    }
  }
}

template <class Law>
void BodyContact::evaluate_pairs(const Model& m, double step_dt) {
  PairInput in;
  in.v = m.v.data();
  in.step_dt = step_dt;
  const auto np = static_cast<std::int64_t>(pairs_.size());
#pragma omp parallel for schedule(dynamic, 256) if (pairs_.size() > kParallelMinPairs) \
    firstprivate(in)
  for (std::int64_t q = 0; q < np; ++q) {
    Pair& p = pairs_[q];
    // Most candidates are apart: the kernel's own first test (the corners' boxes overlap, on
    // the same numbers) on the boxes of this step, without gathering the corners. A pair that
    // fails it and holds no friction spring has nothing to report.
    const Aabb& a = tet_boxes_[p.i];
    const Aabb& b = tet_boxes_[p.j];
    const bool apart = a.hi[0] <= b.lo[0] || b.hi[0] <= a.lo[0] || a.hi[1] <= b.lo[1] ||
                       b.hi[1] <= a.lo[1] || a.hi[2] <= b.lo[2] || b.hi[2] <= a.lo[2];
    if (apart && !p.spring.stretched()) {
      evaluated_[q] = 0;
      continue;
    }
    in.corners_a = &tet_positions_[p.i];
    in.corners_b = &tet_positions_[p.j];
    in.tet_a = m.contact_tets[p.i];
    in.tet_b = m.contact_tets[p.j];
    in.penalty = p.penalty;
    in.friction = p.friction;
    PairOutcome& r = results_[q];
    Law::evaluate(in, p.spring, r);
    evaluated_[q] = r.touching || r.dissipated != 0.0;
  }
}

void BodyContact::gather_patches(const Model& m) {
  // Sorted by body pair, then by the pairs' own order: the sums do not depend on threads.
  patches_.clear();
  patch_keys_.clear();
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q] || !results_[q].touching) continue;
    std::uint64_t a = static_cast<std::uint32_t>(m.contact_tet_body[pairs_[q].i]);
    std::uint64_t b = static_cast<std::uint32_t>(m.contact_tet_body[pairs_[q].j]);
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
    const bool j_is_a = m.contact_tet_body[pairs_[q].j] == p.body_a;
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
  for (std::size_t q = 0; q < nodes_.size(); ++q) {
    const std::int32_t n = nodes_[q];
    node_positions_[q] = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
  }
  // every sub-tet's corners when the list is rebuilt (its filter needs them), else only those
  // of the listed pairs
  if (verlet_.needs_rebuild(node_positions_)) {
    update_tet_boxes(m, true);
    update_candidates(m);
  } else {
    update_tet_boxes(m, false);
  }
  max_k_over_m_ = near_k_over_m_;

  std::visit([&]<class Law>(const Law&) { evaluate_pairs<Law>(m, step_dt); }, law_);

  // sum in pair order: the same bits with any number of threads
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q]) continue;
    const PairOutcome& r = results_[q];
    dissipated_ += r.dissipated;
    if (!r.touching) continue;
    ++touching_;
    energy_ += r.energy;
    max_penetration_ = std::max(max_penetration_, r.penetration);
    const double per_size = r.penetration / std::min(m.contact_tet_depth[pairs_[q].i],
                                                     m.contact_tet_depth[pairs_[q].j]);
    if (per_size > max_penetration_per_size_) {
      max_penetration_per_size_ = per_size;
      deepest_bodies_ = {m.contact_tet_body[pairs_[q].i], m.contact_tet_body[pairs_[q].j]};
    }
    const auto& ta = m.contact_tets[pairs_[q].i];
    const auto& tb = m.contact_tets[pairs_[q].j];
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) {
        f[3 * ta[c] + k] += r.force[3 * c + k];
        f[3 * tb[c] + k] += r.force[12 + 3 * c + k];
      }
    for (int c = 0; c < 4; ++c) {
      node_stiffness_[ta[c]] += r.stiffness;
      node_stiffness_[tb[c]] += r.stiffness;
    }
  }
  pair_evaluations_ += static_cast<std::int64_t>(pairs_.size());
  touching_evaluations_ += static_cast<std::int64_t>(touching_);
  if (collect_patches_) gather_patches(m);
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q] || !results_[q].touching) continue;
    for (const auto* t : {&m.contact_tets[pairs_[q].i], &m.contact_tets[pairs_[q].j]})
      for (std::int32_t n : *t) {
        if (node_stiffness_[n] > 0.0 && m.mass[n] > 0.0 && !held(m, n))
          max_k_over_m_ = std::max(max_k_over_m_, node_stiffness_[n] / m.mass[n]);
        node_stiffness_[n] = 0.0;
      }
  }
}

void BodyContact::append_springs(const Model& m, std::vector<ContactSpring>& out) const {
  const double margin = m.settings.contact_stiffness_margin();
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!evaluated_[q]) continue;
    const PairOutcome& r = results_[q];
    if (!r.touching || !(r.stiffness > 0.0)) continue;
    const Vec3 fb(r.normal_force_b[0], r.normal_force_b[1], r.normal_force_b[2]);
    const double N = fb.norm();
    if (!(N > 0.0)) continue;
    const Vec3 n = fb / N;
    ContactSpring c;
    c.count = 8;
    c.k = margin * r.stiffness;
    const auto& ta = m.contact_tets[pairs_[q].i];
    const auto& tb = m.contact_tets[pairs_[q].j];
    for (int k = 0; k < 4; ++k) {
      c.node[k] = ta[k];
      c.node[4 + k] = tb[k];
      c.weight[k] = Vec3(r.force[3 * k], r.force[3 * k + 1], r.force[3 * k + 2]).dot(n) / N;
      c.weight[4 + k] =
          Vec3(r.force[12 + 3 * k], r.force[13 + 3 * k], r.force[14 + 3 * k]).dot(n) / N;
    }
    out.push_back(c);
  }
  node_mark_.assign(m.node_count, 0);
  for (std::size_t q = 0; q < pairs_.size(); ++q)
    if (evaluated_[q] && results_[q].touching)
      for (std::uint32_t t : {pairs_[q].i, pairs_[q].j})
        for (std::int32_t n : m.contact_tets[t]) node_mark_[n] = 1;
  for (const Pair& p : pairs_)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t n : m.contact_tets[t]) {
        if (node_mark_[n] || !(node_contact_stiffness_[n] > 0.0) || held(m, n)) continue;
        node_mark_[n] = 1;
        ContactSpring c;
        c.count = 1;
        c.node[0] = n;
        c.weight[0] = 1.0;
        c.k = margin * node_contact_stiffness_[n];
        out.push_back(c);
      }
}

void BodyContact::exchange_state(StateArchive& a) {
  using L = StateArchive::Length;
  const StateArchive::Scope scope(a, "body_contact");
  a.array("pairs", pairs_, L::variable);
  a.array("active_tets", active_tets_, L::variable);
  std::vector<Vec3> reference = verlet_.recorded_positions();
  a.array("verlet_reference", reference, L::variable);
  a.array("node_contact_stiffness", node_contact_stiffness_);
  a.value("near_k_over_m", near_k_over_m_);
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
  // the per-pair slots of the next step, as a rebuild leaves them
  results_.resize(pairs_.size());
  evaluated_.assign(pairs_.size(), 0);
}

}  // namespace femdem
