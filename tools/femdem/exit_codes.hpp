// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The program's exit codes (README, docs/SCENES.md): what a script or batch queue sees.
namespace femdem {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // anything else, including an interrupted run
constexpr int kExitBadInput = 2;  // scene, mesh, option: the message names file, line and key
constexpr int kExitUnstable = 3;  // the simulation diverged: the message says where and why

}  // namespace femdem
