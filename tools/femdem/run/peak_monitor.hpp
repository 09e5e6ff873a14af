// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The run's extremes that summary.json reports, sampled with the history rows: each body's
// largest principal stress and the deepest overlap between bodies, and when they occurred.
#include <cmath>
#include <vector>

#include "tools/femdem/run/history_sample.hpp"

namespace femdem {

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
  }
  double principal_stress(std::size_t body) const { return principal_[body]; }
  double principal_stress_time(std::size_t body) const { return principal_time_[body]; }
  double penetration() const { return penetration_; }
  double penetration_time() const { return penetration_time_; }

 private:
  std::vector<double> principal_, principal_time_;
  double penetration_ = 0.0, penetration_time_ = 0.0;
};

}  // namespace femdem
