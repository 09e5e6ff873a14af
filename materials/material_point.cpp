// SPDX-License-Identifier: GPL-3.0-or-later
#include "materials/material_point.hpp"

#include <string>

#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"
#include "materials/piecewise_drucker_prager.hpp"
#include "materials/von_mises.hpp"

namespace femdem {

namespace {

// Calls f(model) with the return-mapping model of `m`.
template <class Fn>
std::vector<MaterialPointStep> with_model(const MaterialParams& m, Fn&& f) {
  if (!(m.youngs_modulus > 0.0) || !(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    throw MaterialPointError("material '" + m.name +
                             "': youngs_modulus must be positive and poisson_ratio in (-1, 0.5)");
  switch (m.model) {
    case MaterialModel::Elastic:
      return f(ElasticModel{m.lame_lambda(), m.shear_modulus()});
    case MaterialModel::VonMises: {
      const std::string err = von_mises_param_error(m);
      if (!err.empty()) throw MaterialPointError("material '" + m.name + "': " + err);
      return f(make_von_mises(m));
    }
    case MaterialModel::DruckerPrager: {
      const std::string err = drucker_prager_param_error(m);
      if (!err.empty()) throw MaterialPointError("material '" + m.name + "': " + err);
      return f(make_drucker_prager(m));
    }
    case MaterialModel::MohrCoulomb: {
      const std::string err = mohr_coulomb_param_error(m);
      if (!err.empty()) throw MaterialPointError("material '" + m.name + "': " + err);
      return f(make_mohr_coulomb(m));
    }
    case MaterialModel::PiecewiseDruckerPrager: {
      const std::string err = piecewise_drucker_prager_param_error(m);
      if (!err.empty()) throw MaterialPointError("material '" + m.name + "': " + err);
      return f(make_piecewise_drucker_prager(m));
    }
  }
  throw MaterialPointError("material '" + m.name + "': unknown material model");
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
