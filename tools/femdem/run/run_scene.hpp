// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem run`: builds the model of a loaded scene, integrates it to end_time (or until at rest,
// diverged or stopped by a signal) and writes the outputs into out_dir: results.h5/.xdmf,
// history.csv, summary.json, run.log (docs/OUTPUTS.md).
#include <string>
#include <vector>

#include "io/scene/scene_reader.hpp"

namespace femdem {

struct RunOptions {
  std::string out_dir;
  int threads = -1;  // -1: the scene's value
  bool quiet = false;
  std::string command_line;
  std::vector<std::string> overrides;  // the scene's --set, kept in the checkpoint for resume
  bool force = false;  // --force: replace an earlier run's outputs in out_dir
  // Called as `python3 SCRIPT OUT_DIR` after a completed run whose scene has [compaction]
  // (tools/plot_compaction.py); empty: no plots. A failing script is reported, not fatal.
  std::string plot_script;
};

// Returns the process exit code. Throws InputError (bad input) and InstabilityError.
int run_scene(const SceneFile& scene, const RunOptions& options);

struct ResumeOptions {
  RunOptions run;                      // out_dir: the run's folder
  std::vector<std::string> overrides;  // --set: only the keys of resumable_keys()
};
// `femdem resume OUT_DIR`: continues the run in its folder from checkpoint.h5 (made again from
// the run's scene file and overrides, which must resolve to the same scene but for the
// resumable keys), cutting history.csv and results.h5 back to the checkpoint and appending to
// them. Throws InputError (exit 2) naming the file on a missing, damaged or foreign checkpoint,
// a changed scene or a key that may not change; nothing in the folder is changed then.
int resume_run(const ResumeOptions& options);

}  // namespace femdem
