// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A material of a scene: the common constants (MaterialBase) and its model with that model's
// own constants (one of the registry's Params types, materials/material_registry.hpp).
#include <string>

#include "materials/material_registry.hpp"

namespace femdem {

struct MaterialParams : MaterialBase {
  MaterialModelParams model;  // default: elastic

  template <class Params>
  bool is() const {
    return std::holds_alternative<Params>(model);
  }
  template <class Params>
  const Params& params() const {
    return std::get<Params>(model);
  }
  template <class Params>
  Params& params() {
    return std::get<Params>(model);
  }
};

// The scene name of the material's model (`model = "..."`).
inline std::string material_model_name(const MaterialParams& m) {
  return material_model_names()[m.model.index()];
}

// The material's "" if usable, else the model's message.
inline std::string material_param_error(const MaterialParams& m) {
  return with_material_model(m.model.index(), [&](auto model) -> std::string {
    using M = decltype(model);
    return M::check(m, std::get<typename M::Params>(m.model));
  });
}

// The material's compiled return mapping.
inline MaterialKernel compile_material(const MaterialParams& m) {
  return with_material_model(m.model.index(), [&](auto model) -> MaterialKernel {
    using M = decltype(model);
    return M::compile(m, std::get<typename M::Params>(m.model));
  });
}

}  // namespace femdem
