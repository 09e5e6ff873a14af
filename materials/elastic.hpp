// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The scene model `elastic`: Hencky elasticity alone (its kernel is ElasticModel,
// materials/finite_strain_update.hpp). No constants beyond the common ones.
#include <string>
#include <vector>

#include "materials/finite_strain_update.hpp"
#include "materials/material_base.hpp"
#include "materials/material_keys.hpp"

namespace femdem {

struct ElasticParams {};

struct ElasticMaterial {
  static constexpr const char* name = "elastic";
  using Params = ElasticParams;
  using Kernel = ElasticModel;
  static std::vector<std::string> keys() { return {}; }
  static std::string check(const MaterialBase&, const Params&) { return {}; }
  static Kernel compile(const MaterialBase& e, const Params&) {
    return ElasticModel{e.lame_lambda(), e.shear_modulus()};
  }
  static Params read(const MaterialBase&, MaterialKeys&) { return {}; }
  static std::string describe(const MaterialBase&, const Params&) { return {}; }
};

}  // namespace femdem
