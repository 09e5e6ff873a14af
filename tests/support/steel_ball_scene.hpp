// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A small scene the command-line tests share: a coarse steel ball of radius 4 mm (about 100
// TET10) falling at 2 m/s onto a floor wall 50 um below it, after a [simulation] section of the
// caller's; `extra` is appended (e.g. a [contact] section). Runs in well under a second.
#include <string>

namespace femdem::test {

inline std::string steel_ball_scene(const std::string& title, const std::string& simulation,
                                    const std::string& extra = "") {
  return "title = \"" + title + "\"\n[simulation]\n" + simulation +
         R"(
[[materials]]
name = "steel"
model = "elastic"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3

[[bodies]]
name = "ball"
material = "steel"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2e-3 }
position = [0.0, 0.0, 4.05e-3]
velocity = [0.0, 0.0, -2.0]

[[walls]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
)" + extra;
}

}  // namespace femdem::test
