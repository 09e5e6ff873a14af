// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A run's output folder: never an empty name, owned by one femdem process at a time, and not
// overwritten unless asked. The owner holds an flock on DIR/.femdem.lock (which names its pid
// and command), released when the process ends however it ends; a second run or resume into
// the folder meanwhile is refused. A new run into a folder that holds an earlier run's outputs
// needs --force (femdem resume continues that run instead).
#include <filesystem>
#include <string>

namespace femdem {

// Throws InputError (exit 2) for an empty folder name, and, unless `force`, for a folder that
// holds an earlier run's outputs (saying what is there and the ways on). Changes nothing.
void check_new_run_folder(const std::string& dir, bool force);

class OutputFolderLock {
 public:
  // Creates `dir` if needed and takes its lock. Throws InputError naming the owner when another
  // femdem holds it, std::runtime_error when the lock file cannot be made.
  OutputFolderLock(const std::filesystem::path& dir, const std::string& command_line);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace femdem
