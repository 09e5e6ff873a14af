// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Linear cohesion hardening or softening for the pressure-dependent models (Drucker-Prager,
// Mohr-Coulomb): c(kappa) = c0 + H kappa, never below the residual cohesion c_res when H < 0
// (softening stops there). kappa is the model's hardening variable (de Souza Neto, Peric & Owen
// 2008, ch. 8: Mohr-Coulomb kappa += 2 cos(phi) sum dgamma, Drucker-Prager kappa += xi dgamma),
// chosen so that for associated flow the plastic work rate is c kappa-dot.
//
// Every return of these models reduces to one scalar equation in a plastic multiplier x >= 0
// that is linear but for the cohesion:
//   r(x) = phi_trial - a x - m (c(kappa_n + k x) - c(kappa_n)) = 0,
// with a > 0 the elastic stiffness of the return, m = -dPhi/dc and k = dkappa/dx. c is
// continuous and piece-wise linear (two pieces when softening), so the root is found exactly:
// first on the current piece; if that crosses the knee onto the residual plateau, again there.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "materials/frictional_params.hpp"

namespace femdem {

struct CohesionHardening {
  double c0 = 0.0;        // initial cohesion [Pa]
  double H = 0.0;         // dc/dkappa [Pa]; < 0 softens
  double residual = 0.0;  // floor of c when softening [Pa], <= c0

  // kappa at which softening reaches the residual cohesion (infinity when not softening).
  double knee() const {
    return H < 0.0 ? (residual - c0) / H : std::numeric_limits<double>::infinity();
  }
  double value(double kappa) const { return std::max(residual, c0 + H * kappa); }
  double slope(double kappa) const { return kappa < knee() ? H : 0.0; }

  // Root of r(x) above. The caller guarantees a + m k slope > 0 (checked when the material is
  // read: softening no steeper than the elastic return).
  double solve(double phi_trial, double a, double m, double k, double kappa_n) const {
    const double h = slope(kappa_n);
    double x = phi_trial / (a + m * k * h);
    if (h != 0.0 && kappa_n + k * x > knee()) {
      // past the knee the cohesion is the residual one: r = phi - a x - m (c_res - c_n)
      x = (phi_trial - m * (residual - value(kappa_n))) / a;
    }
    return x;
  }
};

// Empty if the cohesion-law constants of m are usable, else a message naming the key.
// `steepest_softening` (< 0) is the most negative H for which every return of the model still
// has a unique multiplier (a + m k H > 0 for each of its returns, see CohesionHardening); a
// steeper softening is a snap-back at the material point.
inline std::string cohesion_param_error(const FrictionalParams& m, double steepest_softening) {
  if (!(m.cohesion >= 0.0) || !std::isfinite(m.cohesion)) return "cohesion must be >= 0 and finite";
  if (!std::isfinite(m.cohesion_hardening_modulus))
    return "cohesion_hardening_modulus must be finite";
  if (!(m.residual_cohesion >= 0.0) || !(m.residual_cohesion <= m.cohesion))
    return "residual_cohesion must lie in [0, cohesion]";
  if (!(m.cohesion_hardening_modulus > steepest_softening))
    return "cohesion_hardening_modulus must be above " + std::to_string(steepest_softening) +
           " Pa: steeper softening has no unique return (snap-back at the material point)";
  return {};
}

}  // namespace femdem
