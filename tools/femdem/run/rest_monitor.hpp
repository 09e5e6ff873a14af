// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Stop at rest (simulation.rest_kinetic_fraction, docs/SCENES.md): the run is at rest once the
// total kinetic energy has stayed below `fraction` of its peak so far for `hold` seconds,
// checked at the history rows.
#include "engine/state_archive.hpp"

namespace femdem {

class RestMonitor {
 public:
  RestMonitor(double fraction, double hold) : fraction_(fraction), hold_(hold) {}

  bool enabled() const { return fraction_ > 0.0; }
  void observe(double time, double kinetic) {
    if (!enabled()) return;
    if (kinetic > peak_) peak_ = kinetic, peak_time_ = time;
    if (peak_ > 0.0 && kinetic < fraction_ * peak_) {
      if (below_since_ < 0.0) below_since_ = time;
      if (time - below_since_ >= hold_ * (1.0 - 1e-9)) rest_time_ = time;
    } else {
      below_since_ = -1.0;
    }
  }
  bool at_rest() const { return rest_time_ >= 0.0; }
  double rest_time() const { return rest_time_; }  // -1 until at rest
  double fraction() const { return fraction_; }
  double hold() const { return hold_; }
  double peak() const { return peak_; }
  double peak_time() const { return peak_time_; }

  // Forgets a rest found (or being timed) under other criteria, keeping the peak: a resumed run
  // whose criteria changed looks for rest by its own.
  void rearm() { below_since_ = -1.0, rest_time_ = -1.0; }
  // Saves or loads what it has seen (the criteria are the resumed run's own).
  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "rest");
    a.value("peak", peak_);
    a.value("peak_time", peak_time_);
    a.value("below_since", below_since_);
    a.value("rest_time", rest_time_);
  }

 private:
  double fraction_, hold_;
  double peak_ = 0.0, peak_time_ = 0.0;
  double below_since_ = -1.0, rest_time_ = -1.0;
};

}  // namespace femdem
