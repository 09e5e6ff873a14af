// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Bodies on rigid walls: every boundary node of a free body against every wall, with the node's
// penalty k = M A / h (M from engine/contact_stiffness.hpp, A the node's boundary area share, h
// the depth of the element behind it), through the scene's wall law (`[contact] wall_law`,
// contact/contact_laws.hpp). Holds the friction spring of each (node, wall), the per-(body, wall)
// patches for impact damping, each wall's contact stiffness for the step of force-driven walls,
// and each wall's deepest node. Serial in node order: the sums are deterministic.
#include <cmath>
#include <vector>

#include "contact/contact_laws.hpp"
#include "engine/contact_model.hpp"

namespace femdem {

class WallContact final : public ContactModel {
 public:
  WallContact(const Model& m, bool collect_patches);

  bool active() const override { return active_; }
  void compute(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums) override;
  void append_patches(std::vector<ContactPatch>& out) const override;
  // Per node near a wall (within one element depth) the element's frequency plus the spring's,
  // with the dashpot's shrink factor; and each force-driven wall's own frequency on the springs.
  double stable_step(const Model& m, double dt_element, double dt) override;
  // Every node within an element depth of a wall, with its spring (as stable_step counts them).
  void append_springs(const Model& m, std::vector<ContactSpring>& out) const override;
  // What the walls' dashpots and the force-driven walls' own frequency allow, from the last
  // stable_step(): the factor sqrt(1 + xi^2) - xi of the most damped wall with a node near it,
  // and the step of the stiffest force-driven wall on its springs (HUGE_VAL: none).
  double damping_factor() const { return damping_factor_; }
  // Per wall, the deepest node of the last compute(): its depth behind the wall (0: none), and
  // the largest depth over the element depth behind the node.
  double max_penetration(std::size_t wall) const { return penetration_[wall]; }
  double max_penetration_per_size(std::size_t wall) const { return penetration_per_size_[wall]; }
  double driven_wall_step() const { return driven_wall_step_; }

 private:
  template <class Law>
  void compute_with(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums);

  WallLaw law_;
  bool active_ = false;
  bool collect_patches_ = false;
  // Tangential spring stretch (3) per (surface node, wall); empty when no wall has friction.
  std::vector<double> stick_;
  std::vector<ContactPatch> patches_;  // per (body, wall), body-major
  std::vector<double> stiffness_;      // per wall: the contact stiffness near it
  std::vector<double> penetration_, penetration_per_size_;  // per wall, last compute()
  double damping_factor_ = 1.0, driven_wall_step_ = HUGE_VAL;
};

}  // namespace femdem
