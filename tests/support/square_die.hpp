// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The side walls of a square die 8 mm wide around the z axis, with friction 0.2 (TOML for a
// scene's [[walls]]): the die of the program tests that press a punch (restart, distributed
// runs).
namespace femdem::test {

inline constexpr const char* kSquareDieSideWalls = R"(
[[walls]]
name = "left"
point = [-4e-3, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
friction = 0.2
[[walls]]
name = "right"
point = [4e-3, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
friction = 0.2
[[walls]]
name = "front"
point = [0.0, -4e-3, 0.0]
normal = [0.0, 1.0, 0.0]
friction = 0.2
[[walls]]
name = "back"
point = [0.0, 4e-3, 0.0]
normal = [0.0, -1.0, 0.0]
friction = 0.2
)";

}  // namespace femdem::test
