// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/wall_contact.hpp"

#include "engine/contact_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace femdem {
namespace {

// The spring of a node near a wall (within the depth of the element behind it: it may touch
// within the step), or 0 when it is farther.
double near_wall_stiffness(const Model& m, const SurfaceNode& s, const Vec3& p, const Wall& w) {
  if ((p - w.point).dot(w.normal) - w.relief() > s.depth) return 0.0;
  return wall_modulus(m, w, s.body) * s.area / s.depth;
}

// The reach's buffer as a fraction of the thinnest element behind a boundary node: larger means
// fewer rebuilds but more pairs visited every step.
constexpr double kReachBufferPerDepth = 0.5;

double reach_buffer(const Model& m) {
  double depth = HUGE_VAL;
  for (const SurfaceNode& s : m.surface)
    if (!m.bodies[s.body].fixed) depth = std::min(depth, s.depth);
  return std::isfinite(depth) && depth > 0.0 ? kReachBufferPerDepth * depth : 1.0;
}

}  // namespace

WallContact::WallContact(const Model& m, bool collect_patches, const Distribution* dist)
    : dist_(dist),
      active_(!m.walls.empty()),
      collect_patches_(collect_patches),
      moved_(reach_buffer(m)) {
  const std::optional<WallLaw> law = wall_law_named(m.contact.wall_law);
  if (!law)
    throw std::invalid_argument("unknown wall law '" + std::string(m.contact.wall_law) + "'");
  law_ = *law;
  for (const Wall& w : m.walls) friction_ = friction_ || w.friction > 0.0;
  // (the same buffer on every rank: the thinnest element behind any boundary node)
  reach_buffer_ = reduce_min(moved_.buffer());
  moved_ = VerletBuffer(reach_buffer_);
  for (std::size_t si = 0; si < m.surface.size(); ++si)
    if (!m.bodies[m.surface[si].body].fixed &&
        (!dist_ || dist_->part.node_owned[m.surface[si].node]))
      tracked_.push_back(static_cast<std::uint32_t>(si));
  tracked_positions_.resize(tracked_.size());
  wall_offset_at_build_.assign(m.walls.size(), 0.0);
  stiffness_.assign(m.walls.size(), 0.0);
  penetration_.assign(m.walls.size(), 0.0);
  penetration_per_size_.assign(m.walls.size(), 0.0);
  deepest_body_.assign(m.walls.size(), -1);
  force_sums_.resize(3 * m.walls.size());
  if (collect_patches_) patches_.assign(m.bodies.size() * m.walls.size(), ContactPatch{});
}

void WallContact::compute(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums) {
  for (auto& w : m.walls) w.force.setZero();
  std::fill(penetration_.begin(), penetration_.end(), 0.0);
  std::fill(penetration_per_size_.begin(), penetration_per_size_.end(), 0.0);
  std::fill(deepest_body_.begin(), deepest_body_.end(), -1);
  if (collect_patches_) std::fill(patches_.begin(), patches_.end(), ContactPatch{});
  if (!active_) return;
  std::visit(
      [&]<class Law>(const Law&) {
        refresh_near<Law>(m);
        compute_with<Law>(m, step_dt, f, sums);
      },
      law_);
}

void WallContact::build_near(const Model& m) {
  std::swap(near_, old_near_);
  std::swap(stick_, old_stick_);
  near_.clear();
  stick_.clear();
  for (std::size_t wi = 0; wi < m.walls.size(); ++wi)
    wall_offset_at_build_[wi] = m.walls[wi].point.dot(m.walls[wi].normal);
  for (std::size_t q = 0; q < tracked_.size(); ++q) {
    const SurfaceNode& s = m.surface[tracked_[q]];
    const Vec3& p = tracked_positions_[q];
    for (std::size_t wi = 0; wi < m.walls.size(); ++wi) {
      const Wall& w = m.walls[wi];
      if ((p - w.point).dot(w.normal) - w.relief() > s.depth + reach_buffer_) continue;
      near_.push_back({tracked_[q], static_cast<std::uint32_t>(wi),
                       wall_modulus(m, w, s.body) * s.area / s.depth});
    }
  }
  if (friction_) stick_.assign(3 * near_.size(), 0.0);
  moved_.record(tracked_positions_);
  ++near_builds_;
}

template <class Law>
void WallContact::refresh_near(const Model& m) {
  for (std::size_t q = 0; q < tracked_.size(); ++q) {
    const std::int32_t n = m.surface[tracked_[q]].node;
    tracked_positions_[q] = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
  }
  double travel = 0.0;
  for (std::size_t wi = 0; wi < m.walls.size(); ++wi)
    travel = std::max(
        travel, std::fabs(m.walls[wi].point.dot(m.walls[wi].normal) - wall_offset_at_build_[wi]));
  // a node's distance to a wall changes by at most its displacement plus the wall's travel
  // (on every rank when on any: the list stays the one process's, cut by owner)
  if (!any_rank(moved_.max_displacement(tracked_positions_) + travel > reach_buffer_)) return;
  build_near(m);
  if (!friction_) return;
  // carry each kept pair's friction spring over (both lists are sorted); one that left with
  // its spring stretched (it cannot have been touching, but the books must close) releases it
  ContactSums dropped;
  std::size_t o = 0;
  for (std::size_t q = 0; q < near_.size(); ++q) {
    const NearPair& e = near_[q];
    for (; o < old_near_.size() &&
           (old_near_[o].surface < e.surface ||
            (old_near_[o].surface == e.surface && old_near_[o].wall < e.wall));
         ++o)
      Law::release(old_near_[o].k, old_stick_.data() + 3 * o, dropped);
    if (o < old_near_.size() && old_near_[o].surface == e.surface && old_near_[o].wall == e.wall) {
      for (int c = 0; c < 3; ++c) stick_[3 * q + c] = old_stick_[3 * o + c];
      ++o;
    }
  }
  for (; o < old_near_.size(); ++o)
    Law::release(old_near_[o].k, old_stick_.data() + 3 * o, dropped);
  released_ += dropped.friction_dissipated;
}

template <class Law>
void WallContact::compute_with(Model& m, double step_dt, std::vector<double>& f,
                               ContactSums& sums) {
  const double* x = m.x.data();
  const std::size_t nw = m.walls.size();
  // the step's accounts: springs released by a rebuild outside compute() (in stable_step) are
  // booked now
  enum { kEnergy, kDamping, kFriction, kSums };
  ExactSum accounts[kSums];
  accounts[kFriction].add(released_);
  released_ = 0.0;
  for (ExactSum& e : force_sums_) e = ExactSum{};
  for (std::size_t q = 0; q < near_.size(); ++q) {
    const std::size_t si = near_[q].surface, wi = near_[q].wall;
    const SurfaceNode& s = m.surface[si];
    const Vec3 p(x[3 * s.node], x[3 * s.node + 1], x[3 * s.node + 2]);
    const Vec3 v(m.v[3 * s.node], m.v[3 * s.node + 1], m.v[3 * s.node + 2]);
    {
      Wall& w = m.walls[wi];
      double* slip = stick_.empty() ? nullptr : stick_.data() + 3 * q;
      const double k = near_[q].k;
      // the depth and direction the wall pushes the node out by (a node past the end of a
      // bounded wall, a die's mouth, is as free as one in front of it)
      const Wall::Push push = w.push(p);
      const double d = push.depth;
      if (!(d > 0.0)) {
        if (slip) {
          ContactSums released;
          Law::release(k, slip, released);
          accounts[kFriction].add(released.friction_dissipated);
        }
        continue;
      }
      penetration_[wi] = std::max(penetration_[wi], d);
      if (d / s.depth > penetration_per_size_[wi])
        penetration_per_size_[wi] = d / s.depth, deepest_body_[wi] = s.body;
      if (collect_patches_) {
        const double fn = k * d;
        ContactPatch& q = patches_[static_cast<std::size_t>(s.body) * nw + wi];
        q.force_on_a += fn * push.normal;
        q.weighted_point += fn * p;
        q.weight += fn;
        q.stiffness += k;
      }
      const WallContactInput in{.k = k,
                                .depth = d,
                                .node_mass = m.mass[s.node],
                                .damping = w.damping,
                                .friction = w.friction,
                                .step_dt = step_dt,
                                .normal = push.normal,
                                .v_rel = v - w.step_velocity};
      ContactSums pair;
      const Vec3 fc = Law::apply(in, slip, pair);
      accounts[kEnergy].add(pair.energy);
      accounts[kDamping].add(pair.damping_power);
      accounts[kFriction].add(pair.friction_dissipated);
      for (int c = 0; c < 3; ++c) {
        f[3 * s.node + c] += fc[c];
        force_sums_[3 * wi + c].add(-fc[c]);
      }
    }
  }
  reduce(accounts);
  reduce(force_sums_);
  sums.energy += accounts[kEnergy].value();
  sums.damping_power += accounts[kDamping].value();
  sums.friction_dissipated += accounts[kFriction].value();
  for (std::size_t wi = 0; wi < nw; ++wi)
    m.walls[wi].force = Vec3(force_sums_[3 * wi].value(), force_sums_[3 * wi + 1].value(),
                             force_sums_[3 * wi + 2].value());
  reduce_deepest();
}

void WallContact::reduce_deepest() {
  if (!dist_) return;
  // the deepest node over the ranks, for every wall in two calls; its body as one process finds
  // it: the first (lowest boundary node, so lowest body) among those as deep
  const Communicator& comm = *dist_->comm;
  const std::size_t nw = penetration_.size();
  std::vector<double> deepest(2 * nw);  // negated: the ranks take minima
  for (std::size_t wi = 0; wi < nw; ++wi)
    deepest[wi] = -penetration_[wi], deepest[nw + wi] = -penetration_per_size_[wi];
  comm.min(deepest);
  std::vector<double> body(nw, HUGE_VAL);  // (body indices are exact in a double)
  for (std::size_t wi = 0; wi < nw; ++wi)
    if (deepest_body_[wi] >= 0 && penetration_per_size_[wi] == -deepest[nw + wi])
      body[wi] = deepest_body_[wi];
  comm.min(body);
  for (std::size_t wi = 0; wi < nw; ++wi) {
    penetration_[wi] = -deepest[wi];
    penetration_per_size_[wi] = -deepest[nw + wi];
    deepest_body_[wi] = body[wi] == HUGE_VAL ? -1 : static_cast<int>(body[wi]);
  }
}

void WallContact::append_patches(std::vector<ContactPatch>& out) const {
  const std::size_t nw = stiffness_.size();
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    ContactPatch q = patches_[i];
    if (!(q.weight > 0.0)) continue;
    q.body_a = static_cast<std::int32_t>(i / nw);
    q.body_b = ContactPatch::wall_side(i % nw);
    out.push_back(q);
  }
}

double WallContact::stable_step(const Model& m, double dt_element, double dt) {
  damping_factor_ = 1.0;
  driven_wall_step_ = HUGE_VAL;
  if (!active_) return dt;
  // A wall adds a spring k to boundary nodes near it; bound the node's frequency by the
  // element's plus the spring's (omega^2 <= omega_e^2 + k/m).
  const double omega_el = 2.0 / dt_element;
  const double margin = m.settings.contact_stiffness_margin();
  std::visit([&]<class Law>(const Law&) { refresh_near<Law>(m); }, law_);
  std::vector<ExactSum> stiffness(m.walls.size());
  for (const NearPair& e : near_) {
    const SurfaceNode& s = m.surface[e.surface];
    const Vec3 p(m.x[3 * s.node], m.x[3 * s.node + 1], m.x[3 * s.node + 2]);
    {
      const std::size_t wi = e.wall;
      const double k = margin * near_wall_stiffness(m, s, p, m.walls[wi]);
      if (!(k > 0.0)) continue;
      stiffness[wi].add(k);
      // a damping ratio xi shrinks the stable step by sqrt(1 + xi^2) - xi
      const double xi = m.walls[wi].damping;
      const double shrink = std::sqrt(1.0 + xi * xi) - xi;
      damping_factor_ = std::min(damping_factor_, shrink);
      dt = std::min(dt, 2.0 * shrink / std::sqrt(omega_el * omega_el + k / m.mass[s.node]));
    }
  }
  reduce(stiffness);
  for (std::size_t wi = 0; wi < stiffness_.size(); ++wi) stiffness_[wi] = stiffness[wi].value();
  dt = reduce_min(dt);
  damping_factor_ = reduce_min(damping_factor_);
  // A force-driven wall is a mass on the contact springs of every node near it (in parallel):
  // its own frequency must be resolved too. (The nodes' bound above counts each spring on its
  // node's side.)
  for (std::size_t wi = 0; wi < m.walls.size(); ++wi)
    if (m.walls[wi].force_driven() && stiffness_[wi] > 0.0)
      driven_wall_step_ =
          std::min(driven_wall_step_, 2.0 / std::sqrt(stiffness_[wi] / m.walls[wi].mass));
  return std::min(dt, driven_wall_step_);
}

void WallContact::append_springs(const Model& m, std::vector<ContactSpring>& out) const {
  if (!active_) return;
  const double margin = m.settings.contact_stiffness_margin();
  for (const SurfaceNode& s : m.surface) {
    if (m.bodies[s.body].fixed) continue;
    const Vec3 p(m.x[3 * s.node], m.x[3 * s.node + 1], m.x[3 * s.node + 2]);
    for (const Wall& w : m.walls) {
      const double k = margin * near_wall_stiffness(m, s, p, w);
      if (!(k > 0.0)) continue;
      ContactSpring c;
      c.node[0] = s.node;
      c.weight[0] = 1.0;
      c.count = 1;
      c.k = k;
      out.push_back(c);
    }
  }
}

void WallContact::exchange_state(StateArchive& a) {
  using L = StateArchive::Length;
  const StateArchive::Scope scope(a, "wall_contact");
  // the list by global boundary-node index: key = node entry x walls + wall
  const std::uint64_t nw = wall_offset_at_build_.size();
  std::vector<std::uint64_t> key;
  std::vector<double> k;
  std::vector<std::uint32_t> reach_surface;
  std::vector<Vec3> reference;
  if (a.saving()) {
    for (const NearPair& e : near_) {
      key.push_back(global_surface(e.surface) * nw + e.wall);
      k.push_back(e.k);
    }
    reference = moved_.recorded_positions();
    if (!reference.empty())
      for (const std::uint32_t si : tracked_) reach_surface.push_back(global_surface(si));
  }
  a.array("near_key", key, L::variable);
  a.array("near_k", k, L::variable);
  a.array("stick", stick_, L::variable);
  a.array("wall_offset_at_build", wall_offset_at_build_);
  a.array("reach_surface", reach_surface, L::variable);
  a.array("reach_reference", reference, L::variable);
  a.value("released", released_);
  a.value("near_builds", near_builds_);
  a.array("stiffness", stiffness_);
  a.array("penetration", penetration_);
  a.array("penetration_per_size", penetration_per_size_);
  a.value("damping_factor", damping_factor_);
  a.value("driven_wall_step", driven_wall_step_);
  if (a.saving()) return;
  // keep the entries of the boundary nodes tracked here (all of them in one process)
  std::vector<std::int64_t> local_of;  // global boundary-node index -> tracked entry here
  for (const std::uint32_t si : tracked_) {
    const std::uint32_t g = global_surface(si);
    if (local_of.size() <= g) local_of.resize(g + 1, -1);
    local_of[g] = si;
  }
  auto local = [&](std::uint64_t g) { return g < local_of.size() ? local_of[g] : -1; };
  const std::vector<double> stick = std::move(stick_);
  near_.clear();
  stick_.clear();
  for (std::size_t i = 0; i < key.size(); ++i) {
    const std::int64_t si = local(key[i] / nw);
    if (si < 0) continue;
    near_.push_back(
        {static_cast<std::uint32_t>(si), static_cast<std::uint32_t>(key[i] % nw), k[i]});
    if (!stick.empty())
      stick_.insert(stick_.end(), stick.begin() + 3 * i, stick.begin() + 3 * i + 3);
  }
  if (reference.size() != reach_surface.size())
    throw CheckpointError("'wall_contact/reach_reference' and 'reach_surface' differ in length");
  if (!reference.empty()) {
    std::vector<Vec3> mine;
    for (std::size_t i = 0; i < reference.size(); ++i)
      if (local(reach_surface[i]) >= 0) mine.push_back(reference[i]);
    moved_.record(mine);
  }
}

}  // namespace femdem
