// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The contact stiffness between bodies and of bodies on walls (docs/ARCHITECTURE.md, "The
// contact stiffness"). By default it is automatic, derived from the elements in contact, as
// explicit codes derive a segment stiffness f K A^2 / V: the pair's penalty-potential force
// grows with p A |grad phi| per unit of overlap, |grad phi| = 4 A_face / (3 V) for a contact
// sub-tetrahedron, and a wall's node spring is k A / h over its element depth h, so with p and
// k proportional to the material's P-wave modulus M (what sets the elements' own frequency,
// c^2 = M / rho) a contact spring stays a fixed fraction of the elements' stiffness on every
// mesh, and the step in contact a fixed fraction of the step before it. The softer side's M:
// the contact spring is then no stiffer than either side's elements. An explicit
// `penalty_factor` (scene key, [contact] or per wall) overrides this with the thesis' p = a E of
// the stiffer side.
#include <algorithm>
#include <cstdint>

#include "engine/model.hpp"

namespace femdem {

// p = kAutoPairFactor M of the softer body. Measured on steel cubes pressed flat together: the
// assembled step in contact is r = 1 / sqrt(1 + 9 p / E) of the cubes' own, so 0.2 M (0.27 E)
// keeps r at 0.54 (docs/ARCHITECTURE.md, "The contact stiffness").
inline constexpr double kAutoPairFactor = 0.2;
// k = kAutoWallFactor M A / h: the same spring on a node as a flat body pair's (a flat pair's
// node stiffness is 16 p A / h).
inline constexpr double kAutoWallFactor = 16.0 * kAutoPairFactor;

// The penalty (Pa) between two bodies' contact sub-tetrahedra.
inline double pair_penalty(const Model& m, std::int32_t body_a, std::int32_t body_b) {
  const MaterialParams& a = m.materials[m.bodies[body_a].material];
  const MaterialParams& b = m.materials[m.bodies[body_b].material];
  if (m.contact.penalty_factor > 0.0)
    return m.contact.penalty_factor * std::max(a.youngs_modulus, b.youngs_modulus);
  return kAutoPairFactor * std::min(a.p_wave_modulus(), b.p_wave_modulus());
}

// The modulus (Pa) of a wall's node springs on `body`: k = wall_modulus * area / depth.
inline double wall_modulus(const Model& m, const Wall& w, std::int32_t body) {
  const MaterialParams& mat = m.materials[m.bodies[body].material];
  if (w.penalty_factor > 0.0) return w.penalty_factor * mat.youngs_modulus;
  return kAutoWallFactor * mat.p_wave_modulus();
}

}  // namespace femdem
