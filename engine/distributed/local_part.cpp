// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/local_part.hpp"

#include <algorithm>

#include "engine/gather_map.hpp"

namespace femdem {
namespace {

// Ascending global ids of the elements and nodes `rank` holds.
void held(const Model& m, const Partition& p, int rank, int layers,
          std::vector<std::int32_t>& elements, std::vector<std::int32_t>& nodes) {
  std::vector<std::uint8_t> node_in(m.node_count, 0), elem_in(m.element_count, 0);
  for (std::int32_t n = 0; n < m.node_count; ++n) node_in[n] = p.node_rank[n] == rank;
  for (std::int32_t e = 0; e < m.element_count; ++e) elem_in[e] = p.element_rank[e] == rank;
  for (int layer = 0; layer < layers; ++layer) {
    // the elements around the nodes reached so far, then all their nodes
    for (std::int32_t n = 0; n < m.node_count; ++n) {
      if (!node_in[n]) continue;
      for (std::int32_t k = m.node_elem_offset[n]; k < m.node_elem_offset[n + 1]; ++k)
        elem_in[m.node_elem_slot[k] / 10] = 1;
    }
    for (std::int32_t e = 0; e < m.element_count; ++e)
      if (elem_in[e])
        for (std::int32_t n : m.conn[e]) node_in[n] = 1;
  }
  elements.clear();
  nodes.clear();
  for (std::int32_t e = 0; e < m.element_count; ++e)
    if (elem_in[e]) elements.push_back(e);
  for (std::int32_t n = 0; n < m.node_count; ++n)
    if (node_in[n]) nodes.push_back(n);
}

template <class T>
void copy_rows(const std::vector<T>& from, std::vector<T>& to, const std::vector<std::int32_t>& ids,
               std::size_t width) {
  to.resize(ids.size() * width);
  for (std::size_t k = 0; k < ids.size(); ++k)
    std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(ids[k] * width), width,
                to.begin() + static_cast<std::ptrdiff_t>(k * width));
}

}  // namespace

int ghost_layers(const Model& m) {
  return std::find(m.element_fbar.begin(), m.element_fbar.end(), FbarMode::Nodal) !=
                 m.element_fbar.end()
             ? 3
             : 1;
}

LocalPart local_part(const Model& m, const Partition& p, int rank, int layers) {
  LocalPart part;
  part.rank = rank;
  held(m, p, rank, layers, part.elements, part.nodes);
  part.element_owned.resize(part.elements.size());
  for (std::size_t k = 0; k < part.elements.size(); ++k)
    part.element_owned[k] = p.element_rank[part.elements[k]] == rank;
  part.node_owned.resize(part.nodes.size());
  std::vector<std::int32_t> local(m.node_count, -1);
  for (std::size_t k = 0; k < part.nodes.size(); ++k) {
    part.node_owned[k] = p.node_rank[part.nodes[k]] == rank;
    local[part.nodes[k]] = static_cast<std::int32_t>(k);
  }
  std::vector<std::int32_t> their_elements, their_nodes;
  for (int other = 0; other < p.parts; ++other) {
    if (other == rank) continue;
    LocalPart::Neighbour nb;
    nb.rank = other;
    for (std::size_t k = 0; k < part.nodes.size(); ++k)
      if (p.node_rank[part.nodes[k]] == other) nb.receive.push_back(static_cast<std::int32_t>(k));
    held(m, p, other, layers, their_elements, their_nodes);
    for (std::int32_t n : their_nodes)
      if (p.node_rank[n] == rank) nb.send.push_back(local[n]);
    if (!nb.receive.empty() || !nb.send.empty()) part.neighbours.push_back(std::move(nb));
  }
  for (const Body& b : m.bodies) part.body_first_element.push_back(b.first_element);
  for (std::size_t si = 0; si < m.surface.size(); ++si)
    if (local[m.surface[si].node] >= 0) part.surface.push_back(static_cast<std::int32_t>(si));
  part.global_node_count = m.node_count;
  part.global_element_count = m.element_count;
  for (const Body& b : m.bodies) {
    std::int32_t r = b.element_count > 0 ? p.element_rank[b.first_element] : -1;
    for (std::int32_t e = b.first_element; e < b.first_element + b.element_count; ++e)
      if (p.element_rank[e] != r) r = -1;
    part.body_rank.push_back(r);
  }
  part.contact_tets = m.contact_tets;
  part.contact_tet_body = m.contact_tet_body;
  part.contact_tet_depth = m.contact_tet_depth;
  part.contact_tet_local.assign(m.contact_tets.size(), -1);
  std::int32_t held_tets = 0;  // (local_model keeps the same ones, in the same order)
  for (std::size_t t = 0; t < m.contact_tets.size(); ++t) {
    bool all = true;
    for (std::int32_t n : m.contact_tets[t]) all = all && local[n] >= 0;
    if (all) part.contact_tet_local[t] = held_tets++;
  }
  part.node_rank = p.node_rank;
  return part;
}

Model local_model(const Model& m, const LocalPart& part) {
  Model l;
  l.title = m.title;
  l.settings = m.settings;
  l.contact = m.contact;
  l.materials = m.materials;
  l.walls = m.walls;
  l.contact_tet_min_edge = m.contact_tet_min_edge;
  const auto nn = static_cast<std::int32_t>(part.nodes.size());
  const auto ne = static_cast<std::int32_t>(part.elements.size());
  l.node_count = nn;
  l.element_count = ne;
  std::vector<std::int32_t> local(m.node_count, -1);
  for (std::int32_t k = 0; k < nn; ++k) local[part.nodes[k]] = k;

  copy_rows(m.X, l.X, part.nodes, 3);
  copy_rows(m.x, l.x, part.nodes, 3);
  copy_rows(m.v, l.v, part.nodes, 3);
  copy_rows(m.f_int, l.f_int, part.nodes, 3);
  copy_rows(m.f_contact, l.f_contact, part.nodes, 3);
  copy_rows(m.mass, l.mass, part.nodes, 1);  // complete: summed over all elements at the build
  copy_rows(m.node_body, l.node_body, part.nodes, 1);
  copy_rows(m.dof_mode, l.dof_mode, part.nodes, 3);
  copy_rows(m.dof_velocity, l.dof_velocity, part.nodes, 3);

  l.conn.resize(ne);
  for (std::int32_t k = 0; k < ne; ++k)
    for (int a = 0; a < 10; ++a) l.conn[k][a] = local[m.conn[part.elements[k]][a]];
  copy_rows(m.element_body, l.element_body, part.elements, 1);
  copy_rows(m.element_material, l.element_material, part.elements, 1);
  copy_rows(m.dNdX, l.dNdX, part.elements, 120);
  copy_rows(m.gauss_weight, l.gauss_weight, part.elements, 4);
  copy_rows(m.straight_sided, l.straight_sided, part.elements, 1);
  copy_rows(m.inverse_jacobian, l.inverse_jacobian, part.elements, 9);
  copy_rows(m.frequency_factor, l.frequency_factor, part.elements, 1);
  copy_rows(m.element_fbar, l.element_fbar, part.elements, 1);
  copy_rows(m.subtet_volume0, l.subtet_volume0, part.elements, 1);
  copy_rows(m.states, l.states, part.elements, 1);
  copy_rows(m.stress, l.stress, part.elements, 24);
  copy_rows(m.strain_energy_density, l.strain_energy_density, part.elements, 4);
  build_gather_map(l);

  // bodies keep their indices; their node and element ranges are where their held nodes and
  // elements fall in the local numbering (contiguous: global bodies are contiguous ranges)
  l.bodies = m.bodies;
  for (std::size_t b = 0; b < l.bodies.size(); ++b) {
    Body& body = l.bodies[b];
    const Body& g = m.bodies[b];
    auto range = [](const std::vector<std::int32_t>& ids, std::int32_t first, std::int32_t count,
                    std::int32_t& local_first, std::int32_t& local_count) {
      const auto lo = std::lower_bound(ids.begin(), ids.end(), first);
      const auto hi = std::lower_bound(ids.begin(), ids.end(), first + count);
      local_first = static_cast<std::int32_t>(lo - ids.begin());
      local_count = static_cast<std::int32_t>(hi - lo);
    };
    range(part.nodes, g.first_node, g.node_count, body.first_node, body.node_count);
    range(part.elements, g.first_element, g.element_count, body.first_element, body.element_count);
    body.surface_nodes.clear();
    for (std::int32_t n : g.surface_nodes)
      if (local[n] >= 0) body.surface_nodes.push_back(local[n]);
  }
  for (const std::int32_t si : part.surface) {
    const SurfaceNode& s = m.surface[si];
    l.surface.push_back({local[s.node], s.body, s.area, s.depth});
  }
  for (std::size_t t = 0; t < m.contact_tets.size(); ++t) {
    std::array<std::int32_t, 4> lt;
    bool all = true;
    for (int a = 0; a < 4; ++a) all = all && (lt[a] = local[m.contact_tets[t][a]]) >= 0;
    if (!all) continue;
    l.contact_tets.push_back(lt);
    l.contact_tet_body.push_back(m.contact_tet_body[t]);
    l.contact_tet_depth.push_back(m.contact_tet_depth[t]);
  }
  return l;
}

}  // namespace femdem
