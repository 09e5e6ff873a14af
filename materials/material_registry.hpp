// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The material models a scene can name, in one list. A model is one header in materials/ that
// defines its kernel (a return mapping with `return_map(e_trial[3], kappa, dt)`, see
// finite_strain_update.hpp) and a descriptor struct:
//   static constexpr const char* name;          // the scene's `model = "..."`
//   using Params = ...;                         // its constants as the scene gives them
//   using Kernel = ...;                         // the return mapping the element kernel calls
//   static std::vector<std::string> keys();     // its scene keys beyond the common ones
//   static Params read(const MaterialBase&, MaterialKeys&);  // read and check them
//   static std::string check(const MaterialBase&, const Params&);  // "" if usable
//   static Kernel compile(const MaterialBase&, const Params&);
//   static std::string describe(const MaterialBase&, const Params&);  // `femdem check` lines
// Adding a model is that header and one entry in MaterialModels below; the scene reader, the
// element loop (one dispatch per element), the material-point driver and `femdem check` follow
// from the list (docs/ARCHITECTURE.md, "How to add a material model").
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "materials/drucker_prager.hpp"
#include "materials/elastic.hpp"
#include "materials/mohr_coulomb.hpp"
#include "materials/piecewise_drucker_prager.hpp"
#include "materials/von_mises.hpp"

namespace femdem {

template <class... Models>
struct ModelList {
  using Params = std::variant<typename Models::Params...>;
  using Kernel = std::variant<typename Models::Kernel...>;
  using Tuple = std::tuple<Models...>;
  static constexpr std::size_t size = sizeof...(Models);
};

// The registry: every model a scene can name, in this order (the first is the default).
using MaterialModels = ModelList<ElasticMaterial, VonMisesMaterial, DruckerPragerMaterial,
                                 MohrCoulombMaterial, PiecewiseDruckerPragerMaterial>;

using MaterialModelParams = MaterialModels::Params;  // a material's model and its constants
using MaterialKernel = MaterialModels::Kernel;       // its compiled return mapping

// Calls f(Model{}) for the model at `index` of the list (the variant index of its Params).
template <class F>
decltype(auto) with_material_model(std::size_t index, F&& f) {
  return [&]<std::size_t... I>(std::index_sequence<I...>)->decltype(auto) {
    using R = decltype(f(std::tuple_element_t<0, MaterialModels::Tuple>{}));
    if constexpr (std::is_void_v<R>) {
      ((index == I ? (f(std::tuple_element_t<I, MaterialModels::Tuple>{}), true) : false) || ...);
    } else {
      R out{};
      ((index == I ? (out = f(std::tuple_element_t<I, MaterialModels::Tuple>{}), true) : false) ||
       ...);
      return out;
    }
  }
  (std::make_index_sequence<MaterialModels::size>{});
}

// The scene names of the models, in registry order.
inline std::vector<std::string> material_model_names() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < MaterialModels::size; ++i)
    with_material_model(i, [&](auto model) { names.emplace_back(decltype(model)::name); });
  return names;
}

// The registry index of a scene name, or -1.
inline int material_model_index(const std::string& name) {
  const std::vector<std::string> names = material_model_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

}  // namespace femdem
