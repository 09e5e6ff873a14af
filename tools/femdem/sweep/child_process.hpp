// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The processes of a sweep: each run is a child `femdem run ...` started by fork and exec.
#include <sys/types.h>

#include <string>
#include <vector>

namespace femdem::sweep {

// Cores this process may run on (its affinity mask), at least 1.
int available_cores();
// fork + exec; stdout and stderr to `output` ("" keeps them), stdin from /dev/null. With
// search_path the program is looked up on the PATH. Returns the child's pid (-1: not started).
pid_t spawn(const std::vector<std::string>& args, const std::string& output, bool search_path);
// The exit code of a waitpid status (128 + signal for a killed child).
int exit_code_of(int status);

}  // namespace femdem::sweep
