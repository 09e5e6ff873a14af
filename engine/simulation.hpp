// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The explicit time loop: central differences in kick-drift-kick form (velocities at whole
// steps, so kinetic energy and outputs are synchronous with positions), automatic stable step.
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/body_contact.hpp"
#include "engine/contact_patch.hpp"
#include "engine/distributed/distribution.hpp"
#include "engine/element_pass.hpp"
#include "engine/impact_damping.hpp"
#include "engine/model.hpp"
#include "engine/stable_step/highest_frequency.hpp"
#include "engine/state_archive.hpp"
#include "engine/wall_contact.hpp"
#include "materials/material_params.hpp"

namespace femdem {

struct Energies {
  double kinetic = 0.0;
  double internal = 0.0;             // stored elastic energy
  double plastic_dissipation = 0.0;  // accumulated
  double contact = 0.0;              // penalty energy stored in contacts (walls and bodies)
  double contact_dissipation = 0.0;  // accumulated work of contact dashpots and friction
  double viscous_dissipation = 0.0;  // accumulated work of the artificial bulk viscosity
  // Kinetic energy given up when mass scaling adds mass to a moving node at constant momentum.
  double mass_scaling_dissipation = 0.0;
  double external_work = 0.0;  // accumulated work of gravity, walls and driven nodes
  // kinetic + internal + plastic + contact - external_work - (its value at t = 0)
  double balance() const {
    return kinetic + internal + plastic_dissipation + contact + contact_dissipation +
           viscous_dissipation + mass_scaling_dissipation - external_work;
  }
};

struct BodyState {
  double mass = 0.0;        // rho V0, without mass added by mass scaling
  double added_mass = 0.0;  // by mass scaling so far
  double volume = 0.0;      // current, from the deformed elements
  Vec3 com = Vec3::Zero();
  Vec3 vcom = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, about the centre of mass (body_state only)
  double kinetic_energy = 0.0;
  Vec3 contact_force = Vec3::Zero();  // walls and other bodies, on this body
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();
  double max_equivalent_plastic_strain = 0.0;
};

// Builds the flat model: lumped masses, reference gradients, stable-step factors, constraints,
// surface nodes. Throws InputError for inverted or degenerate elements (naming body and element).
Model build_model(const ModelSpec& spec);

class Simulation {
 public:
  // Throws InputError when a rank's part (`local` of `part`) holds what distributed runs cannot
  // yet do. The constructor checks it too, but after its first collective call: a rank group
  // checks first, so that every rank refuses the scene before the ranks start (the refusal is
  // then agreed as bad input: engine/distributed/communicator.hpp).
  static void check_distributable(const Model& local, const LocalPart& part);
  // With a distribution: `model` is this rank's part (local_model), and the steps give its
  // owned nodes the same bits as one process would (docs/ARCHITECTURE.md, "Distributed runs");
  // energies() and the stable step are then the whole model's, and every rank must call
  // step() and energies() alike. Throws InputError for what distributed runs cannot do yet.
  explicit Simulation(Model model, std::optional<Distribution> distribution = std::nullopt);
  // (its parts keep pointers to its distribution)
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // One step. Throws InstabilityError (with body, element, time and advice) on det F <= 0 or
  // non-finite values.
  // dt_limit caps this step (to land exactly on an end time).
  void step(double dt_limit = HUGE_VAL);

  const Model& model() const { return model_; }
  // The element kernel: the SIMD update where it applies (default) or the scalar reference for
  // every element (tests and benchmarks compare the two).
  void choose_element_kernel(ElementKernelChoice choice) { element_pass_.choose(choice); }
  const ElementPass& element_pass() const { return element_pass_; }
  const BodyContact& body_contact() const { return body_contact_; }
  const WallContact& wall_contact() const { return wall_contact_; }
  double time() const { return time_; }
  std::int64_t steps() const { return steps_; }
  double dt() const { return dt_; }                // step that the next step() will take
  double stable_dt() const { return stable_dt_; }  // current stable estimate (before safety)
  // The element-and-contact bound now, and the assembled estimates made so far (with their
  // Lanczos iterations in all): `stable_dt() / stable_bound()` is what the estimates gained.
  double stable_bound() const { return stable_bound_; }
  std::int64_t frequency_estimates() const { return frequency_estimates_; }
  std::int64_t frequency_iterations() const { return frequency_iterations_; }

  Energies energies() const;
  // (energies().balance() - its initial value) / max(initial total, largest energy seen)
  double balance_error() const;
  // The whole state of a body (its motion summed as body_samples sums it).
  BodyState body_state(int body) const;
  // The cheap part of body_state (no volume, no bounding box), for per-step monitoring.
  BodyState body_motion(int body) const;
  // body_motion of every body (in parallel over bodies), into `out`. Distributed: every rank
  // calls it, and `out` is complete on rank 0 (a body cut among ranks is summed exactly over
  // the ranks: equal to one process's to round-off, not to the bit).
  void body_motions(std::vector<BodyState>& out) const;
  // Largest principal Cauchy stress (tension positive) over the body's Gauss points now: the
  // peak tension that cracks concrete, e.g. in the arms of a dropped armour unit.
  double max_principal_stress(int body) const;
  // What a history row shows of every body: its motion as body_motion, but summed exactly (the
  // same bits however its nodes are shared among threads or ranks), and its largest principal
  // stress. Distributed: every rank calls it, and the results are complete on rank 0.
  void body_samples(std::vector<BodyState>& motions, std::vector<double>& max_principal) const;
  Vec3 wall_position(int wall) const { return model_.walls[wall].point; }
  Vec3 wall_force(int wall) const { return model_.walls[wall].force; }
  Vec3 wall_velocity(int wall) const { return model_.walls[wall].velocity; }
  // Current (deformed) volume of the bodies b with body_mask[b] != 0 (one entry per body)
  // together: one pass over the elements, no allocation, deterministic (what the compaction
  // columns call every history row). On the ranks of a distributed run every rank calls it
  // (the owned elements' volumes are added over the ranks).
  double bodies_volume(std::span<const std::uint8_t> body_mask) const;

  // Gauss-point averages per element for output: Cauchy stress (6), von Mises, pressure
  // (-trace/3), equivalent plastic strain.
  void element_stress(std::vector<double>& stress6, std::vector<double>& von_mises,
                      std::vector<double>& pressure, std::vector<double>& eq_plastic) const;

  // Rank 0's whole-model Simulation in a distributed run, which is not stepped, takes a
  // part's clock after each step: time, step count, step sizes and the estimates' counters
  // (tools/femdem/run/rank_group.hpp).
  void follow_clock(const Simulation& part);

  // Saves the whole state between two steps into the archive, or loads it into a Simulation
  // built from the same scene (engine/simulation_checkpoint.cpp): the steps after a load are the
  // same bits as those of the run that saved it. Throws CheckpointError on a checkpoint that
  // does not fit the model.
  void exchange_state(StateArchive& a);

 private:
  // internal + wall contact at current x, after a step of length step_dt (0 at the start);
  // advances the material state and updates energies and element steps
  void compute_forces(double step_dt);
  void set_time_step();
  // The smallest element step bound (with the mass scaling) lowered by the walls' springs.
  double element_and_wall_bound();
  // The assembled estimate's step (elements and walls) given their bound (re-estimating when
  // due, or now if `force`).
  double assembled_step(double bound, bool force = false);
  // Selective mass scaling: raises the mass of elements whose stable step is below
  // `element_dt_needed` (conserving nodal momentum once the run has started); true if it added
  // mass.
  bool scale_masses(double element_dt_needed);
  std::string advice() const;  // what to change when the run diverges
  // distributed runs: what this rank sums (its owned nodes and elements), and the sums and
  // minima over all ranks (no-ops in one process)
  bool owns_node(std::int64_t n) const { return !dist_ || dist_->part.node_owned[n]; }
  bool owns_element(std::int64_t e) const { return !dist_ || dist_->part.element_owned[e]; }
  void reduce(std::span<ExactSum> sums) const {
    if (dist_) dist_->comm->sum(sums);
  }
  double reduce_min(double x) const { return dist_ ? dist_->comm->min(x) : x; }
  // Distributed: rank 0 gets the rows of the bodies other ranks hold whole (their motion and
  // largest tension, in `out` and `tension` on their rank), and every body cut among ranks
  // summed over them.
  void gather_body_rows(std::vector<BodyState>& out, std::vector<double>& tension,
                        bool with_tension) const;
  double element_max_principal_stress(std::int64_t e) const;
  // Throws InstabilityError once the balance's change exceeds settings.energy_balance_limit
  // times the largest energy seen (at least energy_floor_).
  void check_energy_balance(const Energies& en) const;
  // Adds the deformation damping force of every free body to f_int; returns its dissipation
  // rate (W, >= 0).
  double damp_deformation(double alpha);
  // Force-driven walls: acceleration from the prescribed load and the contact forces just
  // computed, then the second half kick of their velocity (step_dt 0: acceleration only).
  void update_force_driven_walls(double step_dt);

  // A material's return mapping, built once from its parameters.
  struct CompiledMaterial {
    double wave_speed = 0.0;  // dilatational, sqrt((K + 4G/3) / rho)
    double density = 0.0;
  };

  Model model_;
  std::optional<Distribution> dist_;
  std::vector<CompiledMaterial> compiled_;
  std::vector<MaterialKernel> kernels_;  // compiled_[i].kernel, as the element pass takes them
  ElementPass element_pass_;
  std::vector<ElementResult> elem_result_;  // per element, this step
  std::vector<double> elem_dissipation_;    // per element, this step
  double plastic_dissipation_ = 0.0;
  double contact_dissipation_ = 0.0;
  double viscous_dissipation_ = 0.0;
  double mass_scaling_dissipation_ = 0.0;
  std::vector<double> elem_mass_scale_;      // >= 1 per element; empty when mass scaling is off
  std::vector<double> body_added_mass_;      // per body
  std::vector<double> body_added_at_start_;  // per body: what the scaling before step 1 added
  WallContact wall_contact_;
  BodyContact body_contact_;
  // impact damping and rolling resistance (Model::patch_loads()): all patches of the
  // step, and the rigid motions of the bodies in them with their loads
  std::vector<ContactPatch> patches_;
  PatchLoads patch_loads_;
  std::vector<double> elem_viscous_power_;    // per element, this step
  mutable std::vector<double> elem_scratch_;  // per element, for bodies_volume
  // nodal F-bar (FbarMode::Nodal) work arrays
  bool has_nodal_fbar_ = false;
  std::vector<double> elem_volume_, elem_pressure_weight_, elem_volume_gradient_, node_J_, node_Q_,
      node_ref_volume_;
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  double dt_ = 0.0;
  double stable_dt_ = 0.0;
  // the assembled stable-step estimate (settings.stable_step == assembled; empty otherwise):
  // the bound at the last estimate and the ratio estimate / bound it found
  std::optional<HighestFrequency> frequency_;
  std::vector<ContactSpring> springs_;
  double stable_bound_ = 0.0, bound_at_estimate_ = 0.0, step_ratio_ = 1.0;
  std::int64_t estimate_step_ = 0, frequency_estimates_ = 0, frequency_iterations_ = 0;
  std::vector<double> accel_;             // 3 per node
  std::vector<double> body_power_;        // per body, scratch of damp_deformation
  std::vector<double> elem_force_;        // 30 per element
  std::vector<double> elem_energy_;       // per element
  std::vector<double> elem_dt_;           // per element stable step
  std::vector<double> reaction_;          // 3 per node, at constrained dofs
  std::vector<std::size_t> driven_dofs_;  // dofs with a prescribed velocity
  double internal_energy_ = 0.0;
  double contact_energy_ = 0.0;
  double external_work_ = 0.0;
  double initial_balance_ = 0.0;
  double max_energy_ = 0.0;
  double energy_floor_ = 0.0;  // J: the smallest energy scale of the balance stop rule
};

}  // namespace femdem
