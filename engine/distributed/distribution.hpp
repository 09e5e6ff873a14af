// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a Simulation on one rank of a distributed run knows of the others (docs/ARCHITECTURE.md,
// "Distributed runs"): its part of the model (what it owns, holds and exchanges) and the ranks
// to add its sums with and take its ghosts from.
#include "engine/distributed/communicator.hpp"
#include "engine/distributed/local_part.hpp"

namespace femdem {

struct Distribution {
  LocalPart part;
  const Communicator* comm = nullptr;
};

}  // namespace femdem
