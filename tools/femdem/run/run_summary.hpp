// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// summary.json of a run, made from the simulation's state and the run monitors at the end (or
// when a run diverges or is interrupted).
#include <string>
#include <vector>

#include "io/results/summary_writer.hpp"
#include "tools/femdem/run/output_tables.hpp"
#include "tools/femdem/run/restitution_monitor.hpp"

namespace femdem {

struct RunIdentity {
  std::string scene;  // as given on the command line
  int threads = 1;
  double wall_time_s = 0.0;  // since the run started, setup included
};

RunSummary make_run_summary(const RunRecord& run, const RunIdentity& id,
                            const std::vector<RestitutionMonitor>& restitution, RunStatus status);

}  // namespace femdem
