// SPDX-License-Identifier: GPL-3.0-or-later
#include "materials/material_point.hpp"

#include <string>

namespace femdem {

namespace {

// Calls f(kernel) with the return mapping of `m`, after checking its constants.
template <class Fn>
std::vector<MaterialPointStep> with_model(const MaterialParams& m, Fn&& f) {
  if (!(m.youngs_modulus > 0.0) || !(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    throw MaterialPointError("material '" + m.name +
                             "': youngs_modulus must be positive and poisson_ratio in (-1, 0.5)");
  const std::string err = material_param_error(m);
  if (!err.empty()) throw MaterialPointError("material '" + m.name + "': " + err);
  return std::visit([&](const auto& kernel) { return f(kernel); }, compile_material(m));
}

}  // namespace

std::vector<MaterialPointStep> drive_deformation(const MaterialParams& material,
                                                 const std::vector<F3>& path, int substeps,
                                                 double dt) {
  return with_model(
      material, [&](const auto& model) { return drive_deformation(model, path, substeps, dt); });
}

std::vector<MaterialPointStep> drive_mixed(const MaterialParams& material,
                                           const std::vector<MixedTarget>& path,
                                           LateralControl lateral, double dt) {
  return with_model(material,
                    [&](const auto& model) { return drive_mixed(model, path, lateral, dt); });
}

}  // namespace femdem
