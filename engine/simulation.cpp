// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/simulation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "engine/distributed/patch_motions.hpp"
#include "engine/element_gather.hpp"
#include "engine/element_kernel.hpp"
#include "engine/errors.hpp"
#include "engine/exact_sum.hpp"
#include "engine/parallel_threshold.hpp"
#include "engine/rolling_resistance.hpp"
#include "materials/symmetric_eigen3.hpp"

namespace femdem {
namespace {

std::vector<MaterialKernel> compile_kernels(const std::vector<MaterialParams>& materials) {
  std::vector<MaterialKernel> out;
  for (const MaterialParams& p : materials) out.push_back(compile_material(p));
  return out;
}

// A global element's body and its index in the body, in one process (dist null) or on any rank
// (whether or not it holds the element).
std::pair<int, std::int64_t> element_of_body(const Model& m, const Distribution* dist,
                                             std::int64_t global) {
  if (!dist) {
    const int body = m.element_body[global];
    return {body, global - m.bodies[body].first_element};
  }
  const std::vector<std::int32_t>& first = dist->part.body_first_element;
  const auto body =
      static_cast<int>(std::upper_bound(first.begin(), first.end(), global) - first.begin() - 1);
  return {body, global - first[body]};
}

}  // namespace

Simulation::Simulation(Model model, std::optional<Distribution> distribution)
    : model_(std::move(model)),
      dist_(std::move(distribution)),
      kernels_(compile_kernels(model_.materials)),
      element_pass_(model_, kernels_),
      wall_contact_(model_, model_.patch_loads(), dist_ ? &*dist_ : nullptr),
      body_contact_(model_, dist_ ? &*dist_ : nullptr) {
  const auto nn = static_cast<std::size_t>(model_.node_count);
  const auto ne = static_cast<std::size_t>(model_.element_count);
  if (dist_) check_distributable(model_, dist_->part);
  accel_.assign(3 * nn, 0.0);
  reaction_.assign(3 * nn, 0.0);
  elem_force_.assign(30 * ne, 0.0);
  elem_result_.assign(ne, ElementResult{});
  elem_energy_.assign(ne, 0.0);
  elem_dt_.assign(ne, 0.0);
  elem_dissipation_.assign(ne, 0.0);
  elem_viscous_power_.assign(ne, 0.0);
  for (std::int32_t e = 0; e < model_.element_count; ++e)
    has_nodal_fbar_ = has_nodal_fbar_ || model_.element_fbar[e] == FbarMode::Nodal;
  if (has_nodal_fbar_) {
    // reference volume around each corner node, over the nodal-F-bar elements that share it
    elem_volume_.assign(ne, 0.0);
    elem_pressure_weight_.assign(4 * ne, 0.0);
    elem_volume_gradient_.assign(30 * ne, 0.0);
    node_J_.assign(nn, 1.0);
    node_Q_.assign(nn, 0.0);
    node_ref_volume_.assign(nn, 0.0);
    for (std::int32_t n = 0; n < model_.node_count; ++n)
      for (std::int32_t k = model_.node_elem_offset[n]; k < model_.node_elem_offset[n + 1]; ++k) {
        const std::int32_t slot = model_.node_elem_slot[k], e = slot / 10;
        if (slot % 10 >= 4 || model_.element_fbar[e] != FbarMode::Nodal) continue;
        const double* w = model_.gauss_weight.data() + 4 * static_cast<std::size_t>(e);
        node_ref_volume_[n] += w[0] + w[1] + w[2] + w[3];
      }
  }
  for (const MaterialParams& p : model_.materials) {
    CompiledMaterial c;
    c.wave_speed = std::sqrt(p.p_wave_modulus() / p.density);
    c.density = p.density;
    compiled_.push_back(std::move(c));
  }
  // A node no element uses has no mass: hold it still rather than divide by zero.
  for (std::size_t n = 0; n < nn; ++n)
    if (!(model_.mass[n] > 0.0))
      for (int k = 0; k < 3; ++k) model_.dof_mode[3 * n + k] = 1, model_.v[3 * n + k] = 0.0;
  // the few driven dofs, so the work of the supports does not scan every node each step
  for (std::size_t i = 0; i < 3 * nn; ++i)
    if (model_.dof_mode[i] == 2 && owns_node(static_cast<std::int64_t>(i / 3)))
      driven_dofs_.push_back(i);
  body_added_mass_.assign(model_.bodies.size(), 0.0);
  body_added_at_start_.assign(model_.bodies.size(), 0.0);
  if (model_.settings.stable_step == SimulationSettings::StableStep::assembled) {
    frequency_.emplace(model_);
  }
  if (model_.settings.mass_scaling_time_step > 0.0) elem_mass_scale_.assign(ne, 1.0);
  // the energy a uniform strain of 1.4e-3 stores in the whole model (rho c^2 eps^2 / 2 per
  // volume): the scale below which an energy error does not stop a run
  ExactSum floor[1] = {exact_sum_of(model_.element_count, [&](std::int64_t e) {
    if (!owns_element(e)) return 0.0;
    const CompiledMaterial& cm = compiled_[model_.element_material[e]];
    const double* w = model_.gauss_weight.data() + 4 * e;
    return 1e-6 * cm.density * cm.wave_speed * cm.wave_speed * (w[0] + w[1] + w[2] + w[3]);
  })};
  reduce(floor);
  energy_floor_ = floor[0].value();
  elem_scratch_.assign(ne, 0.0);
  if (model_.patch_loads()) {
    patch_loads_.resize(model_.bodies.size());
    body_contact_.collect_patches(true);
  }
  compute_forces(0.0);
  update_force_driven_walls(0.0);
  // mass scaling at t = 0 keeps the given initial velocities: it is part of the initial state
  set_time_step();
  initial_balance_ = energies().balance();
  max_energy_ = std::fabs(initial_balance_);
}

void Simulation::compute_forces(double step_dt) {
  Model& m = model_;
  const std::int32_t ne = m.element_count;
  const std::int32_t nn = m.node_count;
  const double* x = m.x.data();

  const bool bulk_viscosity =
      m.settings.bulk_viscosity_linear > 0.0 || m.settings.bulk_viscosity_quadratic > 0.0;

  // 0. nodal F-bar: each corner node's volume ratio over the elements around it
  if (has_nodal_fbar_) {
    element_pass_.nodal_volumes(m, elem_volume_.data());
#pragma omp parallel for schedule(static) if (nn > kParallelMinNodes)
    for (std::int32_t n = 0; n < nn; ++n) {
      if (!(node_ref_volume_[n] > 0.0)) continue;
      double v = 0.0;
      for (std::int32_t k = m.node_elem_offset[n]; k < m.node_elem_offset[n + 1]; ++k) {
        const std::int32_t slot = m.node_elem_slot[k], e = slot / 10;
        if (slot % 10 < 4 && m.element_fbar[e] == FbarMode::Nodal) v += elem_volume_[e];
      }
      node_J_[n] = v / node_ref_volume_[n];
    }
  }

  // 1. elements: independent, written to per-element buffers (engine/element_pass.hpp)
  NodalFbarArrays nodal;
  if (has_nodal_fbar_)
    nodal = {node_J_.data(), elem_pressure_weight_.data(), elem_volume_gradient_.data()};
  element_pass_.update(m, kernels_, step_dt, nodal, elem_force_, elem_result_);
  // 1a. per element: its energies, bulk viscosity and stable step. The run must stop at the
  // first inverted element (lowest index: min is exact, so the same element whatever the threads)
  std::int32_t first_bad = ne;
#pragma omp parallel for schedule(static) reduction(min : first_bad) if (ne > kParallelMinElements)
  for (std::int32_t e = 0; e < ne; ++e) {
    const ElementResult& r = elem_result_[e];
    const CompiledMaterial& cm = compiled_[m.element_material[e]];
    elem_energy_[e] = r.min_J > 0.0 ? r.energy : -HUGE_VAL;
    elem_dissipation_[e] = r.dissipation;
    double cd = cm.wave_speed;
    const double h = r.min_altitude;
    if (bulk_viscosity && r.min_J > 0.0) {
      const std::size_t es = static_cast<std::size_t>(e);
      const Tet10& c = m.conn[e];
      double xe[30], ve[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) {
          xe[3 * a + k] = x[3 * c[a] + k];
          ve[3 * a + k] = m.v[3 * c[a] + k];
        }
      // l: the element's length across its thinnest direction (corner altitude; TET10 has two
      // nodes along it)
      elem_viscous_power_[e] = tet10_bulk_viscosity(
          xe, ve, m.dNdX.data() + 120 * es, m.gauss_weight.data() + 4 * es, cm.density, cd, 0.5 * h,
          m.settings.bulk_viscosity_linear, m.settings.bulk_viscosity_quadratic,
          elem_force_.data() + 30 * es, cd);
    }
    elem_dt_[e] = (r.min_J > 0.0 && h > 0.0) ? 2.0 * h / (m.frequency_factor[e] * cd) : -1.0;
    if (elem_energy_[e] == -HUGE_VAL || !(elem_dt_[e] > 0.0)) first_bad = std::min(first_bad, e);
  }

  // 1b. nodal F-bar pressure: gather each corner's dW/dJbar, then every element adds
  // sum_c Q_c / V_c times the gradient of its own volume (written by the element pass)
  if (has_nodal_fbar_) {
#pragma omp parallel for schedule(static) if (nn > kParallelMinNodes)
    for (std::int32_t n = 0; n < nn; ++n) {
      if (!(node_ref_volume_[n] > 0.0)) continue;
      double Q = 0.0;
      for (std::int32_t k = m.node_elem_offset[n]; k < m.node_elem_offset[n + 1]; ++k) {
        const std::int32_t slot = m.node_elem_slot[k], e = slot / 10;
        if (slot % 10 < 4 && m.element_fbar[e] == FbarMode::Nodal)
          Q += elem_pressure_weight_[4 * static_cast<std::size_t>(e) + slot % 10];
      }
      node_Q_[n] = Q / node_ref_volume_[n];
    }
#pragma omp parallel for schedule(static) if (ne > kParallelMinElements)
    for (std::int32_t e = 0; e < ne; ++e) {
      if (m.element_fbar[e] != FbarMode::Nodal) continue;
      const Tet10& c = m.conn[e];
      const double s = node_Q_[c[0]] + node_Q_[c[1]] + node_Q_[c[2]] + node_Q_[c[3]];
      const std::size_t es = static_cast<std::size_t>(e);
      const double* vg = elem_volume_gradient_.data() + 30 * es;
      double* fe = elem_force_.data() + 30 * es;
      for (int i = 0; i < 30; ++i) fe[i] += s * vg[i];
    }
  }

  // 2. gather per node in the fixed CSR order: same bits for any thread count
  gather_element_forces(m, elem_force_.data(), m.f_int.data());

  // (in a distributed run, the lowest global element over the ranks: every rank stops alike)
  std::int64_t bad = first_bad < ne ? first_bad : INT64_MAX;
  if (dist_) {
    if (bad != INT64_MAX) bad = dist_->part.elements[first_bad];
    bad = dist_->comm->min(bad);
  }
  if (bad != INT64_MAX) {
    const auto [body, index] = element_of_body(m, dist_ ? &*dist_ : nullptr, bad);
    const Body& b = m.bodies[body];
    std::ostringstream msg;
    msg << "element " << index << " of body '" << b.name
        << "' inverted (det F <= 0) at t = " << time_ << " s, step " << steps_ << ". " << advice();
    throw InstabilityError(msg.str());
  }
  // exact sums (engine/exact_sum.hpp): in parallel, the same bits with any threads and ranks
  auto owned_sum = [&](const std::vector<double>& per_element) {
    return exact_sum_of(ne, [&](std::int64_t e) { return owns_element(e) ? per_element[e] : 0.0; });
  };
  ExactSum element_sums[3] = {owned_sum(elem_energy_), owned_sum(elem_dissipation_),
                              bulk_viscosity ? owned_sum(elem_viscous_power_) : ExactSum{}};
  reduce(element_sums);
  internal_energy_ = element_sums[0].value();
  plastic_dissipation_ += element_sums[1].value();
  if (bulk_viscosity) viscous_dissipation_ += element_sums[2].value() * step_dt;

  // 3. contact, in a fixed order: bodies on walls (engine/wall_contact.cpp), then bodies on
  // each other (engine/body_contact.cpp), each adding to f_contact and to the step's sums
  std::fill(m.f_contact.begin(), m.f_contact.end(), 0.0);
  ContactSums sums;
  ContactModel* const contacts[] = {&wall_contact_, &body_contact_};
  for (ContactModel* c : contacts)
    if (c->active()) c->compute(m, step_dt, m.f_contact, sums);
  // 3c. impact damping and rolling resistance on the bodies' rigid motions, per contact patch
  if (m.patch_loads()) {
    patches_.clear();
    body_contact_.append_patches(patches_);
    wall_contact_.append_patches(patches_);
    prepare_patch_loads(m, patches_, accel_, 0.5 * step_dt, patch_loads_);
    if (dist_) share_patch_motions(m, *dist_, patches_, patch_loads_);
    if (m.contact.impact_damping > 0.0)
      damp_impacts(m, m.contact.impact_damping, patches_, patch_loads_);
    if (m.resists_rolling()) resist_rolling(m, patches_, step_dt, patch_loads_);
    // their power and the walls' reactions, each counted once over the ranks
    std::vector<ExactSum>& loads = patch_loads_.wall_force;
    loads.push_back(patch_loads_.power);
    reduce(loads);
    sums.damping_power += loads.back().value();
    for (std::size_t w = 0; w < m.walls.size(); ++w)
      for (int k = 0; k < 3; ++k) m.walls[w].force[k] += loads[3 * w + k].value();
    apply_patch_loads(m, patch_loads_);
  }
  const double contact = sums.energy, friction_dissipated = sums.friction_dissipated,
               damping_power = sums.damping_power;
  contact_energy_ = contact;
  contact_dissipation_ += friction_dissipated - damping_power * step_dt;

  // 3d. deformation damping: part of the internal force (a viscous stress of the bodies), work
  // counted with the bulk viscosity's
  if (m.settings.deformation_damping > 0.0)
    viscous_dissipation_ += damp_deformation(m.settings.deformation_damping) * step_dt;

  // 4. accelerations and reactions of constrained dofs
  const Vec3& g = m.settings.gravity;
#pragma omp parallel for schedule(static) if (nn > kParallelMinNodes)
  for (std::int32_t n = 0; n < nn; ++n) {
    const double mass = m.mass[n];
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * static_cast<std::size_t>(n) + k;
      const double f = m.f_contact[i] - m.f_int[i] + mass * g[k];
      if (m.dof_mode[i] == 0) {
        accel_[i] = f / mass;
        reaction_[i] = 0.0;
      } else {
        accel_[i] = 0.0;
        reaction_[i] = -f;  // the support holds the node at constant velocity
      }
    }
  }
}

double Simulation::damp_deformation(double alpha) {
  Model& m = model_;
  // per body (in parallel: a node belongs to one body), then summed in body order
  const auto nb = static_cast<std::int64_t>(m.bodies.size());
  body_power_.assign(m.bodies.size(), 0.0);
#pragma omp parallel for schedule(dynamic, 1) if (nb > 1 && m.node_count > kParallelMinElements)
  for (std::int64_t bi = 0; bi < nb; ++bi) {
    const Body& b = m.bodies[bi];
    if (b.fixed) continue;
    const std::int32_t n0 = b.first_node, n1 = b.first_node + b.node_count;
    // the rigid motion with the body's momentum and angular momentum (half-step velocities)
    const RigidMotion rm = rigid_motion(m, b);
    if (!(rm.mass > 0.0)) continue;
    const Vec3& c = rm.centre;
    const Vec3& vc = rm.velocity;
    const Vec3& w = rm.angular_velocity;
    double power = 0.0;
    for (std::int32_t n = n0; n < n1; ++n) {
      const double mn = m.mass[n];
      const Vec3 r = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]) - c;
      const Vec3 dv = Vec3(m.v[3 * n], m.v[3 * n + 1], m.v[3 * n + 2]) - vc - w.cross(r);
      for (int k = 0; k < 3; ++k) m.f_int[3 * n + k] += alpha * mn * dv[k];
      // sum m dv . v_rigid = 0 by construction, so the power is -alpha sum m |dv|^2
      power += alpha * mn * dv.squaredNorm();
    }
    body_power_[bi] = power;
  }
  // (exact: a rank has the bodies it holds whole, the others' powers are 0 here)
  ExactSum power[1] = {exact_sum_of(nb, [&](std::int64_t bi) { return body_power_[bi]; })};
  reduce(power);
  return power[0].value();
}

void Simulation::check_distributable(const Model& m, const LocalPart& part) {
  const SimulationSettings& s = m.settings;
  std::string missing;
  const auto& body_rank = part.body_rank;
  const bool cut = std::find(body_rank.begin(), body_rank.end(), -1) != body_rank.end();
  if (cut && s.deformation_damping > 0.0)
    missing = "simulation.deformation_damping on a body cut among ranks";
  else if (cut && m.patch_loads())
    missing = "contact.impact_damping or rolling_resistance on a body cut among ranks";

  if (!missing.empty())
    throw InputError("distributed runs cannot yet do this scene: " + missing +
                     " (issue 23, docs/ARCHITECTURE.md \"Distributed runs\"); run it as one "
                     "process");
}

std::string Simulation::advice() const {
  std::ostringstream a;
  const SimulationSettings& s = model_.settings;
  if (s.time_step > 0.0 && s.time_step > 0.9 * stable_dt_) {
    a << "simulation.time_step = " << s.time_step << " s is above the stable step (" << stable_dt_
      << " s at the last check): lower it, or remove it to let femdem choose.";
  } else {
    a << "The step may be too large for this deformation, or the mesh too coarse or distorted: "
         "lower simulation.time_step_safety (now "
      << s.safety() << "), refine the mesh, or check the loading and penalty factors.";
  }
  return a.str();
}

bool Simulation::scale_masses(double element_dt_needed) {
  Model& m = model_;
  const bool conserve_momentum = steps_ > 0;
  std::int32_t worst = -1;  // the element that needed the most mass this time
  double worst_added = 0.0;
  // Every held element is scaled here (an owned node then gets every element's share, in
  // element order, as in one process); what is counted is what this rank owns, in exact sums
  // added over the ranks (in one process too, so that the bits agree).
  ExactSum dissipated[1];
  std::vector<std::pair<std::int32_t, double>> added_to;  // (body, kg) per owned element
  for (std::int32_t e = 0; e < m.element_count; ++e) {
    double& s = elem_mass_scale_[e];
    const double dt_e = elem_dt_[e] * std::sqrt(s);  // the step bound scales with sqrt(mass)
    if (!(dt_e > 0.0) || dt_e >= element_dt_needed) continue;
    // a hair above the exact factor so that round-off cannot leave the bound just below
    const double s_new = s * (element_dt_needed / dt_e) * (element_dt_needed / dt_e) * (1 + 1e-12);
    const double* w = m.gauss_weight.data() + 4 * static_cast<std::size_t>(e);
    const double added =
        (s_new - s) * m.materials[m.element_material[e]].density * (w[0] + w[1] + w[2] + w[3]);
    s = s_new;
    if (owns_element(e)) {
      added_to.emplace_back(m.element_body[e], added);
      if (added > worst_added) worst_added = added, worst = e;
    }
    const Tet10& c = m.conn[e];
    for (int a = 0; a < 10; ++a) {
      const std::int32_t n = c[a];
      const double m_old = m.mass[n];
      const double m_new = m_old + added * (a < 4 ? tet10::kHrzCorner : tet10::kHrzMidEdge);
      const double ratio = m_old / m_new;
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = 3 * static_cast<std::size_t>(n) + k;
        if (m.dof_mode[i] != 0) continue;  // held or driven: its velocity is prescribed
        accel_[i] *= ratio;                // the same force now moves more mass
        if (conserve_momentum) {
          // a free node gaining mass keeps its momentum and gives up kinetic energy
          if (owns_node(n)) dissipated[0].add(0.5 * m_old * m.v[i] * m.v[i] * (1.0 - ratio));
          m.v[i] *= ratio;
        }
      }
      m.mass[n] = m_new;
    }
  }
  reduce(dissipated);
  mass_scaling_dissipation_ += dissipated[0].value();
  if (dist_ ? !dist_->comm->all(added_to.empty()) : !added_to.empty()) {
    std::vector<ExactSum> per_body(m.bodies.size());
    for (const auto& [b, kg] : added_to) per_body[b].add(kg);
    reduce(per_body);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) body_added_mass_[b] += per_body[b].value();
  }
  // the element that needed the most, by global number (the lowest of equals, as one
  // process's first), and its own step
  std::int64_t worst_global = worst >= 0 ? (dist_ ? dist_->part.elements[worst] : worst) : -1;
  double worst_dt = worst >= 0 ? elem_dt_[worst] : HUGE_VAL;
  if (dist_) {
    const double most = -reduce_min(-worst_added);
    const std::int64_t mine = worst >= 0 && worst_added == most ? worst_global : INT64_MAX;
    const std::int64_t first = dist_->comm->min(mine);
    worst_global = first == INT64_MAX ? -1 : first;
    worst_dt = reduce_min(first != INT64_MAX && mine == first ? worst_dt : HUGE_VAL);
    // a ghost node got only its held elements' shares: its owner's mass (the assembled
    // estimate reads the ghosts' masses)
    if (worst_global >= 0) dist_->comm->exchange(dist_->part, m.mass.data(), 1);
  }
  // At the start the mesh is what the user gave (the run log reports the added mass); later,
  // a body gaining a large share of its mass has an element being crushed flat, whose nodes
  // would carry a huge mass (and gravity on it) while the run still looks balanced.
  // The limit counts what was added after the start only (docs/SCENES.md).
  if (!conserve_momentum) {
    body_added_at_start_ = body_added_mass_;
    return worst_global >= 0;
  }
  if (worst_global < 0) return false;
  const auto [body, index] = element_of_body(m, dist_ ? &*dist_ : nullptr, worst_global);
  const Body& b = m.bodies[body];
  const double added = body_added_mass_[body] - body_added_at_start_[body];
  if (added <= m.settings.mass_scaling_limit * b.mass) return true;
  std::ostringstream msg;
  msg << "mass scaling has added " << added << " kg to body '" << b.name << "' since the start ("
      << 100.0 * added / b.mass << " % of its mass, more than simulation.mass_scaling_limit = "
      << m.settings.mass_scaling_limit << ") at t = " << time_ << " s, step " << steps_
      << ": element " << index << " of the body is being crushed (its own "
      << "stable step fell to " << worst_dt << " s). The results would no longer be "
      << "physical. Stiffen the contact (penalty_factor), lower the impact speed, refine the "
      << "mesh, or raise simulation.mass_scaling_limit if this much added mass is acceptable.";
  throw InstabilityError(msg.str());
}

double Simulation::element_and_wall_bound() {
  const Model& m = model_;
  // (min is exact: the same bits whatever the threads)
  double dt_el = HUGE_VAL;
  const auto ne = static_cast<std::int64_t>(elem_dt_.size());
  if (elem_mass_scale_.empty()) {
#pragma omp parallel for schedule(static) reduction(min : dt_el) if (ne > kParallelMinElements)
    for (std::int64_t e = 0; e < ne; ++e) dt_el = std::min(dt_el, elem_dt_[e]);
  } else {
#pragma omp parallel for schedule(static) reduction(min : dt_el) if (ne > kParallelMinElements)
    for (std::int64_t e = 0; e < ne; ++e)
      dt_el = std::min(dt_el, elem_dt_[e] * std::sqrt(elem_mass_scale_[e]));
  }
  dt_el = reduce_min(dt_el);
  return wall_contact_.active() ? wall_contact_.stable_step(m, dt_el, dt_el) : dt_el;
}

namespace {
// A step dt of the rest of the model lowered by a term omega2 added to its frequency squared.
double with_added_frequency(double dt, double omega2) {
  if (!(omega2 > 0.0)) return dt;
  const double omega = 2.0 / dt;
  return 2.0 / std::sqrt(omega * omega + omega2);
}
}  // namespace

void Simulation::set_time_step() {
  const SimulationSettings& s = model_.settings;
  // Mass scaling raises the elements' bound to the requested step (over the safety factor); the
  // assembled estimate, which sees the new masses at once, may allow a longer step still. (Aiming
  // the bound lower by the measured ratio would add less mass, but a global ratio does not say
  // which elements it came from: measured, it fell as the scaled elements caught up, and the
  // rescaling ran away.)
  const bool added =
      !elem_mass_scale_.empty() && scale_masses(s.mass_scaling_time_step / s.safety());
  // The elements and the walls' node springs (each on one node) are measured by the assembled
  // estimate; the springs between bodies are added every step by Weyl's inequality (the largest
  // eigenvalue of a sum is at most the sum of the largest eigenvalues), from a bound that holds
  // for whatever pairs touch now, with a flat contact's stiffness on the pairs that may touch
  // within the step (BodyContact::omega_squared_bound). A contact that starts between two
  // estimates is then counted from its first step without a ratio measured before it existed,
  // and the pairs the candidate list holds but that cannot touch yet cost nothing.
  const double bound = element_and_wall_bound();
  const double rest = frequency_ ? assembled_step(bound, added && steps_ == 0) : bound;
  // (the pairs that may touch within the longest step this can give)
  const double omega2 =
      body_contact_.active()
          ? body_contact_.omega_squared_bound(
                model_, s.time_step > 0.0 ? s.time_step : s.safety() * std::max(rest, bound))
          : 0.0;
  stable_bound_ = with_added_frequency(bound, omega2);
  const double dt = with_added_frequency(rest, omega2);
  stable_dt_ = dt;
  dt_ = s.time_step > 0.0 ? s.time_step : s.safety() * dt;
}

double Simulation::assembled_step(double bound, bool force) {
  const Model& m = model_;
  // Between estimates the bound follows the elements' shapes and the walls' springs every step;
  // the step keeps the ratio to it that the last estimate measured. A bound that has moved by
  // more than kRecheck since (a node reaching a wall, an element being crushed) is re-estimated
  // at once, at most every kMinGap steps, so a fast change cannot run far on an old ratio.
  constexpr double kRecheck = 0.1;
  constexpr std::int64_t kMinGap = 5;
  // The ratio is kept within what the bound can be wrong by: the assembled frequency is at
  // least that of the lightest node on its stiffest spring, and the element bound is at most
  // this many times too high (3.2 measured on the crushed foot of the Taylor bar): a larger
  // ratio means the estimate went wrong, and the step stays within this of the bound.
  constexpr double kMaxRatio = 10.0;
  const std::int64_t since = steps_ - estimate_step_;
  const bool moved = !(std::fabs(bound / bound_at_estimate_ - 1.0) <= kRecheck);
  if (force || frequency_estimates_ == 0 || since >= m.settings.stable_step_interval ||
      (moved && since >= kMinGap)) {
    springs_.clear();
    if (wall_contact_.active()) wall_contact_.append_springs(m, springs_);
    const FrequencyEstimate est = frequency_->estimate(m, springs_, dist_ ? &*dist_ : nullptr);
    ++frequency_estimates_;
    frequency_iterations_ += est.iterations;
    estimate_step_ = steps_;
    bound_at_estimate_ = bound;
    // the walls' dashpots shrink the step as in the bound
    const double dt = est.omega > 0.0 ? 2.0 * wall_contact_.damping_factor() / est.omega : bound;
    step_ratio_ = std::min(dt / bound, kMaxRatio);
  }
  return std::min(step_ratio_ * bound, wall_contact_.driven_wall_step());
}

void Simulation::step(double dt_limit) {
  Model& m = model_;
  const double dt = std::min(dt_, dt_limit);
  const std::int32_t nn = m.node_count;
  const Vec3& g = m.settings.gravity;

  // work of supports and walls over the step, trapezoidal in their forces
  auto boundary_power = [&]() {
    ExactSum supports[1];
    for (const std::size_t i : driven_dofs_) supports[0].add(reaction_[i] * m.dof_velocity[i]);
    reduce(supports);
    double p = supports[0].value();
    for (const auto& w : m.walls) p -= w.force.dot(w.velocity);
    return p;
  };
  const double power0 = boundary_power();

  // kick (half) + drift
  double gravity_work = 0.0;
#pragma omp parallel for schedule(static) if (nn > kParallelMinNodes)
  for (std::int32_t n = 0; n < nn; ++n) {
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * static_cast<std::size_t>(n) + k;
      if (m.dof_mode[i] == 0)
        m.v[i] += 0.5 * dt * accel_[i];
      else
        m.v[i] = (m.dof_mode[i] == 2) ? m.dof_velocity[i] : 0.0;
      m.x[i] += dt * m.v[i];
    }
  }
  // a distributed run: the ghosts' positions and half-step velocities from their owners, so
  // that everything the step reads from here on is what one process has
  if (dist_) {
    dist_->comm->exchange(dist_->part, m.x.data(), 3);
    dist_->comm->exchange(dist_->part, m.v.data(), 3);
  }
  if (g.squaredNorm() > 0.0) {
    ExactSum work[1] = {exact_sum_of(nn, [&](std::int64_t n) {
      if (!owns_node(n)) return 0.0;
      double w = 0.0;
      for (int k = 0; k < 3; ++k) w += m.mass[n] * g[k] * dt * m.v[3 * n + k];
      return w;
    })};
    reduce(work);
    gravity_work = work[0].value();
  }
  for (auto& w : m.walls) {
    if (w.force_driven()) {
      // the same kick-drift as the nodes, along the normal only
      w.velocity += (0.5 * dt * w.accel) * w.normal;
      w.point += dt * w.velocity;
      w.step_velocity = w.velocity;
    } else if (w.velocity_history.empty()) {
      w.point += dt * w.velocity;
    } else {
      // exact integral of the history; the velocity is the one at the end of the step
      const Vec3 d0 = history_displacement(w.velocity_history, time_);
      const Vec3 d1 = history_displacement(w.velocity_history, time_ + dt);
      w.point = w.point0 + d1;
      if (dt > 0.0) w.step_velocity = (d1 - d0) / dt;
      w.velocity = history_velocity(w.velocity_history, time_ + dt);
    }
  }
  time_ += dt;
  ++steps_;

  compute_forces(dt);
  update_force_driven_walls(dt);

  // second half kick
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(&& : finite) if (nn > kParallelMinNodes)
  for (std::int32_t n = 0; n < nn; ++n)
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 3 * static_cast<std::size_t>(n) + k;
      if (m.dof_mode[i] == 0) m.v[i] += 0.5 * dt * accel_[i];
      finite = finite && std::isfinite(m.v[i]) && std::isfinite(m.x[i]);
    }
  if (dist_) finite = dist_->comm->all(finite);
  if (!finite) {
    std::ostringstream msg;
    msg << "non-finite velocity or position at t = " << time_ << " s, step " << steps_
        << ": the run diverged. " << advice();
    throw InstabilityError(msg.str());
  }
  external_work_ += gravity_work + 0.5 * dt * (power0 + boundary_power());
  const Energies en = energies();
  max_energy_ =
      std::max({max_energy_, en.kinetic + en.internal + en.contact, std::fabs(en.external_work)});
  check_energy_balance(en);
  set_time_step();
}

void Simulation::check_energy_balance(const Energies& en) const {
  const double limit = model_.settings.energy_balance_limit;
  if (!(limit > 0.0)) return;
  // against the largest energy so far, but never less than the floor: while the energies are
  // tiny (the first touch of a wall), round-off and the trapezoidal work are large beside them
  if (!(std::fabs(en.balance() - initial_balance_) > limit * std::max(max_energy_, energy_floor_)))
    return;
  const double error = balance_error();
  std::ostringstream msg;
  msg << "the energy balance error reached " << 100.0 * error << " % at t = " << time_
      << " s, step " << steps_ << " (more than simulation.energy_balance_limit = " << 100.0 * limit
      << " %): the run " << (error > 0.0 ? "created" : "lost") << " energy that no load or "
      << "dissipation accounts for (now kinetic " << en.kinetic << " J, internal " << en.internal
      << " J, contact " << en.contact << " J, external work " << en.external_work << " J). "
      << advice();
  throw InstabilityError(msg.str());
}

void Simulation::update_force_driven_walls(double step_dt) {
  for (Wall& w : model_.walls) {
    if (!w.force_driven()) continue;
    // pushed along its normal by the prescribed load, held back by the bodies (w.force is the
    // force they exert on it)
    w.accel = (history_force(w.force_history, time_) + w.force.dot(w.normal)) / w.mass;
    w.velocity += (0.5 * step_dt * w.accel) * w.normal;
  }
}

}  // namespace femdem
