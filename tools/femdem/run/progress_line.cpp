// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/progress_line.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "engine/simulation.hpp"
#include "tools/femdem/run/run_log.hpp"

namespace femdem {

ProgressLine::ProgressLine(bool quiet, double end_time, const Simulation& sim)
    : quiet_(quiet),
      tty_(!quiet && isatty(STDOUT_FILENO)),
      end_(end_time),
      time_at_start_(sim.time()),
      start_(std::chrono::steady_clock::now()),
      last_(start_),
      steps_at_last_(sim.steps()),
      tenths_printed_(
          end_time > 0.0 ? static_cast<int>(std::min(10.0, 10.0 * sim.time() / end_time)) : 0) {}

void ProgressLine::update(const Simulation& sim) {
  if ((sim.steps() & 15) != 0 || quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  const int tenths = end_ > 0.0 ? static_cast<int>(std::min(10.0, 10.0 * sim.time() / end_)) : 0;
  if (tty_ ? since < 0.5 : (since < 60.0 && tenths <= tenths_printed_)) return;
  tenths_printed_ = std::max(tenths_printed_, tenths);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = (sim.steps() - steps_at_last_) / since;
  const double eta = elapsed * (end_ - sim.time()) / std::max(sim.time() - time_at_start_, 1e-300);
  char buf[200];
  std::snprintf(buf, sizeof buf, "t = %.4g / %.4g s (%3.0f%%)  %lld steps  %.0f steps/s  ETA %s",
                sim.time(), end_, 100.0 * sim.time() / end_, static_cast<long long>(sim.steps()),
                rate, format_duration(eta).c_str());
  if (tty_)
    std::printf("\r%s   ", buf), std::fflush(stdout);
  else
    std::printf("%s\n", buf), std::fflush(stdout);
  last_ = now;
  steps_at_last_ = sim.steps();
}

void ProgressLine::clear() {
  if (tty_) std::printf("\r%*s\r", 100, ""), std::fflush(stdout);
}

void ProgressLine::break_line() {
  if (tty_) std::printf("\n");
}

}  // namespace femdem
