// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The progress line of a run on standard output: rewritten in place on a terminal (every 0.5 s);
// when the output goes to a file or pipe, a new line each time the run passes another tenth of
// its end time or a minute after the last line, whichever comes first; nothing with --quiet.
// The rate and the estimate count from where this run started (a resumed run starts at its
// checkpoint's time and step, not at zero).
#include <chrono>
#include <cstdint>

namespace femdem {

class Simulation;

class ProgressLine {
 public:
  // The loop starts now, from `sim`'s time and step.
  ProgressLine(bool quiet, double end_time, const Simulation& sim);
  // Cheap to call every step: looks at the clock every 16 steps.
  void update(const Simulation& sim);
  void clear();       // the end of a run: wipe the line on a terminal
  void break_line();  // before an error message: end the line on a terminal

 private:
  bool quiet_, tty_;
  double end_;
  double time_at_start_;
  std::chrono::steady_clock::time_point start_, last_;
  std::int64_t steps_at_last_;
  int tenths_printed_ = 0;  // piped: the tenths of the end time passed at the last line
};

}  // namespace femdem
