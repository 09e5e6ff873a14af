// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// An elastic material for engine tests, in one line.
#include <string>

#include <utility>

#include "materials/material_params.hpp"

namespace femdem::test {

inline MaterialParams elastic_material(std::string name, double density, double youngs_modulus,
                                       double poisson_ratio) {
  MaterialParams m;
  m.name = std::move(name);
  m.density = density;
  m.youngs_modulus = youngs_modulus;
  m.poisson_ratio = poisson_ratio;
  return m;
}

}  // namespace femdem::test
