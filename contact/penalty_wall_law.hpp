// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The node-on-rigid-wall contact law (docs/ARCHITECTURE.md, "Wall contact"): a linear penalty
// spring k d along the wall normal, an optional dashpot on the normal speed (a fraction of
// critical, never pulling), and Coulomb friction by a tangential spring as stiff as the normal
// one that slides at mu times the normal force. Conservative but for the dashpot and sliding,
// whose work it reports. A wall law is one such struct, named in contact/contact_laws.hpp:
// engine/wall_contact.cpp applies it to every (boundary node, wall) pair in contact.
#include <algorithm>
#include <cmath>

#include "elements/tet10_mesh.hpp"

namespace femdem {

// One boundary node against one wall, this step.
struct WallContactInput {
  double k = 0.0;          // normal penalty stiffness of the node, N/m
  double depth = 0.0;      // penetration, > 0
  double node_mass = 0.0;  // for the dashpot's critical damping
  double damping = 0.0;    // fraction of critical
  double friction = 0.0;   // Coulomb coefficient
  double step_dt = 0.0;    // the step the tangential motion is integrated over
  Vec3 normal = Vec3::UnitZ();
  Vec3 v_rel = Vec3::Zero();  // node velocity relative to the wall (half-step)
};

// What the law adds to the step's accounts (in the order the energy balance sums them).
struct WallContactSums {
  double energy = 0.0;               // stored in springs now
  double damping_power = 0.0;        // of the dashpots, <= 0
  double friction_dissipated = 0.0;  // by sliding and released springs over the step
};

struct PenaltyWallLaw {
  static constexpr const char* name = "penalty";  // the scene's [contact] wall_law
  // The force on the node; `slip` (3, or null without friction) is the friction spring's
  // stretch, updated.
  static Vec3 apply(const WallContactInput& in, double* slip, WallContactSums& sums) {
    const double k = in.k, d = in.depth;
    double fn = k * d;
    const double vn = in.v_rel.dot(in.normal);
    if (in.damping > 0.0) {
      // dashpot on the approach/separation speed (half-step velocity), never pulling
      const double fd = std::max(-2.0 * in.damping * std::sqrt(k * in.node_mass) * vn, -fn);
      fn += fd;
      sums.damping_power += fd * vn;  // <= 0
    }
    Vec3 f = fn * in.normal;
    sums.energy += 0.5 * k * d * d;
    if (slip && in.friction > 0.0) {
      // The spring stretches with the tangential motion over the step (half-step velocity);
      // past mu fn it slides, and the energy it sheds is dissipated.
      const Vec3 u_old(slip[0], slip[1], slip[2]);
      const Vec3 du = in.step_dt * (in.v_rel - vn * in.normal);
      Vec3 u = u_old + du;
      u -= u.dot(in.normal) * in.normal;
      const double limit = in.friction * fn / k;  // largest stuck stretch
      const double stretch = u.norm();
      if (stretch > limit) {
        // Slides. Dissipated: the work of the spring force over the step (trapezoidal in its
        // old and new values, as the time integrator applies it) minus the change of its
        // stored energy; mu fn times the slip for a steady slide, 0 when stuck.
        const Vec3 u_new = u * (limit / stretch);
        sums.friction_dissipated +=
            0.5 * k * ((u_old + u_new).dot(du) - (u_new.squaredNorm() - u_old.squaredNorm()));
        u = u_new;
      }
      f -= k * u;
      sums.energy += 0.5 * k * u.squaredNorm();
      slip[0] = u[0], slip[1] = u[1], slip[2] = u[2];
    }
    return f;
  }

  // The node left the wall: its friction spring is released and its energy lost to friction.
  static void release(double k, double* slip, WallContactSums& sums) {
    const Vec3 u(slip[0], slip[1], slip[2]);
    sums.friction_dissipated += 0.5 * k * u.squaredNorm();
    slip[0] = slip[1] = slip[2] = 0.0;
  }
};

}  // namespace femdem
