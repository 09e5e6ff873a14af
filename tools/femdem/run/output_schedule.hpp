// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// When a run writes a history row and a results frame, and how long its last steps are so that
// it lands on end_time exactly. Times within 1e-9 end_time of a due time count as due, so
// round-off in the accumulated time neither skips nor doubles an output.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include "engine/state_archive.hpp"

namespace femdem {

class OutputSchedule {
 public:
  OutputSchedule(double end_time, double output_interval, double history_interval)
      : end_(end_time),
        eps_(1e-9 * end_time),
        frame_interval_(output_interval),
        history_interval_(history_interval),
        next_frame_(output_interval),
        next_history_(history_interval) {}

  double end_time() const { return end_; }
  bool finished(double t) const { return !(t < end_ - eps_); }
  bool history_due(double t) const { return t >= next_history_ - eps_ || finished(t); }
  bool frame_due(double t) const { return t >= next_frame_ - eps_ || finished(t); }
  void history_written(double t) {
    while (next_history_ <= t + eps_) next_history_ += history_interval_;
  }
  void frame_written(double t) {
    while (next_frame_ <= t + eps_) next_frame_ += frame_interval_;
  }
  // At most how many frames the run writes after time t (one per interval, one at the end):
  // what the results writer makes its per-frame views for.
  std::int64_t frames_after(double t) const {
    const double n = std::floor(std::max(0.0, end_ - t) / frame_interval_ + 1e-6);
    return static_cast<std::int64_t>(std::min(n, 1e9)) + 1;
  }
  // The largest step the run may take from t when the stable step is dt: unlimited, except
  // that the last one or two steps split what remains rather than overshoot end_time.
  double step_limit(double t, double dt) const {
    const double remaining = end_ - t;
    if (remaining >= 1.5 * dt) return HUGE_VAL;
    return remaining > dt ? 0.5 * remaining : remaining;
  }

  // Saves or loads the next due times (the intervals and the end time are the resumed run's
  // own: the run's unless the resume sets them).
  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "output_schedule");
    a.value("next_frame", next_frame_);
    a.value("next_history", next_history_);
  }

 private:
  double end_, eps_;
  double frame_interval_, history_interval_;
  double next_frame_, next_history_;
};

}  // namespace femdem
