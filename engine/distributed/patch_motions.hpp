// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Impact damping and rolling resistance on a rank of a distributed run (docs/ARCHITECTURE.md,
// "Distributed runs"): a contact patch between a body this rank holds and one another rank
// holds is on both ranks (each lists every pair of its own body's nodes), and each needs the
// other body's rigid motion to load its own. Bodies are whole on their ranks here (a body cut
// among ranks is refused with these loads).
#include <vector>

#include "engine/contact_patch.hpp"
#include "engine/distributed/distribution.hpp"
#include "engine/impact_damping.hpp"
#include "engine/model.hpp"

namespace femdem {

// After prepare_patch_loads, on every rank: sends the rigid motion of each of this rank's free
// bodies in a patch with another rank's body to that rank, takes theirs into s.rigid (the bits
// their ranks computed), and marks the patches this rank counts in the sums (those whose
// first body it holds: each patch once over the ranks).
void share_patch_motions(const Model& m, const Distribution& dist,
                         const std::vector<ContactPatch>& patches, PatchLoads& s);

}  // namespace femdem
