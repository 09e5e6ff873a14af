// SPDX-License-Identifier: GPL-3.0-or-later
// Simulation's read-only views of the current state, for outputs and monitors: energies and
// balance, body motions and states, principal stresses, element stresses, bodies' volumes.
// Per-element work may run in parallel; every sum is serial in index order, so the results
// are the same bits for any thread count.
#include "engine/simulation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/element_kernel.hpp"
#include "engine/exact_sum.hpp"
#include "engine/parallel_threshold.hpp"
#include "materials/symmetric_eigen3.hpp"

namespace femdem {

double Simulation::bodies_volume(std::span<const std::uint8_t> body_mask) const {
  const Model& m = model_;
  const std::int32_t ne = m.element_count;
  double* ve = elem_scratch_.data();
  // One parallel pass over all elements (a powder of many small bodies parallelises as well as
  // one big body), each into its own slot, then one exact sum (over the owned elements, added
  // over the ranks): the same bits for any thread and rank count.
#pragma omp parallel for schedule(static) if (ne > kParallelMinElements)
  for (std::int32_t e = 0; e < ne; ++e) {
    if (!body_mask[m.element_body[e]]) continue;
    double xe[30];
    for (int a = 0; a < 10; ++a)
      for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.x[3 * m.conn[e][a] + k];
    const std::size_t es = static_cast<std::size_t>(e);
    ve[e] = tet10_current_volume(xe, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es);
  }
  ExactSum v[1] = {exact_sum_of(ne, [&](std::int64_t e) {
    return body_mask[m.element_body[e]] && owns_element(e) ? ve[e] : 0.0;
  })};
  reduce(v);
  return v[0].value();
}

void Simulation::follow_clock(const Simulation& part) {
  time_ = part.time_;
  steps_ = part.steps_;
  dt_ = part.dt_;
  stable_dt_ = part.stable_dt_;
  stable_bound_ = part.stable_bound_;
  frequency_estimates_ = part.frequency_estimates_;
  frequency_iterations_ = part.frequency_iterations_;
}

Energies Simulation::energies() const {
  Energies e;
  ExactSum kinetic[1] = {exact_sum_of(model_.node_count, [&](std::int64_t n) {
    if (!owns_node(n)) return 0.0;
    const double* v = model_.v.data() + 3 * n;
    return 0.5 * model_.mass[n] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  })};
  reduce(kinetic);
  e.kinetic = kinetic[0].value();
  e.internal = internal_energy_;
  e.plastic_dissipation = plastic_dissipation_;
  e.contact_dissipation = contact_dissipation_;
  e.viscous_dissipation = viscous_dissipation_;
  e.mass_scaling_dissipation = mass_scaling_dissipation_;
  e.contact = contact_energy_;
  e.external_work = external_work_;
  return e;
}

double Simulation::balance_error() const {
  const double scale = std::max(max_energy_, 1e-300);
  return (energies().balance() - initial_balance_) / scale;
}

BodyState Simulation::body_motion(int bi) const {
  const Model& m = model_;
  const Body& b = m.bodies[bi];
  BodyState s;
  s.mass = b.mass;
  s.added_mass = body_added_mass_[bi];
  double msum = 0.0;
  for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
    const double mn = m.mass[n];
    const double* x = m.x.data() + 3 * static_cast<std::size_t>(n);
    const double* v = m.v.data() + 3 * static_cast<std::size_t>(n);
    msum += mn;
    for (int k = 0; k < 3; ++k) {
      s.com[k] += mn * x[k];
      s.vcom[k] += mn * v[k];
    }
    s.kinetic_energy += 0.5 * mn * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  // contact acts on boundary nodes and, through the contact sub-tets, on nodes just inside
  for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n)
    s.contact_force += Vec3(m.f_contact[3 * n], m.f_contact[3 * n + 1], m.f_contact[3 * n + 2]);
  s.com /= msum;
  s.vcom /= msum;
  return s;
}

namespace {

// A body's motion as exact sums over the nodes `owned` says (mass, m x, m v, kinetic energy,
// contact force), and the state they give.
constexpr int kMotionSums = 11;

inline void add_to(ExactSum& s, double x) {
  s.add(x);
}
inline void add_to(double& s, double x) {
  s += x;
}

// (Sum: ExactSum, or double for a plain serial sum)
template <class Sum, class Owned>
void add_motion_sums(const Model& m, const Body& body, Owned owned, Sum* s) {
  for (std::int32_t n = body.first_node; n < body.first_node + body.node_count; ++n) {
    if (!owned(n)) continue;
    const double mn = m.mass[n];
    const double* x = m.x.data() + 3 * static_cast<std::size_t>(n);
    const double* v = m.v.data() + 3 * static_cast<std::size_t>(n);
    const double* f = m.f_contact.data() + 3 * static_cast<std::size_t>(n);
    add_to(s[0], mn);
    for (int k = 0; k < 3; ++k) add_to(s[1 + k], mn * x[k]), add_to(s[4 + k], mn * v[k]);
    add_to(s[7], 0.5 * mn * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    for (int k = 0; k < 3; ++k) add_to(s[8 + k], f[k]);
  }
}

BodyState motion_from_sums(double mass, double added_mass, const ExactSum* s) {
  BodyState o;
  o.mass = mass;
  o.added_mass = added_mass;
  const double msum = s[0].value();
  o.com = Vec3(s[1].value(), s[2].value(), s[3].value()) / msum;
  o.vcom = Vec3(s[4].value(), s[5].value(), s[6].value()) / msum;
  o.kinetic_energy = s[7].value();
  o.contact_force = Vec3(s[8].value(), s[9].value(), s[10].value());
  return o;
}

// What a rank sends rank 0 of each body it holds whole: its motion and largest tension.
constexpr int kRowNumbers = 13;

void to_row(const BodyState& s, double tension, double* row) {
  const double r[kRowNumbers] = {
      s.mass,           s.added_mass,       s.com[0],           s.com[1],
      s.com[2],         s.vcom[0],          s.vcom[1],          s.vcom[2],
      s.kinetic_energy, s.contact_force[0], s.contact_force[1], s.contact_force[2],
      tension};
  std::copy(r, r + kRowNumbers, row);
}

void from_row(const double* row, BodyState& s, double& tension) {
  s = BodyState{};
  s.mass = row[0];
  s.added_mass = row[1];
  s.com = Vec3(row[2], row[3], row[4]);
  s.vcom = Vec3(row[5], row[6], row[7]);
  s.kinetic_energy = row[8];
  s.contact_force = Vec3(row[9], row[10], row[11]);
  tension = row[12];
}

}  // namespace

void Simulation::body_motions(std::vector<BodyState>& out) const {
  const auto nb = static_cast<std::int64_t>(model_.bodies.size());
  out.resize(model_.bodies.size());
  // (distributed: only the bodies this rank holds whole)
  const int rank = dist_ ? dist_->comm->rank() : 0;
#pragma omp parallel for schedule(dynamic, \
                                  1) if (nb > 1 && model_.node_count > kParallelMinElements)
  for (std::int64_t b = 0; b < nb; ++b)
    if (!dist_ || dist_->part.body_rank[b] == rank) out[b] = body_motion(static_cast<int>(b));
  if (!dist_) return;
  // A body cut among ranks is summed over each rank's owned nodes and the ranks' sums added:
  // not the bits of one process's serial sum (the restitution monitors' per-step speeds of such
  // a body agree with it to round-off; the history rows use body_samples, which keep the bits).
  std::vector<double> unused(model_.bodies.size(), 0.0);
  gather_body_rows(out, unused, false);
}

void Simulation::body_samples(std::vector<BodyState>& out, std::vector<double>& tension) const {
  const Model& m = model_;
  const auto nb = static_cast<std::int64_t>(m.bodies.size());
  out.assign(m.bodies.size(), BodyState{});
  tension.assign(m.bodies.size(), -HUGE_VAL);
  const int rank = dist_ ? dist_->comm->rank() : 0;
  // exact sums, so that a body's figures do not depend on how its nodes are shared out
#pragma omp parallel for schedule(dynamic, 1) if (nb > 1 && m.node_count > kParallelMinElements)
  for (std::int64_t b = 0; b < nb; ++b) {
    if (dist_ && dist_->part.body_rank[b] != rank) continue;
    ExactSum s[kMotionSums];
    add_motion_sums(
        m, m.bodies[b], [](std::int32_t) { return true; }, s);
    out[b] = motion_from_sums(m.bodies[b].mass, body_added_mass_[b], s);
    tension[b] = max_principal_stress(static_cast<int>(b));
  }
  if (dist_) gather_body_rows(out, tension, true);
}

void Simulation::gather_body_rows(std::vector<BodyState>& out, std::vector<double>& tension,
                                  bool with_tension) const {
  // The bodies held whole go to rank 0 from their rank, as they are; a body cut among ranks is
  // summed exactly over the ranks' owned nodes (its largest tension: the largest of theirs).
  const Model& m = model_;
  const Communicator& comm = *dist_->comm;
  const std::vector<std::int32_t>& body_rank = dist_->part.body_rank;
  std::vector<ExactSum> cut;
  std::vector<std::size_t> cut_bodies;
  std::vector<double> cut_tension;  // negated: the ranks take minima
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (body_rank[b] >= 0) continue;
    cut_bodies.push_back(b);
    cut.resize(cut.size() + kMotionSums);
    ExactSum* sums = cut.data() + cut.size() - kMotionSums;
    if (with_tension) {  // a history row: exact over the nodes
      add_motion_sums(
          m, m.bodies[b], [&](std::int32_t n) { return owns_node(n); }, sums);
    } else {
      // every step: this rank's plain sums (a quarter of the cost), added exactly over the
      // ranks; round-off apart from one process's serial sums either way
      double plain[kMotionSums] = {};
      add_motion_sums(
          m, m.bodies[b], [&](std::int32_t n) { return owns_node(n); }, plain);
      for (int k = 0; k < kMotionSums; ++k) sums[k].add(plain[k]);
    }
    double largest = -HUGE_VAL;
    const Body& body = m.bodies[b];
    if (with_tension)
      for (std::int32_t e = body.first_element; e < body.first_element + body.element_count; ++e)
        if (owns_element(e)) largest = std::max(largest, element_max_principal_stress(e));
    cut_tension.push_back(-largest);
  }
  reduce(cut);
  if (with_tension && !cut_tension.empty()) comm.min(cut_tension);
  std::vector<double> mine;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (body_rank[b] != comm.rank()) continue;
    mine.resize(mine.size() + kRowNumbers);
    to_row(out[b], tension[b], mine.data() + mine.size() - kRowNumbers);
  }
  const auto* bytes = reinterpret_cast<const std::byte*>(mine.data());
  const std::vector<std::vector<std::byte>> all =
      comm.gather({bytes, mine.size() * sizeof(double)});
  if (comm.rank() != 0) return;
  for (int r = 0; r < comm.size(); ++r) {
    std::size_t at = 0;
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      if (body_rank[b] != r) continue;
      double row[kRowNumbers];
      std::memcpy(row, all[r].data() + at, sizeof row);
      at += sizeof row;
      from_row(row, out[b], tension[b]);
    }
  }
  for (std::size_t k = 0; k < cut_bodies.size(); ++k) {
    const std::size_t b = cut_bodies[k];
    out[b] = motion_from_sums(m.bodies[b].mass, body_added_mass_[b], cut.data() + kMotionSums * k);
    tension[b] = -cut_tension[k];
  }
}

BodyState Simulation::body_state(int bi) const {
  const Model& m = model_;
  const Body& b = m.bodies[bi];
  // the motion as the history rows have it (body_samples: exact sums)
  ExactSum sums[kMotionSums];
  add_motion_sums(
      m, b, [](std::int32_t) { return true; }, sums);
  BodyState s = motion_from_sums(b.mass, body_added_mass_[bi], sums);
  s.bbox_min = Vec3::Constant(HUGE_VAL);
  s.bbox_max = Vec3::Constant(-HUGE_VAL);
  for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
    const Vec3 p(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
    s.bbox_min = s.bbox_min.cwiseMin(p);
    s.bbox_max = s.bbox_max.cwiseMax(p);
  }
  // current volume: integral of det F over the reference element
  double vol = 0.0;
  for (std::int32_t e = b.first_element; e < b.first_element + b.element_count; ++e) {
    const double* dN = m.dNdX.data() + 120 * static_cast<std::size_t>(e);
    const double* w = m.gauss_weight.data() + 4 * static_cast<std::size_t>(e);
    for (int gp = 0; gp < 4; ++gp) {
      Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 10; ++a)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            F(i, j) += m.x[3 * m.conn[e][a] + i] * dN[gp * 30 + 3 * a + j];
      vol += w[gp] * F.determinant();
    }
  }
  s.volume = vol;
  // angular velocity: the lumped inertia tensor about the centre of mass inverted on the
  // angular momentum (a deforming body's mean spin)
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Vec3 spin_momentum = Vec3::Zero();
  for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
    const Vec3 r = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]) - s.com;
    const Vec3 u = Vec3(m.v[3 * n], m.v[3 * n + 1], m.v[3 * n + 2]) - s.vcom;
    inertia += m.mass[n] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    spin_momentum += m.mass[n] * r.cross(u);
  }
  if (inertia.determinant() > 0.0) s.angular_velocity = inertia.ldlt().solve(spin_momentum);
  for (std::int32_t e = b.first_element; e < b.first_element + b.element_count; ++e)
    for (int g = 0; g < 4; ++g)
      s.max_equivalent_plastic_strain =
          std::max(s.max_equivalent_plastic_strain, m.states[e].eps_p[g]);
  return s;
}

double Simulation::element_max_principal_stress(std::int64_t e) const {
  double largest = -HUGE_VAL;
  for (int gp = 0; gp < 4; ++gp) {
    // the point's 6 components, 4 apart in the [element][component][point] layout
    const double* first = model_.stress.data() + 24 * e + gp;
    const double s[6] = {first[0], first[4], first[8], first[12], first[16], first[20]};
    largest = std::max(largest, largest_eigenvalue3(s));
  }
  return largest;
}

double Simulation::max_principal_stress(int bi) const {
  const Body& b = model_.bodies[bi];
  const std::int64_t e0 = b.first_element, e1 = e0 + b.element_count;
  double largest = -HUGE_VAL;
  // max is exact in any order, so the reduction gives the same bits with any thread count
#pragma omp parallel for schedule(static) reduction(max \
                                                    : largest) if (e1 - e0 > kParallelMinElements)
  for (std::int64_t e = e0; e < e1; ++e)
    largest = std::max(largest, element_max_principal_stress(e));
  return largest;
}

void Simulation::element_stress(std::vector<double>& stress6, std::vector<double>& von_mises,
                                std::vector<double>& pressure,
                                std::vector<double>& eq_plastic) const {
  const std::int32_t ne = model_.element_count;
  stress6.assign(6 * static_cast<std::size_t>(ne), 0.0);
  von_mises.assign(ne, 0.0);
  pressure.assign(ne, 0.0);
  eq_plastic.assign(ne, 0.0);
  for (std::int32_t e = 0; e < ne; ++e) {
    double s[6] = {};
    for (int g = 0; g < 4; ++g)
      for (int k = 0; k < 6; ++k)
        s[k] += 0.25 * model_.stress[24 * static_cast<std::size_t>(e) + 4 * k + g];
    for (int k = 0; k < 6; ++k) stress6[6 * e + k] = s[k];
    double ep = 0.0;
    for (int g = 0; g < 4; ++g) ep += 0.25 * model_.states[e].eps_p[g];
    eq_plastic[e] = ep;
    const double p = -(s[0] + s[1] + s[2]) / 3.0;
    pressure[e] = p;
    const double d0 = s[0] + p, d1 = s[1] + p, d2 = s[2] + p;
    von_mises[e] = std::sqrt(
        1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
  }
}

}  // namespace femdem
