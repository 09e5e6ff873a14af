// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/tet_potential_contact.hpp"

#include "contact/tet_potential_integral.hpp"
#include "contact/tetrahedron_set_clip.hpp"

namespace femdem::contact {

bool tet_potential_contact(const TetCorners& a, const TetCorners& b, double penalty,
                           TetPairContact& out) {
  return tet_potential_contact_with<TetrahedronSetClip>(a, b, penalty, out);
}

}  // namespace femdem::contact
