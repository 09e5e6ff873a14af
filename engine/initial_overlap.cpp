// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/initial_overlap.hpp"

#include <cstdio>

#include "engine/errors.hpp"

namespace femdem {

void check_initial_overlap(const Simulation& sim) {
  const Model& m = sim.model();
  const double allowed = m.contact.initial_overlap;
  char buf[600];
  const BodyContact& bodies = sim.body_contact();
  if (bodies.active() && bodies.max_penetration_per_size() > allowed) {
    const auto [a, b] = bodies.deepest_bodies();
    std::snprintf(buf, sizeof buf,
                  "bodies '%s' and '%s' overlap at the start (%.3g m deep at the deepest pair of "
                  "their surface elements, %.3g of the element size "
                  "there, more than contact.initial_overlap = %.3g): move them apart (their "
                  "position or mesh), or allow that much with contact.initial_overlap",
                  m.bodies[a].name.c_str(), m.bodies[b].name.c_str(), bodies.max_penetration(),
                  bodies.max_penetration_per_size(), allowed);
    throw InputError(buf, "", 0, 0, "contact.initial_overlap");
  }
  const WallContact& walls = sim.wall_contact();
  for (std::size_t w = 0; w < m.walls.size(); ++w) {
    if (!(walls.max_penetration_per_size(w) > allowed) || walls.deepest_body(w) < 0) continue;
    std::snprintf(buf, sizeof buf,
                  "body '%s' reaches %.3g m behind wall '%s' at the start (%.3g of the element "
                  "size there, more than contact.initial_overlap = %.3g): move the body or the "
                  "wall (walls.%s.point), or allow that much with contact.initial_overlap",
                  m.bodies[walls.deepest_body(w)].name.c_str(), walls.max_penetration(w),
                  m.walls[w].name.c_str(), walls.max_penetration_per_size(w), allowed,
                  m.walls[w].name.c_str());
    throw InputError(buf, "", 0, 0, "contact.initial_overlap");
  }
}

}  // namespace femdem
