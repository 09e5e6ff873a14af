// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The default law between bodies, `[contact] law = "penalty_potential"`: the exact
// penalty-potential force of the pair's overlap (contact/tet_potential_contact.hpp) and Coulomb
// friction by a tangential spring per pair.
//
// Friction. The potential gives a pair its normal force N (the resultant on one side), energy
// E and overlap centroid c. The friction spring of the pair stretches with the tangential
// relative velocity at c, with stiffness k_t = N^2 / (2 E), the pair's secant normal stiffness
// (exact for a flat overlap of depth d, where E = N d / 2), so a stuck contact yields by at most
// mu d before it slides. Its force acts at c on both tetrahedra (spread by the barycentric
// coordinates of c), so it is equal and opposite with no spurious moment. The spring slides at
// mu N; the work of sliding is dissipated, the spring's energy is stored contact energy.
//
// Penetration. A pair's overlap depth is estimated as 2 E / N (exact for a flat overlap, see
// above).
#include "contact/body_pair_law.hpp"

namespace femdem {

struct PenaltyPotentialLaw {
  static constexpr const char* name = "penalty_potential";
  static void evaluate(const PairInput& in, PairSpring& spring, PairOutcome& out);
};

}  // namespace femdem
