// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/thread_count.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace femdem {

int use_threads(int option, int scene) {
  int threads = option >= 0 ? option : scene;
#ifdef _OPENMP
  if (threads <= 0) threads = omp_get_num_procs();
  omp_set_num_threads(threads);
#else
  threads = 1;
#endif
  return threads;
}

}  // namespace femdem
