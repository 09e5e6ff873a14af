// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The node -> (element, local node) map of a model (Model::node_elem_offset, node_elem_slot),
// element by element in element order: the order in which each node's internal force is summed,
// whatever the threads (and, in a distributed run, whatever the ranks: engine/distributed).
#include "engine/model.hpp"

namespace femdem {

void build_gather_map(Model& m);

}  // namespace femdem
