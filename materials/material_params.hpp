// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Material constants as a scene gives them, plus the elastic constants derived from them.
#include <string>
#include <utility>
#include <vector>

namespace femdem {

enum class MaterialModel { Elastic, VonMises, DruckerPrager, MohrCoulomb, PiecewiseDruckerPrager };

// Which Drucker-Prager cone matches the Mohr-Coulomb (cohesion, friction_angle) of a scene
// (materials/drucker_prager.hpp).
enum class DruckerPragerCone { Outer, Inner, PlaneStrain, Inscribed };

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

  // Mohr-Coulomb and Drucker-Prager. Angles in degrees, cohesion in Pa.
  double cohesion = 0.0;
  double friction_angle = 0.0;
  double dilatancy_angle = 0.0;             // = friction_angle: associated flow
  double cohesion_hardening_modulus = 0.0;  // dc/dkappa; < 0 softens
  double residual_cohesion = 0.0;           // floor of c when softening
  DruckerPragerCone cone = DruckerPragerCone::Outer;

  // Piece-wise Drucker-Prager: pieces [A, B] (B in Pa), tension apex first, and the constant
  // dilatancy A_bar of its flow potential.
  std::vector<std::pair<double, double>> pieces;
  double pieces_dilatancy = 0.0;

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const { return bulk_modulus() - 2.0 / 3.0 * shear_modulus(); }
  // P-wave (constrained) modulus K + 4G/3: sets the dilatational wave speed and the stable step.
  double p_wave_modulus() const { return bulk_modulus() + 4.0 / 3.0 * shear_modulus(); }
};

// The scene file's name of a model (`model = "..."`).
inline const char* material_model_name(MaterialModel m) {
  switch (m) {
    case MaterialModel::Elastic:
      return "elastic";
    case MaterialModel::VonMises:
      return "von_mises";
    case MaterialModel::DruckerPrager:
      return "drucker_prager";
    case MaterialModel::MohrCoulomb:
      return "mohr_coulomb";
    case MaterialModel::PiecewiseDruckerPrager:
      return "piecewise_drucker_prager";
  }
  return "?";
}

inline const char* drucker_prager_cone_name(DruckerPragerCone c) {
  switch (c) {
    case DruckerPragerCone::Outer:
      return "outer";
    case DruckerPragerCone::Inner:
      return "inner";
    case DruckerPragerCone::PlaneStrain:
      return "plane_strain";
    case DruckerPragerCone::Inscribed:
      return "inscribed";
  }
  return "?";
}

}  // namespace femdem
