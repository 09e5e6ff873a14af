// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How many threads a run uses, set for OpenMP: the --threads option when given (>= 0), else the
// scene's simulation.threads; 0 means every core, shared among the ranks of a distributed run
// on this machine. 1 without OpenMP.
namespace femdem {

// option: the command line's --threads, -1 when not given; ranks_here: the run's ranks on this
// machine. Returns the count in use.
int use_threads(int option, int scene, int ranks_here = 1);

}  // namespace femdem
