// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/run_summary.hpp"

#include "tools/femdem/run/compaction_curve.hpp"
#include "tools/femdem/run/peak_monitor.hpp"

namespace femdem {

RunSummary make_run_summary(const RunRecord& run, const RunIdentity& id,
                            const std::vector<RestitutionMonitor>& restitution, RunStatus status) {
  const Simulation& sim = run.sim;
  const Model& m = sim.model();
  RunSummary summary;
  summary.scene = id.scene;
  summary.threads = id.threads;
  summary.nodes = m.node_count;
  summary.elements = m.element_count;
  summary.status = status;
  summary.end_time = sim.time();
  summary.steps = sim.steps();
  summary.time_step = sim.dt();
  summary.wall_time_s = id.wall_time_s;
  for (auto& [key, value] : summary_extra(run)) summary.extra[key] = value;
  const Energies e = sim.energies();
  summary.energy = {.kinetic = e.kinetic,
                    .internal = e.internal,
                    .plastic_dissipation = e.plastic_dissipation,
                    .contact = e.contact,
                    .contact_dissipation = e.contact_dissipation,
                    .viscous_dissipation = e.viscous_dissipation,
                    .mass_scaling_dissipation = e.mass_scaling_dissipation,
                    .external_work = e.external_work,
                    .balance_error = sim.balance_error()};
  if (run.compaction) summary.compaction = run.compaction->summarise();
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyState s = sim.body_state(static_cast<int>(b));
    BodySummary bs;
    bs.name = m.bodies[b].name;
    bs.mass = s.mass;
    bs.added_mass = s.added_mass;
    bs.volume = s.volume;
    bs.com = {s.com.x(), s.com.y(), s.com.z()};
    bs.vcom = {s.vcom.x(), s.vcom.y(), s.vcom.z()};
    bs.angular_velocity = {s.angular_velocity.x(), s.angular_velocity.y(), s.angular_velocity.z()};
    bs.kinetic_energy = s.kinetic_energy;
    bs.bbox_min = {s.bbox_min.x(), s.bbox_min.y(), s.bbox_min.z()};
    bs.bbox_max = {s.bbox_max.x(), s.bbox_max.y(), s.bbox_max.z()};
    // equivalent plastic strain never decreases: its value now is the run's maximum
    bs.max_equivalent_plastic_strain = s.max_equivalent_plastic_strain;
    bs.max_principal_stress = run.peaks.principal_stress(b);
    bs.max_principal_stress_time = run.peaks.principal_stress_time(b);
    bs.coefficient_of_restitution = restitution[b].result();
    summary.bodies.push_back(bs);
  }
  return summary;
}

}  // namespace femdem
