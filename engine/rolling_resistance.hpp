// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Rolling resistance: a moment against the relative rolling of two bodies in contact (or a body
// on a wall), the standard rolling friction of DEM (a "type A" model): at each contact patch
// (engine/contact_patch.hpp), of normal force N at distance R_a and R_b from the two bodies'
// centres of mass,
//   M = mu_r R N  against the relative rolling,  R = R_a R_b / (R_a + R_b)  (R_a on a wall),
// the relative rolling being the relative angular velocity of the two rigid motions less its
// spin about the contact normal. It stands for what makes real grains stop rolling (their
// roughness and the flattening of their contacts) and for the shape of grains that are not
// round: a ball rolling on a plane with it slows down at 5/7 mu_r g.
//
// The moment is capped so that within one step it can at most halve the relative rolling
// (M dt (1/I_a + 1/I_b) <= |omega| / 2 about the rolling axis): a plain Coulomb-like moment
// would flip sign every step at rest, and this keeps the explicit update stable while a
// rolling pair slows at the full mu_r R N. It acts on the rigid motions only (a rigid load,
// engine/rigid_motion.hpp) and is equal and opposite on the two bodies; its work, M . omega
// <= 0, is contact dissipation. `contact.rolling_resistance` sets mu_r (0: off); a wall's own
// `rolling_resistance` sets it for the bodies on that wall.
#include <vector>

#include "engine/contact_patch.hpp"
#include "engine/impact_damping.hpp"
#include "engine/model.hpp"

namespace femdem {

// Adds the rolling-resistance moments of the patches to the loads (prepare_patch_loads first)
// and their power (<= 0) to s.power: mu_r is the wall's on a wall's patch, the contact's on the
// others. dt: the step the cap is set for.
void resist_rolling(const Model& m, const std::vector<ContactPatch>& patches, double dt,
                    PatchLoads& s);

}  // namespace femdem
