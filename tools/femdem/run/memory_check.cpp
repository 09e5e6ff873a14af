// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/memory_check.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "engine/errors.hpp"
#include "engine/memory_estimate.hpp"

namespace femdem {
namespace {

std::string megabytes(double bytes) {
  char buf[64];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof buf, "%.1f GB", bytes / 1e9);
  else
    std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  return buf;
}

}  // namespace

double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return -1.0;
}

void check_memory(const ModelSpec& spec, double available) {
  const MemoryEstimate e = estimate_memory(spec);
  if (!(available > 0.0) || e.bytes <= available) return;
  std::ostringstream msg;
  msg << "the model of " << e.nodes << " nodes and " << e.elements << " TET10 elements needs about "
      << megabytes(e.bytes) << " (measured " << kMemoryPerElement / 1e3 << " kB per element and "
      << kMemoryPerNode / 1e3 << " kB per node), more than the " << megabytes(available)
      << " available on this machine now: coarsen the meshes (element_size), or run it on a "
         "machine with more memory";
  throw InputError(msg.str());
}

std::string memory_line(const ModelSpec& spec) {
  const MemoryEstimate e = estimate_memory(spec);
  const double available = available_memory_bytes();
  return "about " + megabytes(e.bytes) + " for " + std::to_string(e.nodes) + " nodes and " +
         std::to_string(e.elements) + " TET10 elements" +
         (available > 0.0 ? " (" + megabytes(available) + " available now)" : std::string());
}

}  // namespace femdem
