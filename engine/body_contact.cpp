// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/body_contact.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "contact/tet_potential_contact.hpp"

namespace femdem {
namespace {

// The buffer as a fraction of the smallest contact sub-tet edge: larger means fewer broadphase
// runs but more candidate pairs to reject every step.
constexpr double kBufferPerEdge = 0.3;

// Below this many candidate pairs a parallel region costs more than it saves.
constexpr std::size_t kParallelMinPairs = 256;

double buffer_for(const Model& m) {
  return m.contact_tet_min_edge > 0.0 ? kBufferPerEdge * m.contact_tet_min_edge : 1.0;
}

// Barycentric coordinates of p in the tetrahedron t (any orientation, non-degenerate).
std::array<double, 4> barycentric(const contact::TetCorners& t, const Vec3& p) {
  Eigen::Matrix3d A;
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) A(k, a) = t[a + 1][k] - t[0][k];
  const Vec3 rhs(p[0] - t[0][0], p[1] - t[0][1], p[2] - t[0][2]);
  const Vec3 l = A.inverse() * rhs;
  return {1.0 - l[0] - l[1] - l[2], l[0], l[1], l[2]};
}

// Sizes of a linear tetrahedron for the stiffness bound of a pair: its total surface area and
// the largest gradient of its potential, max |grad 4 lambda_i| = 4 / (smallest altitude)
// = 4 max_i S_i / (3 V). Zero area for a degenerate tetrahedron (the pair is then not touching).
struct TetSize {
  double area = 0.0, max_gradient = 0.0;
};

TetSize tet_size(const contact::TetCorners& t) {
  const Vec3 p0(t[0][0], t[0][1], t[0][2]), p1(t[1][0], t[1][1], t[1][2]),
      p2(t[2][0], t[2][1], t[2][2]), p3(t[3][0], t[3][1], t[3][2]);
  const double six_v = std::abs((p1 - p0).dot((p2 - p0).cross(p3 - p0)));
  const double s[4] = {0.5 * (p2 - p1).cross(p3 - p1).norm(), 0.5 * (p2 - p0).cross(p3 - p0).norm(),
                       0.5 * (p1 - p0).cross(p3 - p0).norm(),
                       0.5 * (p1 - p0).cross(p2 - p0).norm()};
  TetSize z;
  if (!(six_v > 0.0)) return z;
  z.area = s[0] + s[1] + s[2] + s[3];
  z.max_gradient = 8.0 * std::max(std::max(s[0], s[1]), std::max(s[2], s[3])) / six_v;
  return z;
}

// Upper bound of the stiffness of a pair against relative translation, from the penalty and
// the sizes of the two tetrahedra alone (thesis eq. 2.119 and 2.124: the contact stiffness of
// a boundary tetrahedron is set by k = a E and its size). With E = p int_{A n B} (phi_A +
// phi_B), moving B by delta moves only the faces of B through phi_A (which is continuous and
// vanishes on dA), so d2/d delta2 of p int_{A n B} phi_A is the flux p int_{dB n A}
// (grad phi_A . e)(n . e) dS, at most p max|grad phi_A| area(dB n A); likewise for phi_B. dB n A
// and dA n B are parts of the boundary of the convex A n B, whose area is at most that of
// either tetrahedron. So k <= p (max|grad phi_A| + max|grad phi_B|) min(S_A, S_B). Two
// regular tetrahedra with faces flush (the stiffest contact, 4 p S (1/h_A + 1/h_B)) reach a
// quarter of it; the 2 N^2 / 2E of the contacts in test_body_contact stays below it (the
// same numbers as without the bound), so it acts where the secant has lost its meaning.
double pair_stiffness_bound(const contact::TetCorners& a, const contact::TetCorners& b,
                            double penalty) {
  const TetSize sa = tet_size(a), sb = tet_size(b);
  return penalty * (sa.max_gradient + sb.max_gradient) * std::min(sa.area, sb.area);
}

// A node held in all three directions (a fixed body's) does not oscillate: its contact
// stiffness does not limit the step.
bool held(const Model& m, std::int32_t n) {
  return m.dof_mode[3 * n] != 0 && m.dof_mode[3 * n + 1] != 0 && m.dof_mode[3 * n + 2] != 0;
}

}  // namespace

BodyContact::BodyContact(const Model& m) : verlet_(buffer_for(m)) {
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
  groups_.assign(m.contact_tet_body.begin(), m.contact_tet_body.end());
  node_stiffness_.assign(m.node_count, 0.0);
  double e_max = 0.0;
  for (const Body& b : m.bodies) e_max = std::max(e_max, m.materials[b.material].youngs_modulus);
  node_contact_stiffness_.assign(m.node_count, 0.0);
  for (const SurfaceNode& s : m.surface)
    node_contact_stiffness_[s.node] = 16.0 * m.contact.penalty_factor * e_max * s.area / s.depth;
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
  for (const CandidatePair& c : found_) {
    const int ba = m.contact_tet_body[c.i], bb = m.contact_tet_body[c.j];
    if (m.bodies[ba].fixed && m.bodies[bb].fixed) continue;
    Pair p;
    p.i = c.i;
    p.j = c.j;
    p.penalty =
        m.contact.penalty_factor * std::max(m.materials[m.bodies[ba].material].youngs_modulus,
                                            m.materials[m.bodies[bb].material].youngs_modulus);
    p.friction = m.contact.friction_between(ba, bb);
    while (o < old_pairs_.size() &&
           (old_pairs_[o].i < c.i || (old_pairs_[o].i == c.i && old_pairs_[o].j < c.j)))
      ++o;
    if (o < old_pairs_.size() && old_pairs_[o].i == c.i && old_pairs_[o].j == c.j) {
      std::copy(old_pairs_[o].stick, old_pairs_[o].stick + 3, p.stick);
      p.stick_stiffness = old_pairs_[o].stick_stiffness;
    }
    pairs_.push_back(p);
  }
  near_k_over_m_ = 0.0;
  for (const Pair& p : pairs_)
    for (std::uint32_t t : {p.i, p.j})
      for (std::int32_t n : m.contact_tets[t])
        if (m.mass[n] > 0.0 && !held(m, n))
          near_k_over_m_ = std::max(near_k_over_m_, node_contact_stiffness_[n] / m.mass[n]);
  // A pair that drops out of the list is far apart: its spring was released when it stopped
  // touching (evaluate() zeroes it then), so nothing is lost here.
  results_.resize(pairs_.size());
}

void BodyContact::evaluate(const Model& m, Pair& p, double step_dt, PairResult& r) const {
  contact::TetCorners a, b;
  const auto& ta = m.contact_tets[p.i];
  const auto& tb = m.contact_tets[p.j];
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 3; ++k) {
      a[c][k] = m.x[3 * ta[c] + k];
      b[c][k] = m.x[3 * tb[c] + k];
    }
  r.energy = r.dissipated = r.stiffness = r.penetration = 0.0;
  contact::TetPairContact out;
  r.touching = contact::tet_potential_contact(a, b, p.penalty, out);
  if (!r.touching || !(out.energy > 0.0)) {
    r.touching = false;
    // released: the spring's energy goes to friction
    const double u2 = p.stick[0] * p.stick[0] + p.stick[1] * p.stick[1] + p.stick[2] * p.stick[2];
    r.dissipated = 0.5 * p.stick_stiffness * u2;
    p.stick[0] = p.stick[1] = p.stick[2] = 0.0;
    return;
  }
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 3; ++k) {
      r.force[3 * c + k] = out.force_a[c][k];
      r.force[12 + 3 * c + k] = out.force_b[c][k];
    }
  r.energy = out.energy;
  Vec3 fb = Vec3::Zero();
  for (int c = 0; c < 4; ++c) fb += Vec3(out.force_b[c][0], out.force_b[c][1], out.force_b[c][2]);
  const double N = fb.norm();
  const double k_n = N * N / (2.0 * out.energy);
  // The stable step: a pair stiffer than its secant (a corner poking in: E ~ d^4) by up to 2,
  // but never stiffer than the geometric bound. The secant alone is not a sound estimate when
  // the overlap is a sliver at round-off level (corners, edges or faces of aligned meshes
  // exactly coincident): E is then a difference of O(volume) terms that cancels to almost
  // nothing while N keeps its honest size (volume x potential gradient), and N^2 / 2E grew by
  // 12 orders of magnitude and collapsed the step. The bound depends on the geometry only.
  // The friction spring takes the same capped secant, so that the stiffness counted for the
  // step covers it too; in a regular contact the cap does not act and k_t = N^2 / 2E.
  const double k_s = std::min(k_n, 0.5 * pair_stiffness_bound(a, b, p.penalty));
  r.stiffness = 2.0 * k_s;
  if (N > 0.0) r.penetration = 2.0 * out.energy / N;
  for (int k = 0; k < 3; ++k) {
    r.normal_force_b[k] = fb[k];
    r.centroid[k] = out.overlap_centroid[k];
  }
  r.secant = k_s;
  if (p.friction <= 0.0 || !(N > 0.0)) return;

  const Vec3 n = fb / N;
  const Vec3 c(out.overlap_centroid[0], out.overlap_centroid[1], out.overlap_centroid[2]);
  const auto la = barycentric(a, c), lb = barycentric(b, c);
  Vec3 va = Vec3::Zero(), vb = Vec3::Zero();
  for (int q = 0; q < 4; ++q) {
    va += la[q] * Vec3(m.v[3 * ta[q]], m.v[3 * ta[q] + 1], m.v[3 * ta[q] + 2]);
    vb += lb[q] * Vec3(m.v[3 * tb[q]], m.v[3 * tb[q] + 1], m.v[3 * tb[q] + 2]);
  }
  const Vec3 v_rel = vb - va;
  const Vec3 du = step_dt * (v_rel - v_rel.dot(n) * n);
  Vec3 u_old(p.stick[0], p.stick[1], p.stick[2]);
  u_old -= u_old.dot(n) * n;  // the contact plane turns with the bodies
  Vec3 u = u_old + du;
  const double k_t = k_s;
  const double limit = p.friction * N / k_t;
  const double stretch = u.norm();
  if (stretch > limit) {
    // slides: the spring force's work over the step (trapezoidal, as the integrator applies it)
    // minus the change of its stored energy
    const Vec3 u_new = u * (limit / stretch);
    r.dissipated =
        0.5 * k_t * ((u_old + u_new).dot(du) - (u_new.squaredNorm() - u_old.squaredNorm()));
    u = u_new;
  }
  p.stick[0] = u[0], p.stick[1] = u[1], p.stick[2] = u[2];
  p.stick_stiffness = k_t;
  r.energy += 0.5 * k_t * u.squaredNorm();
  const Vec3 ft = -k_t * u;  // on B at c; minus that on A
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k < 3; ++k) {
      r.force[3 * q + k] -= la[q] * ft[k];
      r.force[12 + 3 * q + k] += lb[q] * ft[k];
    }
}

void BodyContact::gather_patches(const Model& m) {
  // Sorted by body pair, then by the pairs' own order: the sums do not depend on threads.
  patches_.clear();
  patch_keys_.clear();
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    if (!results_[q].touching) continue;
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
    const PairResult& r = results_[q];
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
  energy_ = dissipated_ = max_penetration_ = 0.0;
  touching_ = 0;
  if (!active_) return;
  for (std::size_t q = 0; q < nodes_.size(); ++q) {
    const std::int32_t n = nodes_[q];
    node_positions_[q] = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
  }
  if (verlet_.needs_rebuild(node_positions_)) update_candidates(m);
  max_k_over_m_ = near_k_over_m_;

  const auto np = static_cast<std::int64_t>(pairs_.size());
#pragma omp parallel for schedule(dynamic, 64) if (pairs_.size() > kParallelMinPairs)
  for (std::int64_t q = 0; q < np; ++q) evaluate(m, pairs_[q], step_dt, results_[q]);

  // sum in pair order: the same bits with any number of threads
  for (std::size_t q = 0; q < pairs_.size(); ++q) {
    const PairResult& r = results_[q];
    dissipated_ += r.dissipated;
    if (!r.touching) continue;
    ++touching_;
    energy_ += r.energy;
    max_penetration_ = std::max(max_penetration_, r.penetration);
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
    if (!results_[q].touching) continue;
    for (const auto* t : {&m.contact_tets[pairs_[q].i], &m.contact_tets[pairs_[q].j]})
      for (std::int32_t n : *t) {
        if (node_stiffness_[n] > 0.0 && m.mass[n] > 0.0 && !held(m, n))
          max_k_over_m_ = std::max(max_k_over_m_, node_stiffness_[n] / m.mass[n]);
        node_stiffness_[n] = 0.0;
      }
  }
}

}  // namespace femdem
