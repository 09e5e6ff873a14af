// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What every material has, whatever its model: its name, density and elastic constants (the
// Hencky elasticity that is the elastic part of every model), with the moduli derived from them.
#include <string>

namespace femdem {

struct MaterialBase {
  std::string name;
  double density = 0.0;
  double youngs_modulus = 0.0;
  double poisson_ratio = 0.0;

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const { return bulk_modulus() - 2.0 / 3.0 * shear_modulus(); }
  // P-wave (constrained) modulus K + 4G/3: sets the dilatational wave speed and the stable step.
  double p_wave_modulus() const { return bulk_modulus() + 4.0 / 3.0 * shear_modulus(); }
};

}  // namespace femdem
