// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Bodies that overlap each other or a wall at t = 0 are a scene error (a position or a mesh
// placed wrong), not a run to start: the penalty would throw them apart and the run would stop
// later with advice about the time step. Read from the contact of the Simulation's first force
// evaluation (the broadphase and the exact pair kernel that the run uses).
#include "engine/simulation.hpp"

namespace femdem {

// Throws InputError naming the two bodies (or the body and the wall), the depth, its share of
// the element size and the fix, when an overlap at the start exceeds contact.initial_overlap of
// the element size.
void check_initial_overlap(const Simulation& sim);

}  // namespace femdem
