// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The run's side of checkpoint.h5 (the engine's is Simulation::exchange_state): how the run's
// scene was made (RunOrigin, so that `femdem resume` can make it again), how far its outputs had
// got (OutputCounts: a resume cuts them back to there), and when a checkpoint is due
// (CheckpointClock). The monitors save their own state (exchange_state of each).
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/state_archive.hpp"

namespace femdem {

inline constexpr const char* kCheckpointFile = "checkpoint.h5";

struct RunOrigin {
  std::string scene_path;              // absolute
  std::vector<std::string> overrides;  // the run's --set, in order
  std::string resolved_toml;           // the resolved scene of the run (of its last resume)
};
void exchange_origin(StateArchive& a, RunOrigin& origin);
// The origin stored in a checkpoint (CheckpointError when it is not a readable checkpoint).
RunOrigin read_run_origin(const std::filesystem::path& checkpoint);

struct OutputCounts {
  std::uint64_t history_bytes = 0;  // of history.csv, header included
  std::int64_t history_rows = 0;
  std::int64_t frames = 0;  // of results.h5
  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "outputs");
    a.value("history_bytes", history_bytes);
    a.value("history_rows", history_rows);
    a.value("frames", frames);
  }
};

// Due every `interval` simulated seconds and every `wall_interval` wall seconds (0: never by
// that measure), counted from construction or the last checkpoint.
class CheckpointClock {
 public:
  CheckpointClock(double interval, double wall_interval, double time)
      : interval_(interval), wall_interval_(wall_interval) {
    written(time);
  }
  bool due(double time) const {
    if (interval_ > 0.0 && time >= next_ - 1e-9 * interval_) return true;
    return wall_interval_ > 0.0 &&
           std::chrono::duration<double>(Clock::now() - last_wall_).count() >= wall_interval_;
  }
  void written(double time) {
    if (interval_ > 0.0)
      while (next_ <= time + 1e-9 * interval_) next_ += interval_;
    last_wall_ = Clock::now();
  }

 private:
  using Clock = std::chrono::steady_clock;
  double interval_, wall_interval_;
  double next_ = 0.0;
  Clock::time_point last_wall_;
};

}  // namespace femdem
