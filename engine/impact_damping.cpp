// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/impact_damping.hpp"

#include <algorithm>
#include <cmath>

namespace femdem {

double damp_impacts(Model& m, double ratio, const std::vector<ContactPatch>& patches,
                    const std::vector<double>& accel, double half_dt,
                    std::vector<RigidMotion>& rigid, std::vector<std::uint8_t>& known) {
  auto motion = [&](std::int32_t b) -> const RigidMotion& {
    if (!known[b]) {
      rigid[b] = rigid_motion(m, m.bodies[b], accel.data(), half_dt);
      known[b] = 1;
    }
    return rigid[b];
  };
  auto free_body = [&](std::int32_t b) { return b >= 0 && !m.bodies[b].fixed; };
  double power = 0.0;
  for (const ContactPatch& p : patches) {
    const double F = p.force_on_a.norm();
    if (!(F > 0.0) || !(p.weight > 0.0) || !(p.stiffness > 0.0)) continue;
    const Vec3 n = p.force_on_a / F;  // from b towards a
    const Vec3 x = p.point();
    Vec3 va = Vec3::Zero(), vb = Vec3::Zero();
    double inverse_mass = 0.0;
    if (free_body(p.body_a)) {
      const RigidMotion& r = motion(p.body_a);
      if (!(r.mass > 0.0)) continue;
      va = r.velocity_at(x);
      inverse_mass += r.inverse_mass_along(x, n);
    }
    if (free_body(p.body_b)) {
      const RigidMotion& r = motion(p.body_b);
      if (!(r.mass > 0.0)) continue;
      vb = r.velocity_at(x);
      inverse_mass += r.inverse_mass_along(x, n);
    } else if (p.body_b < 0) {
      vb = m.walls[static_cast<std::size_t>(-1 - p.body_b)].step_velocity;
    }
    if (!(inverse_mass > 0.0)) continue;  // two fixed sides
    const double vn = (va - vb).dot(n);   // < 0 while approaching
    const double c = 2.0 * ratio * std::sqrt(p.stiffness / inverse_mass);
    const double fd = std::max(-c * vn, -F);
    power += fd * vn;
    const Vec3 f = fd * n;
    if (free_body(p.body_a))
      add_rigid_load(m, m.bodies[p.body_a], rigid[p.body_a], x, f, m.f_contact);
    if (free_body(p.body_b)) {
      add_rigid_load(m, m.bodies[p.body_b], rigid[p.body_b], x, -f, m.f_contact);
    } else if (p.body_b < 0) {
      m.walls[static_cast<std::size_t>(-1 - p.body_b)].force -= f;
    }
  }
  return power;
}

}  // namespace femdem
