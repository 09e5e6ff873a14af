// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// NBS ("no binary search") broadphase after Munjiza & Andrews (1998): all pairs of overlapping
// axis-aligned boxes that belong to different groups, in O(N) time and O(N) memory whatever the
// packing density.
//
// Input: one box per contact entity (in femdem the bounding box of a surface sub-tetrahedron,
// already enlarged by the Verlet buffer by the caller, see contact_buffer.hpp) and one group id
// per box (the body). Boxes are closed: boxes that only touch (a face, an edge, a corner, or a
// zero-size box on another's face) overlap, the convention of FCL's AABB::overlap.
//
// Output: pairs (i, j), i < j, boxes[i] and boxes[j] overlap, groups[i] != groups[j], sorted by
// (i, j) and without duplicates: the same input gives the same list on any machine.
//
// How (see nbs_broadphase.cpp for the details):
//  - Cubic cells of edge d = the largest box extent along any axis (times 1 + 1e-6). A box is put
//    in the cell of its min corner. Two overlapping boxes A, B satisfy
//    |A.lo - B.lo| <= max(extent A, extent B) <= d on every axis, so their cells differ by at most
//    one on every axis: a box needs checking only against its own cell and the 26 around it, and,
//    by symmetry, against its own cell and 13 "forward" ones (each cell pair visited once).
//  - Instead of Munjiza's singly linked lists per layer, row and column, the boxes are sorted by
//    the packed integer cell key (z, y, x) with an LSD radix sort (stable, O(N) memory; the same
//    grouping into layers, rows and cells). The 13 forward neighbours of a cell are the next
//    cell of its row and three cells in each of 4 rows whose keys are the cell's key plus a
//    constant, so 4 cursors that only move forward through the sorted cells find them: no
//    binary search and no array over the grid. Within a cell the boxes of one group stay
//    together (the sort is stable, and callers list a body's boxes together), and a run of one
//    group is stepped over at once: the boxes inside a large body cost no tests. Memory never
//    depends on the number of cells of the bounding box, so widely scattered bodies cost nothing
//    extra. (Memory: 96 bytes per box plus 8 per candidate pair, all reused between calls.)
//  - Cells per axis are capped at about 2^21 (a 64-bit key); a scene wider than 2^21 largest
//    boxes (say 1 mm tets spread over 2 km) gets coarser cells: still exact, only slower.
//
// Cost: about N (sort, 1-3 radix passes for usual scenes) + the box tests of neighbouring
// cells. With boxes of similar size each cell holds O(1) boxes and the cost is linear in N. With
// very different sizes the cell follows the largest box, so a cell may hold (d / small size)^3
// small boxes and the tests grow like N times that number (quadratic in the worst case: one box
// as large as the scene). Contact entities of one mesh have similar sizes, so this is rare in
// FEM-DEM; a scene mixing very coarse and very fine bodies should be detected per size class.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace femdem {

struct Aabb {
  std::array<double, 3> lo{};  // min corner
  std::array<double, 3> hi{};  // max corner
};

struct CandidatePair {
  std::uint32_t i = 0;  // i < j
  std::uint32_t j = 0;
  friend bool operator==(const CandidatePair&, const CandidatePair&) = default;
  friend auto operator<=>(const CandidatePair&, const CandidatePair&) = default;
};

// Closed-interval overlap test on all three axes (touching boxes overlap).
inline bool boxes_overlap(const Aabb& a, const Aabb& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// Keeps its work arrays between calls: once they have grown to a scene's size, find_pairs does
// not allocate (out_pairs too, if the caller passes the same vector each time).
class NbsBroadphase {
 public:
  // Replaces out_pairs by the candidate pairs. Throws std::invalid_argument if the sizes differ,
  // if there are 2^32 boxes or more, or naming the first box with a non-finite coordinate or
  // with lo > hi.
  void find_pairs(std::span<const Aabb> boxes, std::span<const std::int32_t> groups,
                  std::vector<CandidatePair>& out_pairs);

  // Bytes held by the work arrays (their capacity), for memory accounting.
  std::size_t memory_bytes() const;

  // Statistics of the last call.
  double cell_size() const { return cell_size_; }
  std::size_t occupied_cells() const { return cell_key_.size(); }
  // Box tests between different groups (runs of one group in a cell are stepped over).
  std::size_t box_tests() const { return box_tests_; }

 private:
  void sort_by_cell(std::size_t n);
  void sweep_cells();
  void order_pairs(std::size_t n, std::vector<CandidatePair>& out_pairs);

  double cell_size_ = 0.0;
  std::size_t box_tests_ = 0;

  // Per box, in input order: packed cell key; then radix-sorted (key, index) pairs.
  std::vector<std::uint64_t> key_, key_tmp_;
  std::vector<std::uint32_t> index_, index_tmp_;
  // Boxes and groups copied in cell order, so the pair tests read memory sequentially.
  std::vector<Aabb> sorted_box_;
  std::vector<std::int32_t> sorted_group_;
  // Per sorted position: one past the last box of its run of one group within its cell.
  std::vector<std::uint32_t> run_end_;
  // Occupied cells in key order: key and first position in the sorted arrays (plus an end).
  std::vector<std::uint64_t> cell_key_;
  std::vector<std::uint32_t> cell_start_;
  // Row key offsets of the forward neighbour rows (see the .cpp).
  std::array<std::uint64_t, 4> row_offset_{};
  // Pairs as found (cell order), and the counting sort by first index.
  std::vector<CandidatePair> found_;
  std::vector<std::uint32_t> count_;
};

}  // namespace femdem
