// SPDX-License-Identifier: GPL-3.0-or-later
// What a checkpoint holds of the engine (Simulation::exchange_state): the model's moving state
// (positions, velocities, forces, masses as mass scaling left them, every Gauss point's history
// and stress, the walls' positions, velocities and forces), the time, step and energy accounts,
// the stable-step bookkeeping and the contact kinds' lists and springs. Everything else the next
// step recomputes before it reads it (element forces and steps, this step's pair outcomes,
// patches and scratch), which the restart tests check: a restored run takes the same bits.
#include "engine/simulation.hpp"

namespace femdem {
namespace {

// A wall's moving state, 13 numbers: point, velocity, step velocity, force, acceleration.
constexpr std::size_t kWallNumbers = 13;

void exchange_walls(StateArchive& a, std::vector<Wall>& walls) {
  std::vector<double> w(kWallNumbers * walls.size());
  if (a.saving())
    for (std::size_t i = 0; i < walls.size(); ++i) {
      double* d = w.data() + kWallNumbers * i;
      for (int k = 0; k < 3; ++k) {
        d[k] = walls[i].point[k];
        d[3 + k] = walls[i].velocity[k];
        d[6 + k] = walls[i].step_velocity[k];
        d[9 + k] = walls[i].force[k];
      }
      d[12] = walls[i].accel;
    }
  a.array("walls", w);
  if (a.saving()) return;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const double* d = w.data() + kWallNumbers * i;
    walls[i].point = Vec3(d[0], d[1], d[2]);
    walls[i].velocity = Vec3(d[3], d[4], d[5]);
    walls[i].step_velocity = Vec3(d[6], d[7], d[8]);
    walls[i].force = Vec3(d[9], d[10], d[11]);
    walls[i].accel = d[12];
  }
}

}  // namespace

void Simulation::exchange_state(StateArchive& a) {
  Model& m = model_;
  {
    const StateArchive::Scope scope(a, "model");
    a.array("x", m.x);
    a.array("v", m.v);
    a.array("f_int", m.f_int);
    a.array("f_contact", m.f_contact);
    a.array("mass", m.mass);
    a.array("gauss_point_states", m.states);
    a.array("stress", m.stress);
    a.array("strain_energy_density", m.strain_energy_density);
    exchange_walls(a, m.walls);
  }
  const StateArchive::Scope scope(a, "simulation");
  a.value("time", time_);
  a.value("steps", steps_);
  a.value("dt", dt_);
  a.value("stable_dt", stable_dt_);
  a.array("acceleration", accel_);
  a.array("reaction", reaction_);
  // energy accounts
  a.value("internal_energy", internal_energy_);
  a.value("contact_energy", contact_energy_);
  a.value("external_work", external_work_);
  a.value("plastic_dissipation", plastic_dissipation_);
  a.value("contact_dissipation", contact_dissipation_);
  a.value("viscous_dissipation", viscous_dissipation_);
  a.value("mass_scaling_dissipation", mass_scaling_dissipation_);
  a.value("initial_balance", initial_balance_);
  a.value("max_energy", max_energy_);
  // mass scaling
  a.array("element_mass_scale", elem_mass_scale_);
  a.array("body_added_mass", body_added_mass_);
  a.array("body_added_at_start", body_added_at_start_);
  // stable step: the bound and the assembled estimate's ratio, warm start and counters
  a.value("stable_bound", stable_bound_);
  a.value("bound_at_estimate", bound_at_estimate_);
  a.value("step_ratio", step_ratio_);
  a.value("estimate_step", estimate_step_);
  a.value("frequency_estimates", frequency_estimates_);
  a.value("frequency_iterations", frequency_iterations_);
  bool assembled = frequency_.has_value();
  a.value("assembled_estimate", assembled);
  if (assembled != frequency_.has_value())
    throw CheckpointError("the checkpoint was written with another simulation.stable_step");
  if (frequency_) {
    const StateArchive::Scope fs(a, "highest_frequency");
    frequency_->exchange_state(a);
  }
  wall_contact_.exchange_state(a);
  body_contact_.exchange_state(a);
}

}  // namespace femdem
