// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/state_transfer.hpp"

#include <algorithm>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "engine/distributed/memory_archive.hpp"

namespace femdem {
namespace {

enum class Spread {
  node,          // a row per node
  element,       // a row per element
  keyed,         // a list of rows with a global key each, cut by owner (kKeyed)
  summed,        // one number per rank, the whole model's being their sum
  same,          // alike on every rank
  derived,       // remade by the loader from other arrays: not gathered
  contact_node,  // a row per node of the contact sub-tetrahedra (ascending global ids)
};

// The lists of rows each rank keeps for its own nodes, by a global key (ascending in one
// process): the first array is the key, the others have as many rows. Gathered, the ranks'
// rows are merged by key; scattered, every rank gets all rows and its loader keeps its own.
// A list with no other arrays has its key in its rows: the first two 4-byte unsigned integers
// of each (the contact pairs' sub-tets i < j), which each rank saves once over the ranks.
struct KeyedList {
  const char* key;
  std::vector<const char*> rows;
};
const KeyedList kKeyed[] = {
    {"simulation/wall_contact/near_key",
     {"simulation/wall_contact/near_k", "simulation/wall_contact/stick"}},
    {"simulation/wall_contact/reach_surface", {"simulation/wall_contact/reach_reference"}},
    {"simulation/body_contact/pairs", {}},
};

// Every array Simulation::exchange_state saves that is not alike on every rank. (What is
// listed nowhere is taken as alike, and checked to have the whole model's length.)
Spread spread_of(const std::string& path) {
  static const char* const node[] = {
      "model/x",
      "model/v",
      "model/f_int",
      "model/f_contact",
      "model/mass",
      "simulation/acceleration",
      "simulation/reaction",
      "simulation/highest_frequency/start",
      "simulation/body_contact/node_contact_stiffness",
  };
  static const char* const element[] = {
      "model/gauss_point_states",    "model/stress",
      "model/strain_energy_density", "simulation/element_mass_scale",
      "frame/element_stress",  // (GatheredState::frame's figures, not a state array)
  };

  for (const KeyedList& k : kKeyed) {
    if (path == k.key) return Spread::keyed;
    for (const char* r : k.rows)
      if (path == r) return Spread::keyed;
  }
  if (path == "simulation/wall_contact/released") return Spread::summed;
  for (const char* n : node)
    if (path == n) return Spread::node;
  for (const char* e : element)
    if (path == e) return Spread::element;
  if (path == "simulation/body_contact/active_tets") return Spread::derived;
  if (path == "simulation/body_contact/verlet_reference") return Spread::contact_node;
  return Spread::same;
}

// The key of row i of a key array (4- or 8-byte unsigned integers, or rows that start with
// two 4-byte ones).
std::uint64_t key_at(const MemoryArchive::Entry& e, std::size_t i) {
  if (e.item_bytes > 8) {
    std::uint32_t k[2];
    std::memcpy(k, e.data.data() + e.item_bytes * i, 8);
    return std::uint64_t{k[0]} << 32 | k[1];
  }
  if (e.item_bytes == 4) {
    std::uint32_t k;
    std::memcpy(&k, e.data.data() + 4 * i, 4);
    return k;
  }
  std::uint64_t k;
  std::memcpy(&k, e.data.data() + 8 * i, 8);
  return k;
}

// Merges the ranks' rows of each keyed list into `w`, in key order (a stable sort of the
// ranks' rows in rank order: each rank's own rows are in key order already).
void merge_keyed(const std::vector<MemoryArchive>& ranks, MemoryArchive& w) {
  for (const KeyedList& list : kKeyed) {
    std::vector<const char*> paths{list.key};
    paths.insert(paths.end(), list.rows.begin(), list.rows.end());
    // every rank's rows of every array of the list, one after the other
    std::vector<MemoryArchive::Entry> joined(paths.size());
    for (std::size_t a = 0; a < paths.size(); ++a) {
      const MemoryArchive::Entry* first = ranks.front().find(paths[a]);
      if (first == nullptr) throw std::logic_error(std::string("state '") + paths[a] + "' missing");
      joined[a] = {first->path, first->type, first->item_bytes, 0, {}};
      for (const MemoryArchive& r : ranks) {
        const MemoryArchive::Entry* e = r.find(paths[a]);
        joined[a].data.insert(joined[a].data.end(), e->data.begin(), e->data.end());
        joined[a].count += e->count;
      }
    }
    const std::size_t rows = joined[0].count;
    std::vector<std::size_t> order(rows);
    for (std::size_t i = 0; i < rows; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return key_at(joined[0], a) < key_at(joined[0], b);
    });
    for (MemoryArchive::Entry& e : joined) {
      if (e.count == 0) {  // (an optional array: stick springs without friction)
        *w.find(e.path) = std::move(e);
        continue;
      }
      const std::size_t row_bytes = e.data.size() / rows;
      std::vector<std::byte> sorted(e.data.size());
      for (std::size_t i = 0; i < rows; ++i)
        std::memcpy(sorted.data() + i * row_bytes, e.data.data() + order[i] * row_bytes, row_bytes);
      e.data = std::move(sorted);
      *w.find(e.path) = std::move(e);
    }
  }
}

// What a frame reads (GatheredState::frame, which takes the elements' stress figures instead of
// their Gauss points), and what the summary reads (GatheredState::outputs).
bool read_by_outputs(const std::string& path, GatheredState what) {
  static const char* const frame[] = {"model/x", "model/v", "model/f_contact", "model/mass"};
  static const char* const summary[] = {
      "model/x",      "model/v", "model/f_contact", "model/mass", "model/gauss_point_states",
      "model/stress",
  };
  auto named = [&](const auto& list) {
    return std::any_of(std::begin(list), std::end(list), [&](const char* r) { return path == r; });
  };
  return what == GatheredState::frame ? named(frame) : named(summary);
}

// The entry that carries GatheredState::frame's element figures (not a state array).
constexpr const char* kElementStressPath = "frame/element_stress";
constexpr std::size_t kElementStressWidth = 9;

// `local`'s element_stress figures of its held elements, 9 a row (kElementStressWidth).
std::vector<double> element_stress_rows(const Simulation& local) {
  std::vector<double> s6, vm, pr, ep;
  local.element_stress(s6, vm, pr, ep);
  std::vector<double> rows(kElementStressWidth * vm.size());
  for (std::size_t e = 0; e < vm.size(); ++e) {
    double* r = rows.data() + kElementStressWidth * e;
    for (int k = 0; k < 6; ++k) r[k] = s6[6 * e + k];
    r[6] = vm[e], r[7] = pr[e], r[8] = ep[e];
  }
  return rows;
}

// The global ids of the nodes (or elements) `rank` owns, ascending: the order its held rows
// keep them in.
std::vector<std::int32_t> owned_ids(const std::vector<std::int32_t>& rank_of, int rank) {
  std::vector<std::int32_t> ids;
  for (std::size_t i = 0; i < rank_of.size(); ++i)
    if (rank_of[i] == rank) ids.push_back(static_cast<std::int32_t>(i));
  return ids;
}

// The nodes of contact sub-tetrahedra, ascending (BodyContact's Verlet list: its rows).
std::vector<std::int32_t> contact_nodes(const std::vector<std::array<std::int32_t, 4>>& tets,
                                        std::int32_t node_count) {
  std::vector<char> used(node_count, 0);
  for (const auto& t : tets)
    for (std::int32_t n : t) used[n] = 1;
  std::vector<std::int32_t> nodes;
  for (std::int32_t n = 0; n < node_count; ++n)
    if (used[n]) nodes.push_back(n);
  return nodes;
}

// Items per row of an array of `count` items over `rows` rows.
std::size_t row_width(const MemoryArchive::Entry& e, std::size_t rows) {
  if (e.count == 0) return 0;
  if (rows == 0 || e.count % rows != 0)
    throw std::logic_error("state '" + e.path + "' has " + std::to_string(e.count) +
                           " items, not a whole number of rows over " + std::to_string(rows));
  return e.count / rows;
}

// Copies rows ids[k] of `from` (rows of `row_bytes`) to rows k of `to`, or the reverse.
void take_rows(const std::vector<std::byte>& from, std::vector<std::byte>& to,
               const std::vector<std::int32_t>& ids, std::size_t row_bytes) {
  to.resize(ids.size() * row_bytes);
  for (std::size_t k = 0; k < ids.size(); ++k)
    std::memcpy(to.data() + k * row_bytes, from.data() + ids[k] * row_bytes, row_bytes);
}
void put_rows(const std::vector<std::byte>& from, std::vector<std::byte>& to,
              const std::vector<std::int32_t>& ids, std::size_t row_bytes) {
  for (std::size_t k = 0; k < ids.size(); ++k)
    std::memcpy(to.data() + ids[k] * row_bytes, from.data() + k * row_bytes, row_bytes);
}

}  // namespace

void gather_state(Simulation& local, const Distribution& dist, const Partition& p,
                  Simulation* whole, GatheredState what, ElementStressFigures* element_stress) {
  const Communicator& comm = *dist.comm;
  const LocalPart& part = dist.part;
  const bool outputs = what == GatheredState::outputs || what == GatheredState::frame;
  // (for the outputs: what they read, and what is alike on every rank, which is small)
  std::function<bool(const std::string&)> keep;
  if (outputs)
    keep = [what](const std::string& path) {
      const Spread s = spread_of(path);
      return read_by_outputs(path, what) || s == Spread::same;
    };
  MemoryArchive mine(keep);
  local.exchange_state(mine);
  if (what == GatheredState::frame) {
    // the held elements' figures, as an element array (its owned rows are sent below)
    const std::vector<double> rows = element_stress_rows(local);
    MemoryArchive::Entry e{kElementStressPath, StateArchive::Type::f64, sizeof(double), rows.size(),
                           std::vector<std::byte>(rows.size() * sizeof(double))};
    if (!rows.empty()) std::memcpy(e.data.data(), rows.data(), e.data.size());
    mine.add(std::move(e));
  }
  // this rank's owned rows of the arrays spread over the ranks
  MemoryArchive owned;
  std::vector<std::int32_t> owned_nodes, owned_elements;
  for (std::size_t k = 0; k < part.nodes.size(); ++k)
    if (part.node_owned[k]) owned_nodes.push_back(static_cast<std::int32_t>(k));
  for (std::size_t k = 0; k < part.elements.size(); ++k)
    if (part.element_owned[k]) owned_elements.push_back(static_cast<std::int32_t>(k));
  // (the contact nodes' rows: a rank's held ones, of which it sends those it owns)
  const Model& lm = local.model();
  std::vector<std::int32_t> owned_contact_nodes;
  {
    const std::vector<std::int32_t> held = contact_nodes(lm.contact_tets, lm.node_count);
    for (std::size_t k = 0; k < held.size(); ++k)
      if (part.node_owned[held[k]]) owned_contact_nodes.push_back(static_cast<std::int32_t>(k));
  }
  for (const MemoryArchive::Entry& e : mine.entries()) {
    const Spread s = spread_of(e.path);
    if (outputs && !read_by_outputs(e.path, what) && e.path != kElementStressPath) continue;
    if (s == Spread::keyed || s == Spread::summed) {
      owned.entries().push_back(e);
      continue;
    }
    if (s == Spread::contact_node) {
      MemoryArchive::Entry rows{e.path, e.type, e.item_bytes, 0, {}};
      if (e.count > 0) {
        const std::size_t held = contact_nodes(lm.contact_tets, lm.node_count).size();
        take_rows(e.data, rows.data, owned_contact_nodes, row_width(e, held) * e.item_bytes);
        rows.count = rows.data.size() / e.item_bytes;
      }
      owned.entries().push_back(std::move(rows));
      continue;
    }
    if (s != Spread::node && s != Spread::element) continue;
    const bool by_node = s == Spread::node;
    const std::size_t width = row_width(e, by_node ? part.nodes.size() : part.elements.size());
    MemoryArchive::Entry rows{e.path, e.type, e.item_bytes, 0, {}};
    if (width > 0) {
      take_rows(e.data, rows.data, by_node ? owned_nodes : owned_elements, width * e.item_bytes);
      rows.count = rows.data.size() / e.item_bytes;
    }
    owned.entries().push_back(std::move(rows));
  }
  const std::vector<std::vector<std::byte>> all = comm.gather(owned.pack());
  if (comm.rank() != 0) return;

  MemoryArchive w(keep);  // the whole model's state as it stands, then updated
  whole->exchange_state(w);
  if (what == GatheredState::frame) {
    const std::size_t n = kElementStressWidth * p.element_rank.size();
    w.add({kElementStressPath, StateArchive::Type::f64, sizeof(double), n,
           std::vector<std::byte>(n * sizeof(double))});
  }
  for (const MemoryArchive::Entry& e : mine.entries()) {
    if (spread_of(e.path) != Spread::same) continue;
    MemoryArchive::Entry* to = w.find(e.path);
    if (to == nullptr || to->count != e.count || to->item_bytes != e.item_bytes)
      throw std::logic_error("state '" + e.path +
                             "' differs in length between a rank's part and the whole model: "
                             "list its layout in engine/distributed/state_transfer.cpp");
    to->data = e.data;
  }
  std::vector<MemoryArchive> from_ranks;
  for (int r = 0; r < comm.size(); ++r) from_ranks.emplace_back(all[r]);
  if (what == GatheredState::everything) merge_keyed(from_ranks, w);
  const std::vector<std::int32_t> whole_contact_nodes =
      contact_nodes(whole->model().contact_tets, whole->model().node_count);
  for (int r = 0; r < comm.size(); ++r) {
    const MemoryArchive& from = from_ranks[r];
    const std::vector<std::int32_t> nodes = owned_ids(p.node_rank, r);
    const std::vector<std::int32_t> elements = owned_ids(p.element_rank, r);
    for (const MemoryArchive::Entry& e : from.entries()) {
      MemoryArchive::Entry* to = w.find(e.path);
      const Spread s = spread_of(e.path);
      if (s == Spread::keyed) continue;
      if (s == Spread::contact_node) {
        // every rank's rows, or none (no list built yet): the whole list's length
        std::vector<std::int32_t> rows;
        for (std::size_t k = 0; k < whole_contact_nodes.size(); ++k)
          if (p.node_rank[whole_contact_nodes[k]] == r)
            rows.push_back(static_cast<std::int32_t>(k));
        if (rows.empty()) continue;
        if (e.count == 0) {
          to->count = 0;
          to->data.clear();
          continue;
        }
        const std::size_t width = e.count / rows.size();
        to->count = width * whole_contact_nodes.size();
        to->data.resize(to->count * e.item_bytes);
        put_rows(e.data, to->data, rows, width * e.item_bytes);
        continue;
      }
      if (s == Spread::summed) {  // (plain, in rank order)
        double total = 0.0, x = 0.0;
        if (r > 0) std::memcpy(&total, to->data.data(), sizeof total);
        std::memcpy(&x, e.data.data(), sizeof x);
        total += x;
        std::memcpy(to->data.data(), &total, sizeof total);
        continue;
      }
      const bool by_node = s == Spread::node;
      const std::vector<std::int32_t>& ids = by_node ? nodes : elements;
      const std::size_t width =
          row_width(*to, by_node ? p.node_rank.size() : p.element_rank.size());
      if (width == 0) continue;
      if (e.count != ids.size() * width)
        throw std::logic_error("rank " + std::to_string(r) + " sent " + std::to_string(e.count) +
                               " items of '" + e.path + "' where it owns " +
                               std::to_string(ids.size()) + " rows");
      put_rows(e.data, to->data, ids, width * e.item_bytes);
    }
  }
  if (what == GatheredState::frame) {  // (left in w: loading reads only the view's arrays)
    const MemoryArchive::Entry& e = *w.find(kElementStressPath);
    const std::size_t ne = e.count / kElementStressWidth;
    const auto* rows = reinterpret_cast<const double*>(e.data.data());
    ElementStressFigures& s = *element_stress;
    s.stress6.resize(6 * ne), s.von_mises.resize(ne), s.pressure.resize(ne);
    s.plastic_strain.resize(ne);
    for (std::size_t k = 0; k < ne; ++k) {
      const double* r = rows + kElementStressWidth * k;
      std::copy(r, r + 6, s.stress6.begin() + static_cast<std::ptrdiff_t>(6 * k));
      s.von_mises[k] = r[6], s.pressure[k] = r[7], s.plastic_strain[k] = r[8];
    }
  }
  w.load();
  whole->exchange_state(w);
}

void scatter_state(Simulation* whole, Simulation& local, const Distribution& dist) {
  const Communicator& comm = *dist.comm;
  const LocalPart& part = dist.part;
  std::vector<std::byte> bytes;
  if (comm.rank() == 0) {
    MemoryArchive w;
    whole->exchange_state(w);
    bytes = w.pack();
  }
  comm.broadcast(bytes);
  const MemoryArchive from(bytes);
  MemoryArchive mine;
  local.exchange_state(mine);
  const auto global_nodes = static_cast<std::size_t>(part.global_node_count);
  for (MemoryArchive::Entry& e : mine.entries()) {
    const MemoryArchive::Entry* src = from.find(e.path);
    if (src == nullptr) throw CheckpointError("state '" + e.path + "' is missing");
    const Spread s = spread_of(e.path);
    if (s == Spread::contact_node) {
      // this rank's held contact nodes' rows, found by global id in the whole model's list
      const std::vector<std::int32_t> whole =
          contact_nodes(part.contact_tets, part.global_node_count);
      const Model& lm = local.model();
      std::vector<std::int32_t> rows;
      for (std::int32_t n : contact_nodes(lm.contact_tets, lm.node_count))
        rows.push_back(static_cast<std::int32_t>(
            std::lower_bound(whole.begin(), whole.end(), part.nodes[n]) - whole.begin()));
      const std::size_t width = row_width(*src, whole.size());
      e.count = width * rows.size();
      if (width > 0)
        take_rows(src->data, e.data, rows, width * e.item_bytes);
      else
        e.data.clear();
      continue;
    }
    if (s == Spread::same || s == Spread::derived || s == Spread::keyed) {
      e.count = src->count;
      e.data = src->data;
      continue;
    }
    if (s == Spread::summed) {  // rank 0 carries the total
      e.data = src->data;
      if (comm.rank() != 0) std::fill(e.data.begin(), e.data.end(), std::byte{0});
      continue;
    }
    const bool by_node = s == Spread::node;
    const std::size_t rows =
        by_node ? global_nodes : static_cast<std::size_t>(part.global_element_count);
    const std::size_t width = row_width(*src, rows);
    e.count = width * (by_node ? part.nodes.size() : part.elements.size());
    if (width > 0)
      take_rows(src->data, e.data, by_node ? part.nodes : part.elements, width * e.item_bytes);
    else
      e.data.clear();
  }
  mine.load();
  local.exchange_state(mine);
}

}  // namespace femdem
