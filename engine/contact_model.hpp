// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the time step asks of a kind of contact (bodies on rigid walls, bodies on each other):
// the forces at the current positions, their energy and dissipation, the touching patches that
// impact damping acts on. The Simulation holds one of each kind and calls them in a fixed order,
// so the sums (and so the bits) do not depend on anything else. A new kind of contact (e.g.
// cohesive bonds) is one class implementing this, added to Simulation's list with its term of the
// stable step (Simulation::set_time_step: WallContact::stable_step, or a bound of its springs'
// largest eigenvalue as BodyContact::omega_squared_bound); a new law for an existing kind is one
// file in contact/ and one name in contact/contact_laws.hpp.
#include <vector>

#include "contact/penalty_wall_law.hpp"
#include "engine/contact_patch.hpp"
#include "engine/model.hpp"

namespace femdem {

// The step's contact accounts, summed over the kinds in Simulation's order.
using ContactSums = WallContactSums;

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  // False when this kind can never act in the model: compute() and the rest are then skipped.
  virtual bool active() const = 0;
  // Adds the contact forces at the current positions to f (3 per node) and the step's energy
  // and dissipation to `sums`, advancing friction springs over step_dt (half-step velocities).
  virtual void compute(Model& m, double step_dt, std::vector<double>& f, ContactSums& sums) = 0;
  // Appends the touching patches of the last compute() (for impact damping).
  virtual void append_patches(std::vector<ContactPatch>& out) const = 0;
};

}  // namespace femdem
