// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Runs the femdem program in one process or on MPI ranks (`mpirun -np N femdem ...`), for the
// tests of distributed runs: FEMDEM_EXE and FEMDEM_MPIEXEC come from tests/CMakeLists.txt.
#include <string>

#include "support/run_command.hpp"

namespace femdem::test {

// `femdem ARGS` in one process (ranks 1) or under mpirun with one thread per rank.
inline CommandResult femdem_on_ranks(int ranks, const std::string& args) {
  std::string exe = std::string("'") + FEMDEM_EXE + "' ";
  // (--oversubscribe: CI has 2 cores; --allow-run-as-root: CI runs as root; no leak check
  // under the sanitizers: Open MPI's start-up allocations, see tests/CMakeLists.txt)
  if (ranks > 1)
    exe = std::string("'") + FEMDEM_MPIEXEC + "' -np " + std::to_string(ranks) +
          " --oversubscribe --allow-run-as-root -x OMP_NUM_THREADS=1 -x "
          "ASAN_OPTIONS=detect_leaks=0 " +
          exe;
  return run_command(exe + args);
}

}  // namespace femdem::test
