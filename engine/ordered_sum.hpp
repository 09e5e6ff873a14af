// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Sums over elements or nodes that reach an output (energies, work), in parallel and yet the same
// bits with any number of threads: the range is cut into chunks of a fixed size (not one per
// thread), each chunk summed in index order by whichever thread takes it, and the chunks' sums
// added in chunk order. The chunk size does not depend on the thread count, so neither do the
// bits.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/parallel_threshold.hpp"

namespace femdem {

inline constexpr std::int64_t kSumChunk = 2048;

// sum over i in [0, n) of term(i); `partial` is scratch (resized, reused between calls).
template <class Term>
double ordered_sum(std::int64_t n, Term term, std::vector<double>& partial) {
  const std::int64_t chunks = (n + kSumChunk - 1) / kSumChunk;
  partial.resize(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static) if (n > kParallelMinElements)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t end = std::min(n, (c + 1) * kSumChunk);
    double s = 0.0;
    for (std::int64_t i = c * kSumChunk; i < end; ++i) s += term(i);
    partial[static_cast<std::size_t>(c)] = s;
  }
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace femdem
