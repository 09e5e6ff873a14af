// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// run.log of a run: every line the run prints also goes there (with --quiet, only there), plus
// the header with the version, command line and resolved scene. Lines reach the file at once,
// so a killed run's log ends with its last line.
#include <filesystem>
#include <fstream>
#include <string>

namespace femdem {

class RunLog {
 public:
  // Creates (truncates) `path`, or with `append` (femdem resume) adds to its end. Throws
  // std::runtime_error if it cannot.
  RunLog(const std::filesystem::path& path, bool quiet, bool append = false);
  void say(const std::string& line);        // standard output (unless quiet) and the log
  void file_only(const std::string& text);  // the log only, as is
  void error(const std::string& line);      // the log only: the caller prints errors itself

 private:
  std::ofstream file_;
  bool quiet_;
};

// "42 s", "3 min 05 s", "2 h 07 min": a wall time as the progress line and log show it.
std::string format_duration(double seconds);

}  // namespace femdem
