// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The two failures a user must be able to tell apart (exit codes 2 and 3 of the command line).
#include <stdexcept>
#include <string>

namespace femdem {

// Bad input: scene, mesh or option. Carries where the problem is, when known.
struct InputError : std::runtime_error {
  std::string file;  // empty if none
  int line = 0;      // 1-based; 0 if unknown
  int column = 0;    // 1-based; 0 if unknown
  std::string key;   // dotted scene key, e.g. "bodies.ball.mesh.radius"; empty if none
  InputError(std::string message, std::string file_ = {}, int line_ = 0, int column_ = 0,
             std::string key_ = {})
      : std::runtime_error(std::move(message)),
        file(std::move(file_)),
        line(line_),
        column(column_),
        key(std::move(key_)) {}
  // "scene.toml:12:5: bodies.ball.mesh.radius: must be positive"
  std::string describe() const {
    std::string s;
    if (!file.empty()) {
      s += file;
      // appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on ":" + string
      if (line > 0) {
        s += ':';
        s += std::to_string(line);
      }
      if (line > 0 && column > 0) {
        s += ':';
        s += std::to_string(column);
      }
      s += ": ";
    }
    if (!key.empty()) s += key + ": ";
    return s + what();
  }
};

// The simulation became unstable (non-finite values, an inverted element). The message says
// where, when, and what to change.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace femdem
