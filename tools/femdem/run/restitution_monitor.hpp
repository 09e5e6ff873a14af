// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Coefficient of restitution of one body (docs/OUTPUTS.md, summary.json): the centre-of-mass
// speed just after its last contact over the speed just before its first, and
// sqrt(KE_after / KE_before). Fed every step, since a contact may last only a few steps.
#include <cmath>
#include <optional>

#include "engine/simulation.hpp"
#include "engine/state_archive.hpp"
#include "io/results/summary_writer.hpp"

namespace femdem {

class RestitutionMonitor {
 public:
  void observe(const BodyState& s) {
    const bool contact = s.contact_force.squaredNorm() > 0.0;
    if (contact && !touched_) {
      touched_ = true;
      speed_before_ = last_speed_;
      ke_before_ = last_ke_;
    }
    if (!contact && in_contact_) {
      speed_after_ = s.vcom.norm();
      ke_after_ = s.kinetic_energy;
    }
    in_contact_ = contact;
    last_speed_ = s.vcom.norm();
    last_ke_ = s.kinetic_energy;
  }
  // Null unless the body touched something and has left it.
  std::optional<Restitution> result() const {
    if (!touched_ || in_contact_ || speed_before_ <= 0.0 || ke_before_ <= 0.0) return std::nullopt;
    return Restitution{speed_after_ / speed_before_, std::sqrt(ke_after_ / ke_before_)};
  }

  // One body's monitor, under the caller's scope.
  void exchange_state(StateArchive& a) {
    a.value("touched", touched_);
    a.value("in_contact", in_contact_);
    a.value("speed_before", speed_before_);
    a.value("ke_before", ke_before_);
    a.value("speed_after", speed_after_);
    a.value("ke_after", ke_after_);
    a.value("last_speed", last_speed_);
    a.value("last_ke", last_ke_);
  }

 private:
  bool touched_ = false, in_contact_ = false;
  double speed_before_ = 0.0, ke_before_ = 0.0;
  double speed_after_ = 0.0, ke_after_ = 0.0;
  double last_speed_ = 0.0, last_ke_ = 0.0;
};

}  // namespace femdem
