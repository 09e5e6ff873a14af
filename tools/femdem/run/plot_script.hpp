// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The plot scripts the program calls after a run (tools/plot_compaction.py for a scene with
// [compaction]): where to find them and how to call one. Plots are a convenience: a missing
// python or matplotlib is a note in the log, never a failed run.
#include <filesystem>
#include <string>

namespace femdem {

// tools/NAME next to the program's source tree (baked in at build time), else in ../tools/ of
// the program's folder; empty if neither exists.
std::string find_plot_script(const std::string& exe, const char* name);

// `python3 SCRIPT OUT_DIR` with the system python (which has Debian's matplotlib), else the
// python3 on the PATH, its output appended to `log_file`. Returns its exit code (127: no
// python).
int run_plot_script(const std::string& script, const std::filesystem::path& out_dir,
                    const std::filesystem::path& log_file);

}  // namespace femdem
