// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Contact between bodies: the NBS broadphase over the contact sub-tetrahedra of all bodies
// (Model::contact_tets), kept valid by a Verlet buffer so it runs only when something has moved
// far enough; every candidate pair evaluated by the scene's contact law (`[contact] law`,
// contact/contact_laws.hpp; by default contact/penalty_potential_law.hpp), which this class
// gives each pair's friction spring and whose outcomes it sums.
//
// Every pair is evaluated independently (OpenMP) into its own slot and the forces are summed
// over pairs in their sorted order, so results do not depend on the thread count. The largest
// penetration over the touching pairs is reported so that a user can see how far the penalty
// lets the bodies sink into each other.
//
// On a rank of a distributed run (docs/ARCHITECTURE.md, "Distributed runs") the sub-tets keep
// the whole model's numbering, and a rank lists the pairs with a sub-tet that has a node it
// owns: the one-process list's pairs that reach its nodes, in the same order, so each owned
// node's contact force has one process's bits. The other ranks' sub-tets within reach come as
// foreign sub-tets: at each broadphase rebuild every rank sends the sub-tets near another
// rank's bodies, and then, until the next, the positions and velocities of the corners of those
// in its pairs. A pair listed on several ranks is evaluated once, by the rank owning the first
// corner of its first sub-tet, which sends the outcome and the friction spring to the others
// (one message a step to each rank it shares pairs with); that rank counts its energy and
// friction work (exact sums, added over the ranks), and the maxima are taken over the ranks.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/contact_laws.hpp"
#include "contact/nbs_broadphase.hpp"
#include "contact/verlet_buffer.hpp"
#include "engine/contact_model.hpp"
#include "engine/contact_patch.hpp"
#include "engine/distributed/distribution.hpp"
#include "engine/model.hpp"
#include "engine/state_archive.hpp"

namespace femdem {

class BodyContact final : public ContactModel {
 public:
  // `dist`: this rank's part of a distributed run (null: one process); kept, must outlive this.
  explicit BodyContact(const Model& m, const Distribution* dist = nullptr);

  // False when no two bodies can touch (fewer than two bodies with contact sub-tets, or all
  // fixed): compute() then does nothing.
  bool active() const override { return active_; }

  // Adds the contact forces at the current positions to f (3 per node), advancing the
  // friction springs over step_dt with the (half-step) velocities.
  void compute(const Model& m, double step_dt, std::vector<double>& f);
  // ContactModel: the same, its energy and friction work added to `sums`.
  void compute(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums) override {
    compute(static_cast<const Model&>(m), step_dt, f);
    sums.energy += energy_;
    sums.friction_dissipated += dissipated_;
  }
  void append_patches(std::vector<ContactPatch>& out) const override {
    out.insert(out.end(), patches_.begin(), patches_.end());
  }
  // The term the stable step adds, by Weyl's inequality, to the elements' own highest frequency
  // squared, every step (contact_stiffness_margin() included): an upper bound of the largest
  // eigenvalue of M^-1/2 K M^-1/2 with K the springs of the pairs touching in the last compute()
  // (max_stiffness_over_mass), or, if larger, the k / m of a flat contact (16 p A / h on a node of
  // boundary area share A and element depth h) on the nodes of the pairs that may touch within
  // `step` with faces flush (body_contact.cpp): a flat overlap is that stiff from its first
  // instant, and one step too long for it kicks the nodes by (omega dt)^2 / 2 times the closing
  // speed. Other pairs add nothing until they touch: the step is set again after every compute(),
  // and a corner or an edge that closes first starts from no stiffness. On a rank: collective.
  double omega_squared_bound(const Model& m, double step);

  double energy() const { return energy_; }          // stored now (potential + springs)
  double dissipated() const { return dissipated_; }  // by friction in the last compute()
  // Largest overlap depth 2 E / N over the pairs touching in the last compute() (0: none).
  double max_penetration() const { return max_penetration_; }
  // Largest over the same pairs of the depth over the element size (the thinner of the two
  // elements' depths behind their boundary faces, Model::contact_tet_depth).
  double max_penetration_per_size() const { return max_penetration_per_size_; }
  // The bodies of the pair with that largest depth per element size (-1, -1: none touching).
  std::pair<int, int> deepest_bodies() const { return deepest_bodies_; }
  // Largest over nodes of (sum over the touching pairs at the node of k W |w_node|) / (its mass)
  // (body_contact.cpp, spring_weights): a bound of the largest eigenvalue of the pairs' springs.
  double max_stiffness_over_mass() const { return max_k_over_m_; }

  // Candidate pairs listed (on a rank: those listed here) and touching (the whole model's).
  std::size_t candidate_pairs() const { return pairs_.size(); }
  std::size_t touching_pairs() const { return touching_; }
  // Adds to per_body[b] the listed pairs with a sub-tet of body b held here (the contact work of
  // each body on this rank, for rebalancing).
  void count_pairs_per_body(std::span<double> per_body) const {
    for (const Pair& p : pairs_)
      for (std::uint32_t t : {p.i, p.j})
        if (here_[t]) per_body[tet_body_[t]] += 1.0;
  }
  // Distributed runs: the other ranks' nodes received per step by all ranks (positions and
  // velocities, 48 bytes each), on average over the steps since the start or the resume.
  double foreign_nodes_per_step() const {
    return computes_ > 0 ? static_cast<double>(foreign_received_) / computes_ : 0.0;
  }
  // Distributed runs: the pairs whose outcome one rank sent to another, and the bytes, a step
  // by all ranks on average; and since the start or the resume, the pairs evaluated on all
  // ranks against the pairs listed (counted once): equal, as each pair is evaluated by one rank.
  double shared_pairs_per_step() const {
    return computes_ > 0 ? static_cast<double>(shared_sent_) / computes_ : 0.0;
  }
  double shared_bytes_per_step() const {
    return computes_ > 0 ? static_cast<double>(shared_bytes_sent_) / computes_ : 0.0;
  }
  std::int64_t evaluations_on_ranks() const { return evaluations_on_ranks_; }
  std::int64_t listed_since_start() const { return listed_since_start_; }
  std::int64_t broadphase_runs() const { return broadphase_runs_; }
  // Totals over the run: candidate pairs evaluated, and those found touching.
  std::int64_t pair_evaluations() const { return pair_evaluations_; }
  std::int64_t touching_evaluations() const { return touching_evaluations_; }
  // The touching pairs of the last compute() summed per pair of bodies (in the order of the
  // bodies' indices, body_a < body_b): filled only when asked for (collect_patches).
  void collect_patches(bool on) { collect_patches_ = on; }
  const std::vector<ContactPatch>& patches() const { return patches_; }
  // Saves or loads (engine/state_archive.hpp) the candidate list with its friction springs, the
  // Verlet reference, the stable-step stiffnesses and the counters: with the model's own state,
  // all that makes the steps after a restart the same bits as without it.
  void exchange_state(StateArchive& a);

 private:
  struct Pair {
    std::uint32_t i = 0, j = 0;  // contact sub-tets (the whole model's numbering), i < j
    double penalty = 0.0;        // Pa
    double friction = 0.0;       // Coulomb coefficient
    PairSpring spring;
  };

  void update_candidates(const Model& m);
  // The sub-tets of the listed pairs (active_tets_) and the pairs' slots for the next step.
  // Keeps, of the present sub-tets, those whose margin box meets the box of another body they
  // may touch (near_, near_boxes_, near_groups_).
  void keep_near_other_bodies(const Model& m);
  void list_pair_tets();
  // The corners and boxes of the sub-tets listed.
  void update_tet_boxes(const Model& m, const std::vector<std::uint32_t>& tets);
  void gather_patches();
  // Every candidate pair through the law, into results_ (in parallel).
  template <class Law>
  void evaluate_pairs(const Model& m, double step_dt);
  // The sums of the step's outcomes (energy, friction work, maxima) into the members, added or
  // compared over the ranks.
  void sum_outcomes(const Model& m);
  // A rank's: whether it owns local node n (every node in one process).
  bool owns(std::int32_t n) const { return !dist_ || dist_->part.node_owned[n]; }
  // Whether this rank counts pair p in the sums (one rank does, the owner of tet i's corner 0).
  bool counts(const Pair& p) const { return here_[p.i] && owns(corners_[p.i][0]); }
  // Distributed runs: the sub-tets of other ranks within reach of this rank's, with the
  // positions and velocities of their corners (at a rebuild).
  void fetch_near(const Model& m);
  // Distributed runs: the lists that bring, each step, the corners of the foreign sub-tets of
  // the pairs; then brings them.
  void subscribe(const Model& m);
  // Brings the foreign corners' positions and velocities along the lists.
  void refresh_foreign(const Model& m);
  // Distributed runs: which listed pairs another rank evaluates (remote_), and the lists their
  // records go by; checks that each side names the same pairs.
  void list_shared_pairs();
  // Sends the outcomes of the pairs evaluated here to the other ranks that list them, and takes
  // theirs.
  void share_outcomes();

  const Distribution* dist_ = nullptr;
  BodyPairLaw law_;
  bool active_ = false;
  NbsBroadphase broadphase_;
  VerletBuffer verlet_;
  // Per contact sub-tet of the whole model: its corners (local nodes when held here, else
  // slots of foreign_nodes_ while it is one), body and depth; whether it is held here, and
  // whether it has a node this rank owns (its pairs are listed here).
  std::vector<std::array<std::int32_t, 4>> corners_;
  std::vector<std::int32_t> tet_body_;
  std::vector<double> tet_depth_;
  std::vector<std::uint8_t> here_, mine_;
  std::vector<std::uint32_t> held_;  // the held sub-tets, ascending
  // The sub-tets the broadphase sees (held, and foreign within reach), ascending, with their
  // margin boxes and bodies in that order.
  std::vector<std::uint32_t> present_;
  std::vector<std::uint8_t> is_present_;
  std::vector<Aabb> boxes_;
  std::vector<std::int32_t> groups_;
  // Body-level boxes first (keep_near_other_bodies): each body's box, the bodies whose boxes meet
  // it (CSR), and the positions in present_ of the sub-tets near a partner, which alone go to
  // the sub-tet broadphase, with their boxes and bodies.
  NbsBroadphase body_broadphase_;
  std::vector<Aabb> body_boxes_;
  std::vector<std::int32_t> boxed_bodies_;  // the bodies with a box, ascending
  std::vector<Aabb> boxed_boxes_;
  std::vector<CandidatePair> body_pairs_;
  std::vector<std::uint32_t> partner_offset_, partner_fill_;
  std::vector<std::int32_t> partners_;
  std::vector<std::uint32_t> near_;
  std::vector<Aabb> near_boxes_;
  std::vector<std::int32_t> near_groups_;
  // Foreign nodes (distributed runs): global ids ascending, positions and velocities (3 each),
  // the lists they come by, and the whole model's contact sub-tets around each global node.
  std::vector<std::int32_t> foreign_nodes_;
  std::vector<double> foreign_x_, foreign_v_;
  std::vector<LocalPart::Neighbour> contact_lists_;
  std::vector<std::int32_t> node_tet_offset_, node_tets_;
  bool resubscribe_ = false;         // after a load: the lists are to be made again
  std::vector<std::int32_t> nodes_;  // the (local) nodes of held contact sub-tets
  std::vector<Vec3> node_positions_;
  std::vector<CandidatePair> found_;
  std::vector<Pair> pairs_, old_pairs_;
  std::vector<PairOutcome> results_;
  // Per candidate pair, this step: 1 when it has something to report (touching, or its friction
  // spring released: results_ holds the outcome), 0 when not (its sub-tets' boxes were apart or
  // the law found it apart, with no spring to release), so that the serial sums read only
  // those outcomes.
  std::vector<std::uint8_t> evaluated_;
  // Per candidate pair: 1 when another rank evaluates it (distributed runs).
  std::vector<std::uint8_t> remote_;
  // The pairs shared with other ranks: the lists (send: slots of outbox_pairs_, receive: slots of
  // inbox_pairs_, each the index of a listed pair), and this step's messages.
  std::vector<LocalPart::Neighbour> shared_lists_;
  std::vector<int> shared_ranks_;  // the ranks of shared_lists_, in its order
  std::vector<std::int32_t> outbox_pairs_, inbox_pairs_;
  std::vector<std::vector<std::byte>> outboxes_;
  std::size_t shared_records_ = 0, shared_bytes_ = 0;  // sent by this rank in the last step
  std::int64_t evaluated_here_ = 0;          // candidate pairs this rank took in the last step
  std::vector<Aabb> tet_boxes_;              // of each contact sub-tet, this step (no margin)
  std::vector<TetPositions> tet_positions_;  // its corners, this step
  std::vector<std::uint32_t> active_tets_;   // the sub-tets of candidate pairs, sorted
  struct TetMotion {
    Vec3 centre_velocity;  // of the sub-tet's centroid
    double spread;         // its largest corner speed about the centroid
  };
  std::vector<TetMotion> tet_motion_;  // of the active sub-tets (omega_squared_bound's scratch)
  // Per contact sub-tet: the sum over the steps of its corners' largest displacement in each
  // (update_tet_boxes), so that two sub-tets have come at most the difference of their sums
  // closer since any step. Per candidate pair: a lower bound of its distance at a step plus
  // both sums then (pair_clearance_ - tet_travel_[i] - tet_travel_[j] bounds its distance now;
  // -HUGE_VAL: none yet). A pair whose bound is positive cannot touch, and evaluate_pairs skips
  // it as it skips a pair whose boxes are apart.
  std::vector<double> tet_travel_;
  std::vector<double> pair_clearance_;
  std::vector<double> node_stiffness_;  // per model node, this step (k W |w|)
  // Per boundary node, the stiffness a flat contact gives it per unit penalty (16 A / h: the
  // potentials of both sides rise by 4 / h across their elements).
  std::vector<double> node_flat_stiffness_per_penalty_;
  double energy_ = 0.0, dissipated_ = 0.0, max_k_over_m_ = 0.0, max_penetration_ = 0.0,
         max_penetration_per_size_ = 0.0;
  std::size_t touching_ = 0;
  std::pair<int, int> deepest_bodies_{-1, -1};
  bool collect_patches_ = false;
  std::vector<ContactPatch> patches_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> patch_keys_;  // (body pair, result index)
  std::int64_t broadphase_runs_ = 0;
  std::int64_t pair_evaluations_ = 0, touching_evaluations_ = 0;
  // (not in checkpoints: log figures)
  std::int64_t foreign_received_ = 0, computes_ = 0, shared_sent_ = 0, shared_bytes_sent_ = 0,
               evaluations_on_ranks_ = 0, listed_since_start_ = 0;
};

}  // namespace femdem
