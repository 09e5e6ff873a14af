// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/thread_count.hpp"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace femdem {

int use_threads(int option, int scene, int ranks_here) {
  int threads = option >= 0 ? option : scene;
#ifdef _OPENMP
  // (ranks sharing the machine share its cores: more threads than cores would spin against
  // each other in OpenMP's and MPI's waits)
  if (threads <= 0) threads = std::max(1, omp_get_num_procs() / std::max(1, ranks_here));
  omp_set_num_threads(threads);
#else
  threads = 1;
#endif
  return threads;
}

}  // namespace femdem
