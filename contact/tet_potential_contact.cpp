// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/tet_potential_contact.hpp"

#include "contact/tet_potential_integral.hpp"

namespace femdem::contact {

bool tet_potential_contact(const TetCorners& a, const TetCorners& b, double penalty,
                           TetPairContact& out) {
  return tet_potential_contact_by_clipped_regions(a, b, penalty, out);
}

}  // namespace femdem::contact
