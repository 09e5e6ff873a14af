// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem run`: builds the model of a loaded scene, integrates it to end_time (or until at rest,
// diverged or stopped by a signal) and writes the outputs into out_dir: results.h5/.xdmf,
// history.csv, summary.json, run.log (docs/OUTPUTS.md).
#include <string>

#include "io/scene/scene_reader.hpp"

namespace femdem {

struct RunOptions {
  std::string out_dir;
  int threads = -1;  // -1: the scene's value
  bool quiet = false;
  std::string command_line;
  // Called as `python3 SCRIPT OUT_DIR` after a completed run whose scene has [compaction]
  // (tools/plot_compaction.py); empty: no plots. A failing script is reported, not fatal.
  std::string plot_script;
};

// Returns the process exit code. Throws InputError (bad input) and InstabilityError.
int run_scene(const SceneFile& scene, const RunOptions& options);

}  // namespace femdem
