// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The scene text of an elastic bar on rollers set vibrating along its length: a 10 x 1 x 1 box
// of 0.5 elements (density 1, E 100, nu 0: a wave speed of 10), y and z held everywhere, an
// initial velocity of 1e-4 along x. The distributed-run tests cut it among ranks
// (tests/tools/test_distributed_run.cpp with one end held, test_distributed_failure.cpp free).
#include <string>

namespace femdem::test {

// `title` and `simulation` (the body of the [simulation] table) are the scene's own.
inline std::string vibrating_bar_scene(const std::string& title, const std::string& simulation) {
  return "title = \"" + title + "\"\n[simulation]\n" + simulation + R"(
[[materials]]
name = "bar"
model = "elastic"
density = 1.0
youngs_modulus = 100.0
poisson_ratio = 0.0

[[bodies]]
name = "bar"
material = "bar"
mesh = { generator = "box", size = [10.0, 1.0, 1.0], element_size = 0.5 }
velocity = [1e-4, 0.0, 0.0]

[[constraints]]
body = "bar"
region = "all"
fix = ["y", "z"]
)";
}

}  // namespace femdem::test
