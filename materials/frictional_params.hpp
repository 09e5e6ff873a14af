// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The constants that Mohr-Coulomb and Drucker-Prager share, as the scene gives them: cohesion,
// friction and dilatancy angles (degrees), and the linear cohesion hardening or softening; with
// their scene reader and the lines `femdem check` prints. One place, since both models read and
// print them alike.
#include <string>
#include <vector>

#include "materials/material_keys.hpp"

namespace femdem {

struct FrictionalParams {
  double cohesion = 0.0;                    // Pa
  double friction_angle = 0.0;              // degrees
  double dilatancy_angle = 0.0;             // = friction_angle: associated flow
  double cohesion_hardening_modulus = 0.0;  // dc/dkappa; < 0 softens
  double residual_cohesion = 0.0;           // floor of c when softening
};

inline std::vector<std::string> frictional_keys() {
  return {"cohesion", "friction_angle", "dilatancy_angle", "cohesion_hardening_modulus",
          "residual_cohesion"};
}

// Cohesion and friction angle, dilatancy (default associated), linear cohesion
// hardening/softening; each checked on its own (the model checks the combination).
inline void read_frictional(MaterialKeys& k, FrictionalParams& m) {
  m.cohesion = k.number("cohesion");
  if (!(m.cohesion >= 0.0)) k.fail("cohesion", "must be >= 0, got " + format_shortest(m.cohesion));
  m.friction_angle = k.number("friction_angle");
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 90.0))
    k.fail("friction_angle",
           "must lie in [0, 90) degrees, got " + format_shortest(m.friction_angle));
  m.dilatancy_angle = k.number("dilatancy_angle", m.friction_angle);
  if (!(m.dilatancy_angle >= 0.0 && m.dilatancy_angle <= m.friction_angle))
    k.fail("dilatancy_angle",
           "must lie in [0, friction_angle = " + format_shortest(m.friction_angle) +
               "] degrees, got " + format_shortest(m.dilatancy_angle));
  if (m.friction_angle == 0.0 && m.cohesion == 0.0)
    k.fail("cohesion", "and friction_angle are both 0: the material has no strength");
  m.cohesion_hardening_modulus = k.number("cohesion_hardening_modulus", 0.0);
  m.residual_cohesion = k.number("residual_cohesion", 0.0);
  if (k.has("residual_cohesion") && !(m.cohesion_hardening_modulus < 0.0))
    k.fail("residual_cohesion",
           "is the floor of a softening cohesion: it needs cohesion_hardening_modulus < 0");
  if (!(m.residual_cohesion >= 0.0 && m.residual_cohesion <= m.cohesion))
    k.fail("residual_cohesion",
           "must lie in [0, cohesion], got " + format_shortest(m.residual_cohesion));
  k.record("cohesion", m.cohesion);
  k.record("friction_angle", m.friction_angle);
  k.record("dilatancy_angle", m.dilatancy_angle);
  k.record("cohesion_hardening_modulus", m.cohesion_hardening_modulus);
  if (m.cohesion_hardening_modulus < 0.0) k.record("residual_cohesion", m.residual_cohesion);
}

inline std::string describe_frictional(const FrictionalParams& m) {
  return "    cohesion " + format_g(m.cohesion) + " Pa, friction angle " +
         format_g(m.friction_angle) + " deg, dilatancy angle " + format_g(m.dilatancy_angle) +
         " deg\n";
}

inline std::string describe_cohesion_hardening(const FrictionalParams& m) {
  if (m.cohesion_hardening_modulus == 0.0) return {};
  return "    cohesion hardening " + format_g(m.cohesion_hardening_modulus) +
         " Pa, residual cohesion " + format_g(m.residual_cohesion) + " Pa\n";
}

}  // namespace femdem
