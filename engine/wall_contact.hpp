// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Bodies on rigid walls: every boundary node of a free body against every wall, with the node's
// penalty k = M A / h (M from engine/contact_stiffness.hpp, A the node's boundary area share, h
// the depth of the element behind it), through the scene's wall law (`[contact] wall_law`,
// contact/contact_laws.hpp). Holds the friction spring of each (node, wall), the per-(body, wall)
// patches for impact damping, each wall's contact stiffness for the step of force-driven walls,
// and each wall's deepest node. Serial in node order: the sums are deterministic.
//
// Only the (node, wall) pairs within reach are visited: a list of those whose node was within
// its element depth plus a buffer of the wall's plane when the list was built, kept until the
// nodes' largest displacement plus the walls' largest travel along their normals exceeds the
// buffer (then a pair off the list may have come within an element depth). The list is sorted
// by node, then wall. The walls' forces, the energies and the stiffness near each wall are
// exact sums (engine/exact_sum.hpp), so they have the same bits in any order.
//
// In a distributed run (docs/ARCHITECTURE.md, "Distributed runs") each rank takes the boundary
// nodes it owns; the sums and the deepest nodes are added and compared over the ranks, and the
// list is rebuilt on every rank when it must be on any, so it is the one process's list cut by
// owner. A checkpoint keeps the list by global boundary-node index (near_key), so that one of
// any number of ranks is the same.
#include <cmath>
#include <cstdint>
#include <vector>

#include "contact/contact_laws.hpp"
#include "contact/verlet_buffer.hpp"
#include "engine/contact_model.hpp"
#include "engine/distributed/distribution.hpp"
#include "engine/exact_sum.hpp"
#include "engine/stable_step/highest_frequency.hpp"
#include "engine/state_archive.hpp"

namespace femdem {

class WallContact final : public ContactModel {
 public:
  WallContact(const Model& m, bool collect_patches, const Distribution* dist = nullptr);

  bool active() const override { return active_; }
  void compute(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums) override;
  void append_patches(std::vector<ContactPatch>& out) const override;
  // Per node near a wall (within one element depth) the element's frequency plus the spring's,
  // with the dashpot's shrink factor; and each force-driven wall's own frequency on the springs.
  double stable_step(const Model& m, double dt_element, double dt);
  // Every node within an element depth of a wall, with its spring (as stable_step counts them),
  // for the assembled stable-step estimate (engine/stable_step/highest_frequency.hpp).
  void append_springs(const Model& m, std::vector<ContactSpring>& out) const;
  // The (node, wall) pairs within reach, and how many times that list was built.
  std::size_t near_pairs() const { return near_.size(); }
  std::int64_t near_list_builds() const { return near_builds_; }
  // What the walls' dashpots and the force-driven walls' own frequency allow, from the last
  // stable_step(): the factor sqrt(1 + xi^2) - xi of the most damped wall with a node near it,
  // and the step of the stiffest force-driven wall on its springs (HUGE_VAL: none).
  double damping_factor() const { return damping_factor_; }
  // Per wall, the deepest node of the last compute(): its depth behind the wall (0: none), and
  // the largest depth over the element depth behind the node.
  double max_penetration(std::size_t wall) const { return penetration_[wall]; }
  double max_penetration_per_size(std::size_t wall) const { return penetration_per_size_[wall]; }
  // The body of the node with that largest depth per element size (-1: none).
  int deepest_body(std::size_t wall) const { return deepest_body_[wall]; }
  double driven_wall_step() const { return driven_wall_step_; }
  // Saves or loads (engine/state_archive.hpp) the reach list with its friction springs, what it
  // was built from, the unbooked releases and the per-wall stiffness, depth and step figures.
  // The list and the recorded positions are keyed by global boundary-node index; loading keeps
  // the entries of the nodes this rank owns.
  void exchange_state(StateArchive& a);

 private:
  struct NearPair {
    std::uint32_t surface = 0, wall = 0;  // index into Model::surface, Model::walls
    double k = 0.0;                       // the node's spring on this wall (N/m)
  };
  template <class Law>
  void compute_with(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums);
  // Rebuilds the list of pairs within reach when the nodes or walls have moved too far; a pair
  // that leaves it with its friction spring still stretched releases it (into released_).
  template <class Law>
  void refresh_near(const Model& m);
  void build_near(const Model& m);
  // The global index of local boundary-node entry `si` (itself in one process).
  std::uint32_t global_surface(std::size_t si) const {
    return dist_ ? static_cast<std::uint32_t>(dist_->part.surface[si])
                 : static_cast<std::uint32_t>(si);
  }
  // Distributed: the sums and extremes of the ranks (no-ops in one process).
  void reduce(std::span<ExactSum> sums) const {
    if (dist_) dist_->comm->sum(sums);
  }
  double reduce_min(double x) const { return dist_ ? dist_->comm->min(x) : x; }
  bool any_rank(bool flag) const { return dist_ ? !dist_->comm->all(!flag) : flag; }
  void reduce_deepest();

  const Distribution* dist_ = nullptr;
  WallLaw law_;
  bool active_ = false;
  bool collect_patches_ = false;
  bool friction_ = false;
  std::vector<NearPair> near_, old_near_;
  // Tangential spring stretch (3) per pair of near_; empty when no wall has friction.
  std::vector<double> stick_, old_stick_;
  std::vector<std::uint32_t> tracked_;  // surface nodes of free bodies
  std::vector<Vec3> tracked_positions_;
  std::vector<double> wall_offset_at_build_;  // point . normal per wall
  VerletBuffer moved_;                        // node positions at the last build
  double reach_buffer_ = 0.0;
  // friction energy released by a rebuild, not yet booked (this rank's; a checkpoint of several
  // ranks holds their total)
  double released_ = 0.0;
  std::vector<ExactSum> force_sums_;  // per wall, 3 components: this step's force
  std::int64_t near_builds_ = 0;
  std::vector<ContactPatch> patches_;  // per (body, wall), body-major
  std::vector<double> stiffness_;      // per wall: the contact stiffness near it
  std::vector<double> penetration_, penetration_per_size_;  // per wall, last compute()
  std::vector<int> deepest_body_;                           // per wall, last compute()
  double damping_factor_ = 1.0, driven_wall_step_ = HUGE_VAL;
};

}  // namespace femdem
