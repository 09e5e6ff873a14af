// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Prescribed motion of a rigid wall: a velocity history, piecewise linear in time and held at
// its last value after its last time; the displacement is its exact integral. A wall that must
// start from rest (a quasi-static compression: a wall starting at full speed v sends a stress
// wave of rho c v into the specimen) or load, unload and come back (a punch) uses one.
#include <cstddef>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

struct VelocityPoint {
  double time = 0.0;
  Vec3 velocity = Vec3::Zero();
};

// points: times strictly increasing from 0 (the reader checks it); empty means "at rest".
inline Vec3 history_velocity(const std::vector<VelocityPoint>& points, double t) {
  if (points.empty()) return Vec3::Zero();
  if (t <= points.front().time) return points.front().velocity;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const VelocityPoint &a = points[i], &b = points[i + 1];
    if (t < b.time) {
      const double s = (t - a.time) / (b.time - a.time);
      return a.velocity + s * (b.velocity - a.velocity);
    }
  }
  return points.back().velocity;
}

// Displacement since t = 0: the exact integral of history_velocity from 0 to t (t >= 0).
inline Vec3 history_displacement(const std::vector<VelocityPoint>& points, double t) {
  Vec3 d = Vec3::Zero();
  if (points.empty() || t <= 0.0) return d;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const VelocityPoint &a = points[i], &b = points[i + 1];
    const double span = b.time - a.time;
    if (t < b.time) {
      const double tau = t - a.time;
      return d + tau * a.velocity + (0.5 * tau * tau / span) * (b.velocity - a.velocity);
    }
    d += 0.5 * span * (a.velocity + b.velocity);
  }
  return d + (t - points.back().time) * points.back().velocity;
}

// A prescribed force history: piecewise linear in time, held at its last value after its last
// time (a punch loaded, held and unloaded: [[0, 0], [t1, F], [t2, F], [t3, 0]]).
struct ForcePoint {
  double time = 0.0;
  double force = 0.0;
};

// points: times strictly increasing from 0 (the reader checks it); empty means no force.
inline double history_force(const std::vector<ForcePoint>& points, double t) {
  if (points.empty()) return 0.0;
  if (t <= points.front().time) return points.front().force;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const ForcePoint &a = points[i], &b = points[i + 1];
    if (t < b.time) return a.force + (t - a.time) / (b.time - a.time) * (b.force - a.force);
  }
  return points.back().force;
}

}  // namespace femdem
