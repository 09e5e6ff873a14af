// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/impact_damping.hpp"

#include <algorithm>
#include <cmath>

#include "engine/parallel_threshold.hpp"

namespace femdem {

void prepare_patch_loads(const Model& m, const std::vector<ContactPatch>& patches,
                         const std::vector<double>& accel, double half_dt, PatchLoads& s) {
  auto free_body = [&](std::int32_t b) { return b >= 0 && !m.bodies[b].fixed; };
  std::fill(s.known.begin(), s.known.end(), 0);
  s.counted.clear();
  s.power = ExactSum{};
  s.wall_force.assign(3 * m.walls.size(), ExactSum{});
  for (const ContactPatch& p : patches) {
    if (!patch_acts(p)) continue;
    for (const std::int32_t b : {p.body_a, p.body_b})
      if (free_body(b)) s.known[b] = 1;
  }
  const auto nb = static_cast<std::int64_t>(m.bodies.size());
#pragma omp parallel for schedule(dynamic, 1) if (nb > 1 && m.node_count > kParallelMinElements)
  for (std::int64_t b = 0; b < nb; ++b) {
    if (!s.known[b]) continue;
    s.rigid[b] = rigid_motion(m, m.bodies[b], accel.data(), half_dt);
    s.force[b].setZero();
    s.moment[b].setZero();
  }
}

void damp_impacts(const Model& m, double ratio, const std::vector<ContactPatch>& patches,
                  PatchLoads& s) {
  auto free_body = [&](std::int32_t b) { return b >= 0 && !m.bodies[b].fixed; };
  for (std::size_t q = 0; q < patches.size(); ++q) {
    const ContactPatch& p = patches[q];
    if (!patch_acts(p)) continue;
    const double F = p.force_on_a.norm();
    const Vec3 n = p.force_on_a / F;  // from b towards a
    const Vec3 x = p.point();
    Vec3 va = Vec3::Zero(), vb = Vec3::Zero();
    double inverse_mass = 0.0;
    if (free_body(p.body_a)) {
      const RigidMotion& r = s.rigid[p.body_a];
      if (!(r.mass > 0.0)) continue;
      va = r.velocity_at(x);
      inverse_mass += r.inverse_mass_along(x, n);
    }
    if (free_body(p.body_b)) {
      const RigidMotion& r = s.rigid[p.body_b];
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
    const Vec3 f = fd * n;
    if (free_body(p.body_a)) s.add(p.body_a, x, f);
    if (free_body(p.body_b)) s.add(p.body_b, x, -f);
    if (!s.counts(q)) continue;
    s.power.add(fd * vn);
    if (p.body_b < 0)
      for (int k = 0; k < 3; ++k)
        s.wall_force[3 * static_cast<std::size_t>(-1 - p.body_b) + k].add(-f[k]);
  }
}

void apply_patch_loads(Model& m, PatchLoads& s) {
  const auto nb = static_cast<std::int64_t>(m.bodies.size());
#pragma omp parallel for schedule(dynamic, 1) if (nb > 1 && m.node_count > kParallelMinElements)
  for (std::int64_t b = 0; b < nb; ++b)
    if (s.known[b] && s.rigid[b].mass > 0.0)
      add_rigid_load(m, m.bodies[b], s.rigid[b], s.force[b], s.moment[b], m.f_contact);
}

}  // namespace femdem
