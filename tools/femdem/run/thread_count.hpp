// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How many threads a run uses, set for OpenMP: the --threads option when given (>= 0), else the
// scene's simulation.threads; 0 means every core. 1 without OpenMP.
namespace femdem {

// option: the command line's --threads, -1 when not given. Returns the count in use.
int use_threads(int option, int scene);

}  // namespace femdem
