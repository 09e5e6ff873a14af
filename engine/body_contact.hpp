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
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "contact/contact_laws.hpp"
#include "contact/nbs_broadphase.hpp"
#include "contact/verlet_buffer.hpp"
#include "engine/contact_model.hpp"
#include "engine/contact_patch.hpp"
#include "engine/model.hpp"
#include "engine/state_archive.hpp"

namespace femdem {

class BodyContact final : public ContactModel {
 public:
  explicit BodyContact(const Model& m);

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
  // omega^2 <= omega_element^2 + max over nodes of k / m (see max_stiffness_over_mass), the
  // springs counted with the settings' contact_stiffness_margin().
  double stable_step(const Model& m, double dt_element, double dt) override {
    if (!(max_k_over_m_ > 0.0)) return dt;
    const double omega_el = 2.0 / dt_element;
    const double k_over_m = m.settings.contact_stiffness_margin() * max_k_over_m_;
    return std::min(dt, 2.0 / std::sqrt(omega_el * omega_el + k_over_m));
  }

  // What the bound counts, as springs, for the assembled estimate: each touching pair on its 8
  // corners (stiffness twice its secant, the corners weighted by their shares of the normal
  // force), and every other node of a candidate pair with the flat-contact stiffness it would
  // have from its first touch.
  void append_springs(const Model& m, std::vector<ContactSpring>& out) const override;

  double energy() const { return energy_; }          // stored now (potential + springs)
  double dissipated() const { return dissipated_; }  // by friction in the last compute()
  // Largest overlap depth 2 E / N over the pairs touching in the last compute() (0: none).
  double max_penetration() const { return max_penetration_; }
  // Largest over the same pairs of the depth over the element size (the thinner of the two
  // elements' depths behind their boundary faces, Model::contact_tet_depth).
  double max_penetration_per_size() const { return max_penetration_per_size_; }
  // The bodies of the pair with that largest depth per element size (-1, -1: none touching).
  std::pair<int, int> deepest_bodies() const { return deepest_bodies_; }
  // Largest over nodes of (sum of the contact stiffness on the node) / (its mass): the stable
  // step bound adds it to the element frequency squared.
  double max_stiffness_over_mass() const { return max_k_over_m_; }

  std::size_t candidate_pairs() const { return pairs_.size(); }
  std::size_t touching_pairs() const { return touching_; }
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
    std::uint32_t i = 0, j = 0;  // contact sub-tets, i < j
    double penalty = 0.0;        // Pa
    double friction = 0.0;       // Coulomb coefficient
    PairSpring spring;
  };

  void update_candidates(const Model& m);
  // The corners and boxes of every contact sub-tet (all) or of those in candidate pairs.
  void update_tet_boxes(const Model& m, bool all);
  void gather_patches(const Model& m);
  // Every candidate pair through the law, into results_ (in parallel).
  template <class Law>
  void evaluate_pairs(const Model& m, double step_dt);

  BodyPairLaw law_;
  bool active_ = false;
  NbsBroadphase broadphase_;
  VerletBuffer verlet_;
  std::vector<std::int32_t> nodes_;  // the nodes of contact sub-tets
  std::vector<Vec3> node_positions_;
  std::vector<Aabb> boxes_;
  std::vector<std::int32_t> groups_;  // body of each contact sub-tet
  std::vector<CandidatePair> found_;
  std::vector<Pair> pairs_, old_pairs_;
  std::vector<PairOutcome> results_;
  // Per candidate pair, this step: 1 when it has something to report (touching, or its friction
  // spring released: results_ holds the outcome), 0 when not (its sub-tets' boxes were apart or
  // the law found it apart, with no spring to release), so that the serial sums read only
  // those outcomes.
  std::vector<std::uint8_t> evaluated_;
  std::vector<Aabb> tet_boxes_;              // of each contact sub-tet, this step (no margin)
  std::vector<TetPositions> tet_positions_;  // its corners, this step
  std::vector<std::uint32_t> active_tets_;   // the sub-tets of candidate pairs, sorted
  std::vector<double> node_stiffness_;       // per model node, this step
  // Per boundary node, the stiffness a flat contact would give it (8 p A / h: the potentials of
  // both sides rise by 4 / h across their elements): counted for the stable step as soon as the
  // node's sub-tets are candidates, because a flat contact is that stiff from its first touch.
  // (16 A / h per node, times the penalty of the stiffest candidate pair the node is in.)
  std::vector<double> node_flat_stiffness_per_penalty_, node_contact_stiffness_;
  double near_k_over_m_ = 0.0;           // largest over the nodes of candidate pairs
  mutable std::vector<char> node_mark_;  // scratch of append_springs, per model node
  double energy_ = 0.0, dissipated_ = 0.0, max_k_over_m_ = 0.0, max_penetration_ = 0.0,
         max_penetration_per_size_ = 0.0;
  std::size_t touching_ = 0;
  std::pair<int, int> deepest_bodies_{-1, -1};
  bool collect_patches_ = false;
  std::vector<ContactPatch> patches_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> patch_keys_;  // (body pair, result index)
  std::int64_t broadphase_runs_ = 0;
  std::int64_t pair_evaluations_ = 0, touching_evaluations_ = 0;
};

}  // namespace femdem
