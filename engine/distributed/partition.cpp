// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/partition.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "engine/errors.hpp"

namespace femdem {
namespace {

// A whole body or a METIS part of one: the unit the bisection deals out.
struct Piece {
  std::vector<std::int32_t> elements;  // ascending
  Vec3 centroid = Vec3::Zero();        // of its elements' corner nodes, current positions
  double weight = 0.0;                 // its elements, plus its share of its body's extra
};

Vec3 corner_centroid(const Model& m, const std::vector<std::int32_t>& elements) {
  Vec3 c = Vec3::Zero();
  for (std::int32_t e : elements)
    for (int a = 0; a < 4; ++a) {
      const std::int32_t n = m.conn[e][a];
      c += Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
    }
  return c / (4.0 * static_cast<double>(elements.size()));
}

// The body's elements in `cuts` parts of about equal size, along element faces (corner nodes
// shared by three: METIS's dual graph), with METIS's fixed default seed.
std::vector<Piece> cut_body(const Model& m, const Body& b, int cuts) {
  std::vector<idx_t> eptr(b.element_count + 1), eind(4 * static_cast<std::size_t>(b.element_count));
  for (std::int32_t k = 0; k < b.element_count; ++k) {
    eptr[k] = 4 * k;
    for (int a = 0; a < 4; ++a) eind[4 * k + a] = m.conn[b.first_element + k][a] - b.first_node;
  }
  eptr[b.element_count] = 4 * b.element_count;
  idx_t ne = b.element_count, nn = b.node_count, common = 3, nparts = cuts, objval = 0;
  std::vector<idx_t> epart(b.element_count), npart(b.node_count);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  const int status =
      METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &common, &nparts,
                         nullptr, options, &objval, epart.data(), npart.data());
  if (status != METIS_OK)
    throw InputError("body '" + b.name + "' could not be cut into " + std::to_string(cuts) +
                     " parts for the ranks (METIS error " + std::to_string(status) + ")");
  std::vector<Piece> pieces(cuts);
  for (std::int32_t k = 0; k < b.element_count; ++k)
    pieces[epart[k]].elements.push_back(b.first_element + k);
  // (METIS may leave a part empty on a body with few elements: the bisection needs none)
  std::erase_if(pieces, [](const Piece& p) { return p.elements.empty(); });
  return pieces;
}

// Deals `pieces[order[lo..hi)]` to ranks [r0, r0 + n): split along the widest spread of their
// centroids where the element count on each side is closest to the ranks' shares.
void bisect(const Model& m, std::vector<Piece>& pieces, std::vector<std::int32_t>& order,
            std::size_t lo, std::size_t hi, int r0, int n, Partition& out) {
  if (n == 1) {
    for (std::size_t k = lo; k < hi; ++k)
      for (std::int32_t e : pieces[order[k]].elements) out.element_rank[e] = r0;
    return;
  }
  Vec3 cmin = Vec3::Constant(HUGE_VAL), cmax = Vec3::Constant(-HUGE_VAL);
  for (std::size_t k = lo; k < hi; ++k) {
    cmin = cmin.cwiseMin(pieces[order[k]].centroid);
    cmax = cmax.cwiseMax(pieces[order[k]].centroid);
  }
  int axis = 0;
  (cmax - cmin).maxCoeff(&axis);
  // ties broken by piece index: the same order on every rank
  std::sort(order.begin() + static_cast<std::ptrdiff_t>(lo),
            order.begin() + static_cast<std::ptrdiff_t>(hi), [&](std::int32_t a, std::int32_t b) {
              const double ca = pieces[a].centroid[axis], cb = pieces[b].centroid[axis];
              return ca < cb || (ca == cb && a < b);
            });
  const int n_left = n / 2;
  double total = 0.0;
  for (std::size_t k = lo; k < hi; ++k) total += pieces[order[k]].weight;
  const double target = total * n_left / n;
  // each side keeps at least as many pieces as it has ranks
  const std::size_t first = lo + static_cast<std::size_t>(n_left);
  const std::size_t last = hi - static_cast<std::size_t>(n - n_left);
  std::size_t split = first;
  double left = 0.0, best = HUGE_VAL;
  for (std::size_t k = lo; k < hi; ++k) {
    if (k >= first && k <= last && std::fabs(left - target) < best) {
      best = std::fabs(left - target);
      split = k;
    }
    left += pieces[order[k]].weight;
  }
  bisect(m, pieces, order, lo, split, r0, n_left, out);
  bisect(m, pieces, order, split, hi, r0 + n_left, n - n_left, out);
}

}  // namespace

Partition partition_model(const Model& m, int parts, std::span<const double> body_extra) {
  if (parts < 1)
    throw InputError("the number of ranks must be at least 1, got " + std::to_string(parts));
  Partition out;
  out.parts = parts;
  out.element_rank.assign(m.element_count, 0);
  const double share = static_cast<double>(m.element_count) / parts;
  std::vector<Piece> pieces;
  for (std::size_t bi = 0; bi < m.bodies.size(); ++bi) {
    const Body& b = m.bodies[bi];
    const std::size_t first_piece = pieces.size();
    const int cuts =
        parts > 1 && b.element_count > kWholeBodyShare * share
            ? std::min(b.element_count,
                       std::max(2, static_cast<int>(std::lround(b.element_count / share))))
            : 1;
    if (cuts > 1) {
      for (Piece& p : cut_body(m, b, cuts)) pieces.push_back(std::move(p));
    } else {
      Piece p;
      p.elements.resize(b.element_count);
      std::iota(p.elements.begin(), p.elements.end(), b.first_element);
      pieces.push_back(std::move(p));
    }
    const double extra = bi < body_extra.size() ? body_extra[bi] : 0.0;
    for (std::size_t k = first_piece; k < pieces.size(); ++k) {
      const auto n = static_cast<double>(pieces[k].elements.size());
      pieces[k].weight = n + (b.element_count > 0 ? extra * n / b.element_count : 0.0);
    }
  }
  if (static_cast<int>(pieces.size()) < parts)
    throw InputError("the scene cannot be split among " + std::to_string(parts) +
                     " ranks: it has " + std::to_string(m.element_count) + " elements in " +
                     std::to_string(pieces.size()) +
                     " piece(s) (whole bodies and cuts of large ones); run it on fewer ranks");
  for (Piece& p : pieces) p.centroid = corner_centroid(m, p.elements);
  std::vector<std::int32_t> order(pieces.size());
  std::iota(order.begin(), order.end(), 0);
  bisect(m, pieces, order, 0, pieces.size(), 0, parts, out);
  return partition_from(m, parts, std::move(out.element_rank));
}

Partition partition_from(const Model& m, int parts, std::vector<std::int32_t> element_rank) {
  Partition out;
  out.parts = parts;
  out.element_rank = std::move(element_rank);
  out.part_elements.assign(parts, 0);
  for (std::int32_t r : out.element_rank) ++out.part_elements[r];
  out.node_rank.assign(m.node_count, -1);
  for (std::int32_t e = 0; e < m.element_count; ++e)
    for (std::int32_t n : m.conn[e])
      if (out.node_rank[n] < 0) out.node_rank[n] = out.element_rank[e];
  return out;
}

}  // namespace femdem
