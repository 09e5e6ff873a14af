// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Moving a distributed run's state between its ranks and one whole-model Simulation on rank 0
// (docs/ARCHITECTURE.md, "Distributed runs"): rank 0 writes the outputs and checkpoints of the
// whole model from that Simulation, in the layout of a one-process run, and a checkpoint (from
// any number of ranks) is handed to the ranks from it. The state is what
// Simulation::exchange_state archives: arrays with a row per node (positions, velocities, ...),
// a row per element (Gauss-point states, stresses, ...), or the same on every rank (time, step,
// energy accounts, walls), or lists keyed by a global key (the walls' near lists, the contact
// pairs between bodies). A row comes from the rank that owns its node or element.
#include <string>
#include <vector>

#include "engine/distributed/distribution.hpp"
#include "engine/distributed/partition.hpp"
#include "engine/simulation.hpp"

namespace femdem {

// The figures a frame writes per element (Simulation::element_stress): stress (6 a row, xx yy
// zz xy yz xz), von Mises, pressure, equivalent plastic strain.
struct ElementStressFigures {
  std::vector<double> stress6, von_mises, pressure, plastic_strain;
};

// What rank 0's Simulation is brought up to date with.
enum class GatheredState {
  // What the outputs read: positions, velocities, masses, contact forces, Gauss-point states
  // and stresses (the summary), and everything the ranks have alike.
  outputs,
  // What a frame writes: positions, velocities, masses and contact forces, each element's
  // stress figures computed by its owner (Simulation::element_stress, into `element_stress`),
  // and everything the ranks have alike; not the Gauss points' states and stresses, which
  // are 30 numbers an element more (docs/PERFORMANCE.md, "Frames of a distributed run").
  frame,
  // All of it (a checkpoint).
  everything,
};

// Every rank calls it; `whole` (the whole model, on rank 0; null elsewhere) then holds the
// state of `local` (each rank's part, of `dist`, cut by `p`). Throws std::logic_error for a
// state array whose layout this file does not know (a new array must be listed here).
// GatheredState::frame also fills `element_stress` on rank 0 (not read elsewhere) with the whole
// model's figures, each element's computed by its owner.
void gather_state(Simulation& local, const Distribution& dist, const Partition& p,
                  Simulation* whole, GatheredState what = GatheredState::everything,
                  ElementStressFigures* element_stress = nullptr);

// Every rank calls it; `local` then holds its part of `whole` (rank 0's; null elsewhere), e.g.
// after rank 0 read a checkpoint. Throws CheckpointError for a state array missing from it.
void scatter_state(Simulation* whole, Simulation& local, const Distribution& dist);

}  // namespace femdem
