// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Material constants as a scene gives them, plus the elastic constants derived from them.
#include <string>
#include <utility>
#include <vector>

namespace femdem {

enum class MaterialModel { Elastic, VonMises };

// von Mises hardening law (materials/von_mises.hpp). A scene picks it by its keys:
// hardening_modulus (or none) -> Linear, hardening_curve -> Tabulated, swift_K -> Swift.
enum class HardeningLaw { Linear, Tabulated, Swift };

struct MaterialParams {
  std::string name;
  MaterialModel model = MaterialModel::Elastic;
  double density = 0.0;
  double youngs_modulus = 0.0;
  double poisson_ratio = 0.0;

  // von Mises (model = VonMises). Stresses in Pa.
  HardeningLaw hardening = HardeningLaw::Linear;
  double yield_stress = 0.0;       // initial yield stress sigma_y0 (linear law)
  double hardening_modulus = 0.0;  // H: sigma_y = sigma_y0 + H eps_p (linear law)
  // [eq_plastic_strain, stress] points, eps_p strictly increasing from 0; piece-wise linear,
  // constant beyond the last point (tabulated law)
  std::vector<std::pair<double, double>> hardening_curve;
  double swift_K = 0.0;     // Swift sigma_y = K (eps0 + eps_p)^n
  double swift_eps0 = 0.0;  // > 0
  double swift_n = 0.0;     // >= 0
  // Johnson-Cook rate factor 1 + C ln(max(1, epsdot_p / epsdot0)); C = 0 switches it off
  double jc_C = 0.0;
  double jc_epsdot0 = 1.0;  // 1/s

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const { return bulk_modulus() - 2.0 / 3.0 * shear_modulus(); }
  // P-wave (constrained) modulus K + 4G/3: sets the dilatational wave speed and the stable step.
  double p_wave_modulus() const { return bulk_modulus() + 4.0 / 3.0 * shear_modulus(); }
};

}  // namespace femdem
