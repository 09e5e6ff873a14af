// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/rolling_resistance.hpp"

#include <algorithm>
#include <cmath>

namespace femdem {

void resist_rolling(const Model& m, const std::vector<ContactPatch>& patches, double dt,
                    PatchLoads& s) {
  auto free_body = [&](std::int32_t b) { return b >= 0 && !m.bodies[b].fixed; };
  for (std::size_t q = 0; q < patches.size(); ++q) {
    const ContactPatch& p = patches[q];
    if (!patch_acts(p)) continue;
    const double mu_r = p.body_b < 0
                            ? m.walls[static_cast<std::size_t>(-1 - p.body_b)].rolling_resistance
                            : m.contact.rolling_resistance;
    if (!(mu_r > 0.0)) continue;
    const double N = p.force_on_a.norm();
    const Vec3 n = p.force_on_a / N;
    const Vec3 x = p.point();
    const bool a_free = free_body(p.body_a), b_free = free_body(p.body_b);
    if (!a_free && !b_free) continue;
    if ((a_free && !(s.rigid[p.body_a].mass > 0.0)) || (b_free && !(s.rigid[p.body_b].mass > 0.0)))
      continue;
    // the relative spin, and the rolling radius: R_a R_b / (R_a + R_b) between two free bodies,
    // the free one's distance to the contact against a fixed body or a wall
    Vec3 w = Vec3::Zero();
    double r_a = 0.0, r_b = 0.0;
    if (a_free) {
      w += s.rigid[p.body_a].angular_velocity;
      r_a = (x - s.rigid[p.body_a].centre).norm();
    }
    if (b_free) {
      w -= s.rigid[p.body_b].angular_velocity;
      r_b = (x - s.rigid[p.body_b].centre).norm();
    }
    const double radius = a_free && b_free ? r_a * r_b / (r_a + r_b) : a_free ? r_a : r_b;
    const Vec3 rolling = w - w.dot(n) * n;  // the spin about the normal is not rolling
    const double omega = rolling.norm();
    if (!(omega > 0.0)) continue;
    const Vec3 e = rolling / omega;
    double inverse_inertia = 0.0;  // about e, of the two bodies together
    if (a_free) inverse_inertia += e.dot(s.rigid[p.body_a].inertia_inverse * e);
    if (b_free) inverse_inertia += e.dot(s.rigid[p.body_b].inertia_inverse * e);
    const double M = std::min(mu_r * radius * N, 0.5 * omega / (inverse_inertia * dt));
    if (s.counts(q)) s.power.add(-M * omega);
    if (a_free) s.moment[p.body_a] -= M * e;
    if (b_free) s.moment[p.body_b] += M * e;
  }
}

}  // namespace femdem
