// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A material for the material-model tests: the common constants and one model's own side by
// side in one struct, so that a test sets any of them directly (m.yield_stress, m.density) and
// passes it wherever a MaterialParams (or the model's Params, or the MaterialBase) is asked for.
#include "materials/material_params.hpp"

namespace femdem {

template <class Params>
struct TestMaterial : MaterialBase, Params {
  operator MaterialParams() const {
    MaterialParams p;
    static_cast<MaterialBase&>(p) = *this;
    p.model = static_cast<const Params&>(*this);
    return p;
  }
};

}  // namespace femdem
