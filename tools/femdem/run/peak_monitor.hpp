// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The run's extremes that summary.json reports, sampled with the history rows: each body's
// largest principal stress, the deepest overlaps between bodies and behind walls (absolute and
// over the element size), and when they occurred. An overlap beyond kOverlapWarning of the
// element size means the contact is soft for its load (the penalty, not the bodies, carries the
// deformation there): the run log warns of it once.
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/state_archive.hpp"
#include "tools/femdem/run/history_sample.hpp"

namespace femdem {

// The overlap per element size beyond which the run log warns.
inline constexpr double kOverlapWarning = 0.1;

class PeakMonitor {
 public:
  explicit PeakMonitor(std::size_t bodies)
      : principal_(bodies, -HUGE_VAL), principal_time_(bodies, 0.0) {}

  void observe(const HistorySample& s) {
    for (std::size_t b = 0; b < s.bodies.size(); ++b)
      if (s.bodies[b].max_principal_stress > principal_[b])
        principal_[b] = s.bodies[b].max_principal_stress, principal_time_[b] = s.time;
    if (s.max_penetration && *s.max_penetration > penetration_)
      penetration_ = *s.max_penetration, penetration_time_ = s.time;
    if (s.max_penetration_per_size > penetration_per_size_)
      penetration_per_size_ = s.max_penetration_per_size, penetration_per_size_time_ = s.time;
    for (std::size_t w = 0; w < s.walls.size(); ++w) {
      wall_penetration_ = std::max(wall_penetration_, s.walls[w].penetration);
      if (s.walls[w].penetration_per_size > wall_per_size_)
        wall_per_size_ = s.walls[w].penetration_per_size, wall_per_size_time_ = s.time,
        wall_per_size_index_ = w;
    }
  }
  // True once, at the first sample whose overlap per element size exceeds kOverlapWarning.
  bool overlap_warning_due() {
    if (warned_ || std::max(penetration_per_size_, wall_per_size_) <= kOverlapWarning) return false;
    return warned_ = true;
  }
  double principal_stress(std::size_t body) const { return principal_[body]; }
  double principal_stress_time(std::size_t body) const { return principal_time_[body]; }
  double penetration() const { return penetration_; }
  double penetration_time() const { return penetration_time_; }
  double penetration_per_size() const { return penetration_per_size_; }
  double penetration_per_size_time() const { return penetration_per_size_time_; }
  double wall_penetration() const { return wall_penetration_; }
  double wall_penetration_per_size() const { return wall_per_size_; }
  double wall_penetration_per_size_time() const { return wall_per_size_time_; }
  std::size_t wall_penetration_per_size_wall() const { return wall_per_size_index_; }

  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "peaks");
    a.array("principal", principal_);
    a.array("principal_time", principal_time_);
    a.value("penetration", penetration_);
    a.value("penetration_time", penetration_time_);
    a.value("penetration_per_size", penetration_per_size_);
    a.value("penetration_per_size_time", penetration_per_size_time_);
    a.value("wall_penetration", wall_penetration_);
    a.value("wall_per_size", wall_per_size_);
    a.value("wall_per_size_time", wall_per_size_time_);
    a.value("wall_per_size_index", wall_per_size_index_);
    a.value("warned", warned_);
  }

 private:
  std::vector<double> principal_, principal_time_;
  double penetration_ = 0.0, penetration_time_ = 0.0;
  double penetration_per_size_ = 0.0, penetration_per_size_time_ = 0.0;
  double wall_penetration_ = 0.0, wall_per_size_ = 0.0, wall_per_size_time_ = 0.0;
  std::size_t wall_per_size_index_ = 0;
  bool warned_ = false;
};

}  // namespace femdem
