// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/nbs_broadphase.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace femdem {

namespace {

// Radix digit: 11 bits, so the usual scenes (up to 2^7 cells per axis, 21 key bits) sort in two
// passes and 2^21 cells per axis in six; the 2048-entry histogram stays in L1.
constexpr int kDigitBits = 11;
constexpr std::uint64_t kDigitMask = (std::uint64_t{1} << kDigitBits) - 1;

// Cells per axis are kept below 2^21 - 2, so a key field (coordinate + 1, room for the -1 and +1
// neighbours) fits in 21 bits and a key in 63. Cell coordinates are then computed to about 1e-9
// of a cell, far inside the 1e-6 margin of the cell size, so rounding never puts two
// overlapping boxes two cells apart. Scenes wider than 2^21 largest boxes get coarser cells:
// still correct, only more boxes per cell.
constexpr double kMaxCellsPerAxis = (1 << 21) - 4;
constexpr int kMaxKeyBits = 63;

[[noreturn]] void bad_box(std::size_t b, const char* what) {
  throw std::invalid_argument("NbsBroadphase: box " + std::to_string(b) + " " + what);
}

}  // namespace

void NbsBroadphase::find_pairs(std::span<const Aabb> boxes, std::span<const std::int32_t> groups,
                               std::vector<CandidatePair>& out_pairs) {
  out_pairs.clear();
  found_.clear();
  cell_key_.clear();
  cell_start_.clear();
  box_tests_ = 0;
  cell_size_ = 0.0;
  const std::size_t n = boxes.size();
  if (groups.size() != n)
    throw std::invalid_argument("NbsBroadphase: " + std::to_string(n) + " boxes but " +
                                std::to_string(groups.size()) + " group ids");
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("NbsBroadphase: 2^32 boxes or more");

  // Validate, and find the scene's extent and the largest box extent.
  std::array<double, 3> scene_lo{}, scene_hi{};
  double largest = 0.0;
  bool one_group = true;
  for (std::size_t b = 0; b < n; ++b) {
    const Aabb& box = boxes[b];
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]))
        bad_box(b, "has a non-finite coordinate");
      if (box.lo[a] > box.hi[a]) bad_box(b, "has lo > hi");
      largest = std::max(largest, box.hi[a] - box.lo[a]);
      scene_lo[a] = b == 0 ? box.lo[a] : std::min(scene_lo[a], box.lo[a]);
      scene_hi[a] = b == 0 ? box.lo[a] : std::max(scene_hi[a], box.lo[a]);  // of the lo corners
    }
    one_group = one_group && groups[b] == groups[0];
  }
  if (n < 2 || one_group) return;

  // Cell size. It must be at least the largest extent (the two-boxes-one-cell-apart argument in
  // the header); the 1e-6 margin absorbs the rounding of extents and cell coordinates.
  std::array<double, 3> span{};
  double widest = 0.0;
  for (int a = 0; a < 3; ++a) {
    span[a] = scene_hi[a] - scene_lo[a];  // may be +inf for coordinates near +-1e308
    widest = std::max(widest, span[a]);
  }
  double d = largest * (1.0 + 1e-6);
  if (d == 0.0) {
    // Only zero-size boxes (points): any cell size works; the mean spacing keeps cells small.
    d = widest / std::cbrt(static_cast<double>(n));
    if (d == 0.0) d = 1.0;  // all at one point
  }
  d = std::max(d, widest / kMaxCellsPerAxis);
  std::array<std::uint64_t, 3> cells{1, 1, 1};
  std::array<int, 3> bits{};
  for (;;) {
    int total = 0;
    for (int a = 0; a < 3; ++a) {
      cells[a] = std::isfinite(d) ? static_cast<std::uint64_t>(span[a] / d) + 1 : 1;
      // Fields hold coordinate + 1 in [0, cells + 1], room for the -1 and +1 neighbours.
      bits[a] = std::bit_width(cells[a] + 1);
      total += bits[a];
    }
    if (total <= kMaxKeyBits) break;
    d *= 2.0;  // a safeguard: kMaxCellsPerAxis already keeps 3 fields within 63 bits
  }
  cell_size_ = d;
  const int shift_y = bits[0];
  const int shift_z = bits[0] + bits[1];

  // Cell key of each box (its lo corner), in input order.
  key_.resize(n);
  index_.resize(n);
  const double inv_d = std::isfinite(d) ? 1.0 / d : 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      double c = std::floor((boxes[b].lo[a] - scene_lo[a]) * inv_d);
      // Clamping is monotone, so boxes one cell apart stay at most one cell apart.
      if (!(c >= 0.0)) c = 0.0;
      c = std::min(c, static_cast<double>(cells[a] - 1));
      const std::uint64_t field = static_cast<std::uint64_t>(c) + 1;
      key |= field << (a == 0 ? 0 : a == 1 ? shift_y : shift_z);
    }
    key_[b] = key;
    index_[b] = static_cast<std::uint32_t>(b);
  }

  // The forward neighbours of cell (x, y, z): (x+1, y, z) is the next key; the other 12 are the
  // three cells x-1..x+1 of the rows (y+1, z), (y-1, z+1), (y, z+1), (y+1, z+1). Each row start
  // (x-1) is the cell key plus a positive constant, because no field borrows or carries.
  const std::uint64_t one_y = std::uint64_t{1} << shift_y;
  const std::uint64_t one_z = std::uint64_t{1} << shift_z;
  row_offset_ = {one_y - 1, one_z - one_y - 1, one_z - 1, one_z + one_y - 1};

  sort_by_cell(n);

  // Boxes in cell order, and the occupied cells.
  sorted_box_.resize(n);
  sorted_group_.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    sorted_box_[s] = boxes[index_[s]];
    sorted_group_[s] = groups[index_[s]];
    if (s == 0 || key_[s] != key_[s - 1]) {
      cell_key_.push_back(key_[s]);
      cell_start_.push_back(static_cast<std::uint32_t>(s));
    }
  }
  cell_start_.push_back(static_cast<std::uint32_t>(n));
  // The end of each box's run of one group within its cell: a cell inside a body holds mostly
  // that body's boxes, and the sweep steps over such a run at once instead of testing each box
  // of it only to reject it (the pairs found, and their order, are the same).
  run_end_.resize(n);
  for (std::size_t s = n; s-- > 0;)
    run_end_[s] = s + 1 < n && key_[s + 1] == key_[s] && sorted_group_[s + 1] == sorted_group_[s]
                      ? run_end_[s + 1]
                      : static_cast<std::uint32_t>(s + 1);

  sweep_cells();
  order_pairs(n, out_pairs);
}

// Stable LSD radix sort of (key_, index_) by key_: within a cell the boxes stay in input order,
// so everything after is deterministic. Digits that are equal for all keys are skipped.
void NbsBroadphase::sort_by_cell(std::size_t n) {
  key_tmp_.resize(n);
  index_tmp_.resize(n);
  std::uint64_t all_bits = 0;
  for (std::size_t b = 0; b < n; ++b) all_bits |= key_[b];
  std::array<std::uint32_t, kDigitMask + 1> hist{};
  for (int shift = 0; shift < 64 && (all_bits >> shift) != 0; shift += kDigitBits) {
    hist.fill(0);
    for (std::size_t b = 0; b < n; ++b) ++hist[(key_[b] >> shift) & kDigitMask];
    if (hist[(key_[0] >> shift) & kDigitMask] == n) continue;  // one digit value: nothing to do
    std::uint32_t sum = 0;
    for (auto& h : hist) {
      const std::uint32_t c = h;
      h = sum;
      sum += c;
    }
    for (std::size_t b = 0; b < n; ++b) {
      const std::uint32_t to = hist[(key_[b] >> shift) & kDigitMask]++;
      key_tmp_[to] = key_[b];
      index_tmp_[to] = index_[b];
    }
    key_.swap(key_tmp_);
    index_.swap(index_tmp_);
  }
}

// Visits every cell with itself and its 13 forward neighbours (each neighbouring cell pair once),
// using one cursor per forward row; a cursor only moves forward, since its target is the current
// key plus a constant.
void NbsBroadphase::sweep_cells() {
  const std::size_t cells = cell_key_.size();
  const Aabb* box = sorted_box_.data();
  const std::int32_t* group = sorted_group_.data();
  const std::uint32_t* index = index_.data();
  const std::uint32_t* run_end = run_end_.data();
  std::size_t tests = 0;

  auto emit = [&](std::uint32_t s, std::uint32_t t) {
    const std::uint32_t a = index[s], b = index[t];
    found_.push_back(a < b ? CandidatePair{a, b} : CandidatePair{b, a});
  };
  // All pairs between cell p (positions [p0, p1)) and cell q, q != p.
  auto cross = [&](std::size_t p, std::size_t q) {
    const std::uint32_t p0 = cell_start_[p], p1 = cell_start_[p + 1];
    const std::uint32_t q0 = cell_start_[q], q1 = cell_start_[q + 1];
    for (std::uint32_t s = p0; s < p1; ++s) {
      const Aabb& bs = box[s];
      const std::int32_t gs = group[s];
      for (std::uint32_t t = q0; t < q1; ++t) {
        if (group[t] == gs) {
          t = run_end[t] - 1;  // the rest of this body's run in the cell
          continue;
        }
        ++tests;
        if (boxes_overlap(bs, box[t])) emit(s, t);
      }
    }
  };

  std::array<std::size_t, 4> cursor{};
  for (std::size_t p = 0; p < cells; ++p) {
    const std::uint64_t key = cell_key_[p];
    // Own cell.
    const std::uint32_t p0 = cell_start_[p], p1 = cell_start_[p + 1];
    for (std::uint32_t s = p0; s < p1; ++s) {
      const Aabb& bs = box[s];
      const std::int32_t gs = group[s];
      for (std::uint32_t t = run_end[s]; t < p1; ++t) {
        if (group[t] == gs) {
          t = run_end[t] - 1;
          continue;
        }
        ++tests;
        if (boxes_overlap(bs, box[t])) emit(s, t);
      }
    }
    // (x+1, y, z): the next occupied cell if its key is one more.
    if (p + 1 < cells && cell_key_[p + 1] == key + 1) cross(p, p + 1);
    // The four forward rows, three cells each.
    for (int r = 0; r < 4; ++r) {
      const std::uint64_t first = key + row_offset_[r];
      std::size_t& q = cursor[r];
      while (q < cells && cell_key_[q] < first) ++q;
      for (std::size_t k = q; k < cells && cell_key_[k] <= first + 2; ++k) cross(p, k);
    }
  }
  box_tests_ = tests;
}

// Counting sort of the found pairs by their first index, then each (short) run by the second:
// O(N + pairs) and the order does not depend on how the boxes fell into cells.
void NbsBroadphase::order_pairs(std::size_t n, std::vector<CandidatePair>& out_pairs) {
  count_.assign(n + 1, 0);
  for (const CandidatePair& p : found_) ++count_[p.i + 1];
  for (std::size_t b = 0; b < n; ++b) count_[b + 1] += count_[b];
  out_pairs.resize(found_.size());
  for (const CandidatePair& p : found_) out_pairs[count_[p.i]++] = p;
  // count_[b] is now the end of box b's run, and count_[b - 1] its start.
  std::uint32_t start = 0;
  for (std::size_t b = 0; b < n; ++b) {
    const std::uint32_t end = count_[b];
    if (end - start > 1) {
      auto first = out_pairs.begin() + start, last = out_pairs.begin() + end;
      if (end - start <= 16) {
        for (auto it = first + 1; it != last; ++it)  // insertion sort: runs are short
          for (auto jt = it; jt != first && jt->j < (jt - 1)->j; --jt) std::iter_swap(jt, jt - 1);
      } else {
        std::sort(first, last);
      }
    }
    start = end;
  }
}

std::size_t NbsBroadphase::memory_bytes() const {
  return (key_.capacity() + key_tmp_.capacity() + cell_key_.capacity()) * sizeof(std::uint64_t) +
         (index_.capacity() + index_tmp_.capacity() + cell_start_.capacity() + count_.capacity() +
          run_end_.capacity()) *
             sizeof(std::uint32_t) +
         sorted_box_.capacity() * sizeof(Aabb) + sorted_group_.capacity() * sizeof(std::int32_t) +
         found_.capacity() * sizeof(CandidatePair);
}

}  // namespace femdem
