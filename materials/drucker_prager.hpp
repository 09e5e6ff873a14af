// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Drucker-Prager plasticity, associated or not, with linear cohesion hardening/softening, in
// principal elastic log strains (the Hencky law makes the finite-strain return the small-strain
// one; materials/finite_strain_update.hpp).
//
// Yield and flow (tension positive, p = tr(tau)/3, s = dev(tau), q = sqrt(J2) = sqrt(s:s/2)):
//   Phi = q + eta p - xi c(kappa),   g = q + eta_bar p.
// This is the textbook form (de Souza Neto, Peric & Owen 2008, sec. 8.3.3 and Box 8.8). The
// thesis (sec. 2.2.4.3, App. E) mixes A I1 and A p and its smooth-return multiplier does not
// match its own apex test (reference notes seed002-part1 sec. 2.6); the thesis' A_I1 is eta/3
// and its B is xi c. The return:
//   smooth cone: dgamma = Phi_trial / (G + K eta eta_bar + xi^2 H)  (with the knee of c handled
//     by CohesionHardening), s = (1 - G dgamma / q_trial) s_trial, p = p_trial - K eta_bar dgamma,
//     kappa += xi dgamma;
//   apex, when that would overshoot the axis (q_trial - G dgamma < 0): s = 0 and
//     p_trial - K dev = (xi / eta) c(kappa_n + (xi / eta_bar) dev), kappa += (xi / eta_bar) dev.
//     With eta_bar = 0 (no dilatancy) the flow cannot change p, so no state on the flow line is
//     admissible; the stress goes to the apex p = xi c / eta, the only admissible point nearest
//     the trial (the thesis' robust apex test 2.113 does the same), and kappa is unchanged.
// Cone matchings to Mohr-Coulomb (c, phi), used for eta(phi), xi(phi) and eta_bar = eta(psi):
//   outer (compressive meridian): eta = 6 sin / (sqrt3 (3 - sin)), xi = 6 cos / (sqrt3 (3 - sin))
//   inner (tensile meridian):     eta = 6 sin / (sqrt3 (3 + sin)), xi = 6 cos / (sqrt3 (3 + sin))
//   plane strain:                 eta = 3 tan / sqrt(9 + 12 tan^2), xi = 3 / sqrt(9 + 12 tan^2)
//   inscribed (inside the whole hexagon): eta = 3 sin / sqrt(9 + 3 sin^2), xi = 3 cos / sqrt(...)
// The outer cone reproduces Mohr-Coulomb in uniaxial-strain (and triaxial) compression, the
// inner one in tension: thesis test 3.2.5 with c = 15 MPa, phi = 30 gives A_I1 = 0.2309 and
// B = 18.00 MPa (outer), 0.1650 and 12.857 MPa (inner); the printed "B = 0.4 / 0.286 MPa" are
// misprints (notes seed002-part1 sec. 2.6).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "materials/cohesion_hardening.hpp"
#include "materials/finite_strain_update.hpp"
#include "materials/hencky.hpp"
#include "materials/material_base.hpp"

namespace femdem {

// Which Drucker-Prager cone matches the Mohr-Coulomb (cohesion, friction_angle) of a scene.
enum class DruckerPragerCone { Outer, Inner, PlaneStrain, Inscribed };

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

// A Drucker-Prager material's constants as the scene gives them.
struct DruckerPragerParams : FrictionalParams {
  DruckerPragerCone cone = DruckerPragerCone::Outer;
};

struct DruckerPrager {
  double K = 0.0, G = 0.0;
  double eta = 0.0;      // pressure sensitivity of the yield surface
  double eta_bar = 0.0;  // of the flow potential (= eta: associated)
  double xi = 0.0;       // cohesion factor
  CohesionHardening cohesion;

  PrincipalReturn return_map(const double e_trial[3], double kappa_n, double /*dt*/) const {
    PrincipalReturn r;
    const MeridianTrial trial = meridian_trial(e_trial, K, G);
    const double p_trial = trial.p, q_trial = trial.q;
    const double c_n = cohesion.value(kappa_n);
    const double phi = q_trial + eta * p_trial - xi * c_n;
    r.kappa = kappa_n;
    r.yielded = phi > 1e-12 * (q_trial + std::fabs(eta * p_trial) + xi * c_n);
    double p = p_trial, factor = 1.0;
    if (r.yielded) {
      const double dgamma = cohesion.solve(phi, G + K * eta * eta_bar, xi, xi, kappa_n);
      if (eta <= 0.0 || q_trial - G * dgamma >= 0.0) {
        factor = q_trial > 0.0 ? std::fmax(0.0, 1.0 - G * dgamma / q_trial) : 0.0;
        p = p_trial - K * eta_bar * dgamma;
        r.kappa = kappa_n + xi * dgamma;
      } else {
        factor = 0.0;
        const double ratio = xi / eta;
        if (eta_bar > 0.0) {
          const double k = xi / eta_bar;
          const double dev = cohesion.solve(p_trial - ratio * c_n, K, ratio, k, kappa_n);
          p = p_trial - K * dev;
          r.kappa = kappa_n + k * dev;
        } else {
          p = ratio * c_n;
        }
      }
    }
    meridian_result(trial, p, factor, K, G, r.tau, r.e_el);
    return r;
  }
};

// eta, xi of a cone matched to Mohr-Coulomb with friction (or dilatancy) angle `angle_rad`.
inline void drucker_prager_cone(DruckerPragerCone cone, double angle_rad, double* eta, double* xi) {
  const double s = std::sin(angle_rad), c = std::cos(angle_rad), sqrt3 = std::sqrt(3.0);
  switch (cone) {
    case DruckerPragerCone::Outer:
      *eta = 6.0 * s / (sqrt3 * (3.0 - s));
      *xi = 6.0 * c / (sqrt3 * (3.0 - s));
      return;
    case DruckerPragerCone::Inner:
      *eta = 6.0 * s / (sqrt3 * (3.0 + s));
      *xi = 6.0 * c / (sqrt3 * (3.0 + s));
      return;
    case DruckerPragerCone::PlaneStrain: {
      const double t = std::tan(angle_rad), d = std::sqrt(9.0 + 12.0 * t * t);
      *eta = 3.0 * t / d;
      *xi = 3.0 / d;
      return;
    }
    case DruckerPragerCone::Inscribed: {
      const double d = std::sqrt(9.0 + 3.0 * s * s);
      *eta = 3.0 * s / d;
      *xi = 3.0 * c / d;
      return;
    }
  }
}

inline DruckerPrager make_drucker_prager(const MaterialBase& e, const DruckerPragerParams& m) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  DruckerPrager d;
  d.K = e.bulk_modulus();
  d.G = e.shear_modulus();
  drucker_prager_cone(m.cone, m.friction_angle * deg, &d.eta, &d.xi);
  double xi_psi;
  drucker_prager_cone(m.cone, m.dilatancy_angle * deg, &d.eta_bar, &xi_psi);
  d.cohesion = {m.cohesion, m.cohesion_hardening_modulus, m.residual_cohesion};
  return d;
}

inline std::string drucker_prager_param_error(const MaterialBase& e, const DruckerPragerParams& m) {
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 90.0))
    return "friction_angle must lie in [0, 90) degrees";
  if (!(m.dilatancy_angle >= 0.0 && m.dilatancy_angle <= m.friction_angle))
    return "dilatancy_angle must lie in [0, friction_angle]";
  const DruckerPrager d = make_drucker_prager(e, m);
  // smooth return: G + K eta eta_bar + xi^2 H > 0; apex: K + xi^2 / (eta eta_bar) H > 0
  double steepest = -(d.G + d.K * d.eta * d.eta_bar) / (d.xi * d.xi);
  if (d.eta * d.eta_bar > 0.0)
    steepest = std::fmax(steepest, -d.K * d.eta * d.eta_bar / (d.xi * d.xi));
  return cohesion_param_error(m, steepest);
}

// The scene model `drucker_prager` (docs/SCENES.md, [[materials]]).
struct DruckerPragerMaterial {
  static constexpr const char* name = "drucker_prager";
  using Params = DruckerPragerParams;
  using Kernel = DruckerPrager;
  static std::vector<std::string> keys() {
    std::vector<std::string> k = frictional_keys();
    k.push_back("cone");
    return k;
  }
  static std::string check(const MaterialBase& e, const Params& p) {
    return drucker_prager_param_error(e, p);
  }
  static Kernel compile(const MaterialBase& e, const Params& p) {
    return make_drucker_prager(e, p);
  }
  static Params read(const MaterialBase& e, MaterialKeys& k) {
    Params m;
    read_frictional(k, m);
    const std::vector<std::string> cones = {"outer", "inner", "plane_strain", "inscribed"};
    const std::string cone = k.text("cone").value_or("outer");
    if (std::find(cones.begin(), cones.end(), cone) == cones.end())
      k.fail("cone", "unknown cone '" + cone + "'" + k.did_you_mean(cone, cones) +
                         "; available: outer, inner, plane_strain, inscribed (matched to "
                         "Mohr-Coulomb in compression, tension, plane strain, or inside the whole "
                         "hexagon)");
    m.cone = cone == "inner"          ? DruckerPragerCone::Inner
             : cone == "plane_strain" ? DruckerPragerCone::PlaneStrain
             : cone == "inscribed"    ? DruckerPragerCone::Inscribed
                                      : DruckerPragerCone::Outer;
    k.record("cone", cone);
    const std::string err = drucker_prager_param_error(e, m);
    if (!err.empty()) k.fail("cohesion_hardening_modulus", err);
    return m;
  }
  static std::string describe(const MaterialBase&, const Params& m) {
    return describe_frictional(m) +
           "    cone matched to Mohr-Coulomb: " + drucker_prager_cone_name(m.cone) + "\n" +
           describe_cohesion_hardening(m);
  }
};

}  // namespace femdem
