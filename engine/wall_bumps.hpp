// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A studded wall's relief: hemispheres of one radius centred on the wall's plane at the nodes
// of a hexagonal (triangular) lattice in it, the rough plane of glued beads a granular column
// collapses on (Lajeunesse et al. 2004). A grain on it sits in the pocket between three bumps
// and must lift its centre over two of them to move, whatever the friction; a flat plane with
// a rolling resistance only resists rolling, and lets a low-friction base slide.
//
// `nearest` gives how deep a point lies inside the nearest bump and the outward direction from
// that bump's centre. All bumps have one radius, so the deepest bump is the one whose centre is
// nearest; in a triangular lattice that is a corner of the lattice triangle the point's
// projection falls in (the Voronoi cells of a triangle's corners cover it), so four corners of
// the lattice rhombus are enough: no search, no allocation, a few flops per node and step.
#include <cmath>

#include "elements/tet10_mesh.hpp"
#include "engine/plane_axis.hpp"

namespace femdem {

struct WallBumps {
  double radius = 0.0;   // 0: a flat wall
  double spacing = 0.0;  // between neighbouring bump centres (2 radius: touching bumps)
  Vec3 u = Vec3::UnitX(), v = Vec3::UnitY();  // orthonormal lattice axes in the wall's plane

  bool present() const { return radius > 0.0; }

  // Lattice axes for a wall of unit normal n: u = in_plane_axis(n) (x for a floor), v = n x u.
  void orient(const Vec3& n) {
    u = in_plane_axis(n);
    v = n.cross(u);
  }

  struct Inside {
    double depth = -HUGE_VAL;  // radius - distance to the nearest centre (> 0: inside it)
    Vec3 normal = Vec3::UnitZ();
  };
  // p's depth in the nearest bump of a lattice with a node at `origin` (a point of the plane).
  Inside nearest(const Vec3& p, const Vec3& origin, const Vec3& wall_normal) const {
    const Vec3 r = p - origin;
    // lattice coordinates: centres at origin + (i + j / 2) s u + j (sqrt(3) / 2) s v
    const double row = spacing * (std::sqrt(3.0) / 2.0);
    const double j = r.dot(v) / row;
    const double i = r.dot(u) / spacing - 0.5 * j;
    const double i0 = std::floor(i), j0 = std::floor(j);
    double best = HUGE_VAL;
    Vec3 best_offset = Vec3::Zero();
    for (int c = 0; c < 4; ++c) {
      const double ic = i0 + (c & 1), jc = j0 + (c >> 1);
      const Vec3 offset = r - ((ic + 0.5 * jc) * spacing) * u - (jc * row) * v;
      const double d2 = offset.squaredNorm();
      if (d2 < best) best = d2, best_offset = offset;
    }
    const double d = std::sqrt(best);
    // (a point on a centre, never met in practice, is pushed out along the wall's normal)
    return {radius - d, d > 0.0 ? Vec3(best_offset / d) : wall_normal};
  }
};

}  // namespace femdem
