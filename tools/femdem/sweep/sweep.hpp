// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem sweep`: runs a scene over the cartesian product of --vary value lists, each point as
// a separate `femdem run` process in its own sub-folder, and collects every run's summary.json
// into DIR/sweep.csv (see docs/OUTPUTS.md, "Parameter sweeps").
#include <string>
#include <vector>

#include "tools/femdem/sweep/value_list.hpp"

namespace femdem {

struct SweepOptions {
  std::string scene_path;
  std::vector<std::string> vary;       // "KEY=V1,V2,..." (the command line's --vary)
  std::vector<std::string> overrides;  // "KEY=VALUE" applied to every run (--set)
  std::string out_dir;                 // empty: out/<scene stem>_sweep/
  int jobs = 0;                        // runs at a time; 0: cores / threads_per_job
  int threads_per_job = 1;             // --threads of each run
  bool quiet = false;
  bool plot = true;        // false: no plots (--no-plot)
  std::string femdem_exe;  // the program each run executes (`femdem run ...`)
  // Words put before each run's command (--launcher 'mpirun -np 2': each run on 2 MPI ranks),
  // looked up on PATH; empty: the run is started directly.
  std::vector<std::string> launcher;
  std::string plot_script;  // tools/plot_sweep.py; empty or missing: no plots (with a note)
};

// Validates everything (exit code 2 via InputError before any run starts), runs the sweep and
// returns the exit code: 0 every run completed, 3 some diverged (and none failed otherwise),
// 1 a run failed otherwise or the sweep was interrupted.
int run_sweep(const SweepOptions& options);

}  // namespace femdem
