// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/run_log.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace femdem {

RunLog::RunLog(const std::filesystem::path& path, bool quiet, bool append)
    : file_(path, append ? std::ios::app : std::ios::trunc), quiet_(quiet) {
  if (!file_)
    throw std::runtime_error(std::string(append ? "cannot open " : "cannot create ") +
                             path.string());
}

void RunLog::say(const std::string& line) {
  if (!quiet_) std::printf("%s\n", line.c_str()), std::fflush(stdout);
  file_ << line << '\n';
  file_.flush();
}

void RunLog::file_only(const std::string& text) {
  file_ << text;
  file_.flush();
}

void RunLog::error(const std::string& line) {
  file_ << line << '\n';
  file_.flush();
}

std::string format_duration(double s) {
  char buf[64];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else
    std::snprintf(buf, sizeof buf, "%.0f h %02.0f min", std::floor(s / 3600),
                  std::fmod(s / 60, 60));
  return buf;
}

}  // namespace femdem
