// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// When must the contact candidate list be rebuilt? The Verlet-list ("buffer zone") rule of
// Munjiza & Andrews (1998), so the broadphase need not run every step.
//
// Convention: `buffer` is the distance up to which entities are listed as candidates. The caller
// enlarges every entity's bounding box by buffer / 2 on each side, so two entities are
// candidates when their true bounding boxes are less than `buffer` apart on every axis (two
// enlarged boxes touch at a gap of exactly buffer).
//
// Why rebuild at half the buffer: a pair missing from the list had its true boxes more than
// `buffer` apart on some axis at the last build. A bounding box of nodes that each moved at most
// s lies inside the old box grown by s, so that gap has shrunk by at most 2 s: the two entities
// may both have moved s towards each other. The list is therefore complete while 2 s <= buffer,
// i.e. while the largest node displacement s since the last build stays <= buffer / 2.
//
// Use: after each broadphase, record(positions); each step, if needs_rebuild(positions), run the
// broadphase again (with boxes built from the current positions) and record again.
#include <span>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

class VerletBuffer {
 public:
  // buffer > 0 and finite; throws std::invalid_argument otherwise.
  explicit VerletBuffer(double buffer);

  double buffer() const { return buffer_; }
  // Each box's enlargement on each side: buffer / 2.
  double margin() const { return 0.5 * buffer_; }

  // Remembers the positions the candidate list was built from (reuses its storage).
  void record(std::span<const Vec3> positions);
  bool has_record() const { return recorded_; }
  // The positions recorded last (empty before the first record): a checkpoint saves them and
  // hands them back to record() on restart.
  const std::vector<Vec3>& recorded_positions() const { return reference_; }

  // Largest |x - x_recorded| over the nodes; +infinity if nothing is recorded, the node count
  // changed, or a position is not finite (NaN compares false, so it must not slip through).
  double max_displacement(std::span<const Vec3> positions) const;

  // True when the list may have missed a pair: max_displacement > buffer / 2.
  bool needs_rebuild(std::span<const Vec3> positions) const;

 private:
  double buffer_ = 0.0;
  bool recorded_ = false;
  std::vector<Vec3> reference_;
};

}  // namespace femdem
