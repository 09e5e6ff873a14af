// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The variants of the SIMD element update, one per F-bar mode and gradient kind, each in its own
// source generated from element_update_variant.cpp.in (CMakeLists.txt) and dispatched to the
// machine's instruction set there. element_update.cpp chooses among them.
#include <cstddef>

#include "engine/element_update/element_update.hpp"

namespace femdem {

#define FEMDEM_ELEMENT_UPDATE_VARIANT(name)                                                   \
  void update_pairs_##name(const MaterialKernel& material, const ElementUpdateArrays& arrays, \
                           const ElementPair* pairs, std::size_t count, double dt);
FEMDEM_ELEMENT_UPDATE_VARIANT(off_straight)
FEMDEM_ELEMENT_UPDATE_VARIANT(off_curved)
FEMDEM_ELEMENT_UPDATE_VARIANT(volume_average_straight)
FEMDEM_ELEMENT_UPDATE_VARIANT(volume_average_curved)
FEMDEM_ELEMENT_UPDATE_VARIANT(centroid_straight)
FEMDEM_ELEMENT_UPDATE_VARIANT(centroid_curved)
FEMDEM_ELEMENT_UPDATE_VARIANT(nodal_straight)
FEMDEM_ELEMENT_UPDATE_VARIANT(nodal_curved)
FEMDEM_ELEMENT_UPDATE_VARIANT(subtet_straight)
FEMDEM_ELEMENT_UPDATE_VARIANT(subtet_curved)
#undef FEMDEM_ELEMENT_UPDATE_VARIANT

}  // namespace femdem
