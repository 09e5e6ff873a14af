// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The plane walls of a regular polygonal prism around an axis: a compaction die
// ([compaction] die) and a tube lifted off a granular column ([[tubes]]) are both made of them.
// Wall k (1-based, named PREFIX_k) faces the axis from the inscribed radius at the angle
// angle + 360 (k - 1) / sides degrees, measured from the first direction across the axis (x, or
// y when the axis is near x, made orthogonal to it; so a 4-sided die about z has faces normal to
// x and y). Only the geometry is set; the caller sets friction, penalty and motion.
#include <optional>
#include <string>
#include <vector>

#include "engine/model_spec.hpp"

namespace femdem::scene {

struct PolygonPrism {
  Vec3 centre = Vec3::Zero();  // a point on the axis
  Vec3 axis = Vec3(0, 0, 1);   // unit
  double radius = 0.0;         // inscribed: each face is this far from the axis
  int sides = 24;
  double angle = 0.0;  // degrees
  // the axial extent, measured along the axis from the centre; unset: unbounded that way
  std::optional<double> from, to;
};

std::vector<WallSpec> polygon_walls(const std::string& prefix, const PolygonPrism& prism);

// The side of a regular polygon of `sides` sides with inscribed radius r, and its area.
double polygon_side(double r, int sides);
double polygon_area(double r, int sides);

}  // namespace femdem::scene
