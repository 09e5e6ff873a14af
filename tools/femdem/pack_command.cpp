// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/pack_command.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/errors.hpp"
#include "tools/femdem/exit_codes.hpp"

namespace femdem {

// `femdem pack OUT ...`: generates a packing, writes it and prints what it got.
int pack_command(const PackingParams& params, const std::string& out, bool quiet) {
  if (auto e = check_packing_params(params)) {
    std::string option = e->key;
    std::replace(option.begin(), option.end(), '_', '-');
    throw InputError(e->message, {}, 0, 0, "--" + option);
  }
  const auto start = std::chrono::steady_clock::now();
  Packing packing;
  try {
    packing = generate_packing(params);
  } catch (InputError& e) {
    std::replace(e.key.begin(), e.key.end(), '_', '-');
    if (!e.key.empty()) e.key = "--" + e.key;
    throw;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_packing(out, packing);
  if (quiet) return kExitOk;
  const PackingStats& s = packing.stats;
  fmt::print("{}: {} particles, {}\n", out, packing.particles.size(), params.arrangement);
  fmt::print("  packing fraction  {:.4f} (bed of height {:g} m); {:.4f} of the container\n",
             s.packing_fraction, s.bed_height, s.container_fraction);
  if (std::isfinite(s.core_packing_fraction))
    fmt::print("  core fraction     {:.4f} (two largest diameters from walls, floor and top)\n",
               s.core_packing_fraction);
  if (std::isfinite(s.min_gap))
    fmt::print("  smallest gap      {:.3g} of the radii sum\n", s.min_gap);
  if (s.settle_steps > 0)
    fmt::print(
        "  settling          {} steps, {:.4g} sqrt(d/g), {}, last max speed {:.3g} sqrt(g d)\n",
        s.settle_steps, s.settle_time, s.at_rest ? "at rest" : "NOT at rest", s.max_speed);
  fmt::print("  time              {:.3f} s\n", seconds);
  return kExitOk;
}

}  // namespace femdem
