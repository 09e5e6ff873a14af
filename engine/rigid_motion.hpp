// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The rigid motion of a deformable body: the velocity field with its momentum and angular
// momentum (from the lumped nodal masses, positions and velocities), and loads that act on that
// motion only. Used by the deformation damping (which damps what is not rigid) and the impact
// damping (which damps the rigid motion at contacts).
#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "engine/model.hpp"

namespace femdem {

struct RigidMotion {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero();            // centre of mass
  Vec3 velocity = Vec3::Zero();          // of the centre of mass
  Vec3 angular_velocity = Vec3::Zero();  // I^-1 L about the centre
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d inertia_inverse = Eigen::Matrix3d::Zero();

  Vec3 velocity_at(const Vec3& p) const { return velocity + angular_velocity.cross(p - centre); }
  // 1 / (the mass a force along n at p meets): 1/M + (r x n) . I^-1 (r x n)
  double inverse_mass_along(const Vec3& p, const Vec3& n) const {
    const Vec3 rn = (p - centre).cross(n);
    return 1.0 / mass + rn.dot(inertia_inverse * rn);
  }
};

// From the current positions and (half-step) velocities; with accel, from the velocities
// v + half_dt accel (the full-step velocities predicted with the last accelerations). mass 0
// for a body without mass. One pass over the body's nodes: the sums are taken about its first
// node (so that they stay of the body's size, not of its distance from the origin) and moved to
// the centre of mass afterwards: L_c = sum m d x v - s x P and sum m r r^T = sum m d d^T -
// M s s^T, with d = x - x_first, s = c - x_first, r = d - s, P the momentum.
inline RigidMotion rigid_motion(const Model& m, const Body& b, const double* accel = nullptr,
                                double half_dt = 0.0) {
  RigidMotion r;
  const std::int32_t n0 = b.first_node, n1 = b.first_node + b.node_count;
  if (n1 <= n0) return r;
  const Vec3 origin(m.x[3 * n0], m.x[3 * n0 + 1], m.x[3 * n0 + 2]);
  Vec3 s = Vec3::Zero(), p = Vec3::Zero(), h = Vec3::Zero();
  double j[6] = {};  // sum m d d^T: xx, yy, zz, xy, xz, yz
  for (std::int32_t n = n0; n < n1; ++n) {
    const double mn = m.mass[n];
    const Vec3 d = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]) - origin;
    Vec3 v(m.v[3 * n], m.v[3 * n + 1], m.v[3 * n + 2]);
    if (accel) v += half_dt * Vec3(accel[3 * n], accel[3 * n + 1], accel[3 * n + 2]);
    r.mass += mn;
    s += mn * d;
    p += mn * v;
    h += mn * d.cross(v);
    j[0] += mn * d[0] * d[0], j[1] += mn * d[1] * d[1], j[2] += mn * d[2] * d[2];
    j[3] += mn * d[0] * d[1], j[4] += mn * d[0] * d[2], j[5] += mn * d[1] * d[2];
  }
  if (!(r.mass > 0.0)) return r;
  const Vec3 c = s / r.mass;  // the centre, from the first node
  r.centre = origin + c;
  r.velocity = p / r.mass;
  const Vec3 L = h - c.cross(p);
  Eigen::Matrix3d rr;  // sum m r r^T about the centre
  rr << j[0], j[3], j[4], j[3], j[1], j[5], j[4], j[5], j[2];
  rr -= r.mass * c * c.transpose();
  r.inertia = rr.trace() * Eigen::Matrix3d::Identity() - rr;
  // a solid body's inertia is positive definite; LDLT also copes with a flat one
  const auto ldlt = r.inertia.ldlt();
  r.angular_velocity = ldlt.solve(L);
  r.inertia_inverse = ldlt.solve(Eigen::Matrix3d::Identity());
  return r;
}

// Adds to f (3 per node) the nodal forces m_i (F / M + alpha x r_i), alpha = I^-1 M: the load of
// resultant F and moment M about the centre applied to the body as if it were rigid (a force F
// at p has M = (p - c) x F). Their resultant is F, their moment M, and their power F . v_c +
// M . omega for any velocity field with the body's momentum and angular momentum: a load on the
// rigid motion only, whose stiffness limit is the body's mass, not that of a light node.
inline void add_rigid_load(const Model& m, const Body& b, const RigidMotion& r, const Vec3& F,
                           const Vec3& M, std::vector<double>& f) {
  const Vec3 a = F / r.mass;
  const Vec3 alpha = r.inertia_inverse * M;
  const std::int32_t n0 = b.first_node, n1 = b.first_node + b.node_count;
  for (std::int32_t n = n0; n < n1; ++n) {
    const double mn = m.mass[n];
    const Vec3 d = Vec3(m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]) - r.centre;
    const Vec3 fn = mn * (a + alpha.cross(d));
    for (int k = 0; k < 3; ++k) f[3 * static_cast<std::size_t>(n) + k] += fn[k];
  }
}

}  // namespace femdem
