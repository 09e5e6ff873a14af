// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What one rank of a distributed run holds of the model, and what it exchanges each step
// (docs/ARCHITECTURE.md, "Distributed runs").
//
// A rank holds the elements it owns and every element around the nodes it owns, `layers` deep
// (ghost_layers), and every node of those elements. The internal force on each node it owns is then
// complete and summed in the same order as in one process (elements in global order: the held
// elements keep it), so it has the same bits. The elements it holds but does not own are
// updated here too, from the same positions, with the same bits as on their owner. Each step it
// receives the positions and velocities of the nodes it holds but does not own (its ghosts)
// from their owners, and sends its own to the ranks that hold them.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/distributed/partition.hpp"
#include "engine/model.hpp"

namespace femdem {

struct LocalPart {
  int rank = 0;
  std::vector<std::int32_t> elements;       // global ids, ascending
  std::vector<std::uint8_t> element_owned;  // per held element
  std::vector<std::int32_t> nodes;          // global ids, ascending
  std::vector<std::uint8_t> node_owned;     // per held node
  // One per rank this one exchanges with, in rank order. Local node ids, in global order (the
  // sender's `send` and the receiver's `receive` list the same nodes in the same order).
  struct Neighbour {
    int rank = 0;
    std::vector<std::int32_t> receive;  // held here, owned by `rank`
    std::vector<std::int32_t> send;     // owned here, held by `rank`
  };
  std::vector<Neighbour> neighbours;
  // the first global element of each body (to name an element in messages on every rank)
  std::vector<std::int32_t> body_first_element;
  std::int32_t global_node_count = 0;
  std::int32_t global_element_count = 0;
  // the global index (into Model::surface) of each local surface node entry, ascending
  std::vector<std::int32_t> surface;
  // per body: the rank that holds all of it, or -1 for a body cut among ranks
  std::vector<std::int32_t> body_rank;
  // For contact between bodies across ranks (engine/body_contact.hpp): the whole model's
  // contact sub-tetrahedra as Model has them (corners as global node ids, bodies, depths),
  // each one's index among the local model's (-1 where this rank does not hold all four
  // corners), and the rank that owns each node of the whole model.
  std::vector<std::array<std::int32_t, 4>> contact_tets;
  std::vector<std::int32_t> contact_tet_body;
  std::vector<double> contact_tet_depth;
  std::vector<std::int32_t> contact_tet_local;
  std::vector<std::int32_t> node_rank;
};

// How deep the held elements must reach around the owned nodes: 1, or 3 if any element uses
// nodal F-bar. There the force on a node comes from its elements (layer 1) through the pressure
// Q gathered at their corners from the elements around those (layer 2), whose pressures need
// the volume ratio J of their corners over the elements around them (layer 3). (Exchanging J
// and Q of the ghost corners, two more messages per step, would need one layer: not done yet.)
int ghost_layers(const Model& m);

// The part of `rank` (every rank can compute every part: the exchange lists need the others').
LocalPart local_part(const Model& m, const Partition& p, int rank, int layers);

// The model a rank steps: the held nodes and elements renumbered in global order, every body
// and wall (bodies keep their global indices and masses; a body with nothing here has empty
// ranges), the surface nodes and the contact sub-tetrahedra whose nodes are all held.
Model local_model(const Model& m, const LocalPart& part);

}  // namespace femdem
