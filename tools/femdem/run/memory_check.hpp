// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A model too large for this machine is refused before it is built (it would grow until
// std::bad_alloc or the kernel's OOM killer ends it, with nothing said beforehand): the
// estimate of engine/memory_estimate.hpp against the memory available now (MemAvailable).
#include <string>

#include "engine/model_spec.hpp"

namespace femdem {

// Bytes available to a new process now (/proc/meminfo MemAvailable), or a negative number when
// that cannot be read.
double available_memory_bytes();

// Throws InputError (exit 2) with the estimate, the available memory and the fix when the
// model will not fit in `available` bytes (negative: unknown, no check).
void check_memory(const ModelSpec& spec, double available);
inline void check_memory(const ModelSpec& spec) {
  check_memory(spec, available_memory_bytes());
}

// "about 420 MB for 148,877 nodes and 105,456 TET10 elements (23.1 GB available)": for check.
std::string memory_line(const ModelSpec& spec);

}  // namespace femdem
