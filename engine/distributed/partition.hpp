// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How a model is cut among the ranks of a distributed run (docs/ARCHITECTURE.md, "Distributed
// runs"): every element goes to one rank. A body small enough to fit in part of one rank's share
// stays whole (grains, armour units: their rigid motions, impact damping and rolling resistance
// then stay on one rank); a larger body is cut into pieces of about one share each by METIS
// along its element faces. The pieces (whole bodies and cut parts) are then dealt to the ranks
// by recursive coordinate bisection of their centroids, weighted by their element counts, so
// that bodies near each other, which are the ones that touch, share a rank. The same model and
// rank count give the same partition on every rank and every run (no random seed varies).
// A node belongs to the rank of its lowest-numbered element.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/model.hpp"

namespace femdem {

struct Partition {
  int parts = 1;
  std::vector<std::int32_t> element_rank;   // per element
  std::vector<std::int32_t> node_rank;      // per node
  std::vector<std::int64_t> part_elements;  // elements per rank
};

// A body is cut when it has more than kWholeBodyShare of one rank's share of the elements.
inline constexpr double kWholeBodyShare = 0.5;

// Throws InputError (naming the rank count) when there are fewer pieces than ranks: a scene
// too small to split this many ways. The bisection weighs each piece by its elements, plus
// body_extra[b] for a body b (its contact work, in elements; a cut body's shared by its pieces
// as their elements), when given; the centroids are those of the current positions m.x.
Partition partition_model(const Model& m, int parts, std::span<const double> body_extra = {});

// The partition that deals the elements as element_rank does (nodes to the rank of their
// lowest-numbered element).
Partition partition_from(const Model& m, int parts, std::vector<std::int32_t> element_rank);

}  // namespace femdem
