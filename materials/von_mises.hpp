// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// von Mises (J2) plasticity with isotropic hardening: radial return in principal deviatoric
// log-strain space (thesis section 2.2.4.1 and App. D; de Souza Neto et al. 2008 Box 7.3/14.3).
//
// Trial state from the principal elastic log strains e_i (Hencky law):
//   p = K tr(e),  s_i = 2 G (e_i - tr(e)/3),  q = sqrt(3/2 s:s),  f = q - sigma_y(eps_p_n).
// Plastic if f > 0 (relative tolerance 1e-12). The return is along s (radial):
//   q_n+1 = q_trial - 3 G dgamma,  s_n+1 = (q_n+1 / q_trial) s_trial,  eps_p += dgamma,
// with dgamma solving q_trial - 3 G dgamma - sigma_y(eps_p_n + dgamma) R(dgamma / dt) = 0.
// For linear hardening dgamma = f / (3G + H). The thesis prints the denominator as "4 mu + H"
// (eqs 2.77 and 8.40) and drops the 3 mu from the s-update factor: both are misprints; its own
// derivation (8.39) gives 3G + H, which is what this file implements.
//
// Hardening laws sigma_y(eps_p): linear sigma_y0 + H eps_p (clipped at 0 if H < 0); tabulated
// piece-wise linear [[eps_p, stress], ...] starting at eps_p = 0, constant beyond the last point;
// Swift K (eps0 + eps_p)^n. Any curve other than linear with H >= 0 (and any rate factor) is
// solved by a safeguarded Newton iteration on the bracket [0, q_trial / 3G]: the residual is
// positive at 0 (the step yielded) and -sigma_y R <= 0 at the upper end, so a root exists for
// every non-negative curve, softening included; Newton steps that leave the bracket or a
// non-decreasing residual fall back to bisection, so it always converges.
//
// Johnson-Cook rate factor (optional, C > 0): R = 1 + C ln(max(1, epsdot_p / epsdot_0)) with
// epsdot_p = dgamma / dt, treated IMPLICITLY: the rate of the current step (the unknown dgamma)
// enters the consistency equation, so the returned stress is on the rate-dependent surface of
// this step (backward Euler, like the rest of the return). A lagged (explicit) rate from the
// previous step would need no iteration but can oscillate step to step in an impact. With dt <= 0
// (quasi-static driving) R = 1. The elastic check uses R = 1 (zero rate).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "materials/finite_strain_update.hpp"
#include "materials/material_base.hpp"
#include "materials/material_keys.hpp"

namespace femdem {

// The hardening law of a scene's von Mises material, picked by its keys: hardening_modulus (or
// none) -> Linear, hardening_curve -> Tabulated, swift_k -> Swift.
enum class HardeningLaw { Linear, Tabulated, Swift };

// A von Mises material's constants as the scene gives them (stresses in Pa).
struct VonMisesParams {
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
};

struct VonMises {
  double lambda = 0.0;  // Lame lambda
  double G = 0.0;       // shear modulus
  HardeningLaw law = HardeningLaw::Linear;
  double yield_stress = 0.0;                     // initial yield stress (linear law)
  double hardening_modulus = 0.0;                // H (linear law)
  std::vector<std::pair<double, double>> curve;  // [eps_p, stress] (tabulated law)
  double swift_K = 0.0, swift_eps0 = 0.0, swift_n = 0.0;
  double jc_C = 0.0;        // Johnson-Cook rate coefficient (0: rate independent)
  double jc_epsdot0 = 1.0;  // reference plastic strain rate [1/s]

  // Flow stress sigma_y(eps_p) and its slope d sigma_y / d eps_p.
  double flow_stress(double eps_p, double* slope) const {
    switch (law) {
      case HardeningLaw::Linear: {
        const double sy = yield_stress + hardening_modulus * eps_p;
        if (sy <= 0.0) {
          *slope = 0.0;
          return 0.0;
        }
        *slope = hardening_modulus;
        return sy;
      }
      case HardeningLaw::Tabulated: {
        const std::size_t n = curve.size();
        if (eps_p >= curve[n - 1].first || n == 1) {
          *slope = 0.0;
          return curve[n - 1].second;
        }
        std::size_t lo = 0, hi = n - 1;  // curve[lo].first <= eps_p < curve[hi].first
        while (hi - lo > 1) {
          const std::size_t mid = (lo + hi) / 2;
          if (curve[mid].first <= eps_p)
            lo = mid;
          else
            hi = mid;
        }
        const double h =
            (curve[hi].second - curve[lo].second) / (curve[hi].first - curve[lo].first);
        *slope = h;
        return curve[lo].second + h * (eps_p - curve[lo].first);
      }
      case HardeningLaw::Swift: {
        const double x = swift_eps0 + eps_p;
        const double sy = swift_K * std::pow(x, swift_n);
        *slope = swift_n * sy / x;
        return sy;
      }
    }
    *slope = 0.0;
    return 0.0;
  }

  // Johnson-Cook factor R(dgamma) and dR/d dgamma.
  double rate_factor(double dgamma, double dt, double* dR) const {
    *dR = 0.0;
    if (jc_C <= 0.0 || dt <= 0.0) return 1.0;
    const double ratio = dgamma / (dt * jc_epsdot0);
    if (ratio <= 1.0) return 1.0;
    *dR = jc_C / dgamma;
    return 1.0 + jc_C * std::log(ratio);
  }

  // Solve q_trial - 3 G x - sigma_y(eps_p_n + x) R(x) = 0 for x in (0, q_trial / 3G].
  double solve_dgamma(double q_trial, double eps_p_n, double f_trial, double dt) const {
    const double three_G = 3.0 * G;
    double lo = 0.0, hi = q_trial / three_G;
    double h0;
    flow_stress(eps_p_n, &h0);
    double x = f_trial / (three_G + std::fmax(h0, 0.0));
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double tol = 1e-14 * q_trial;
    for (int it = 0; it < 200; ++it) {
      double H, dR;
      const double sy = flow_stress(eps_p_n + x, &H);
      const double R = rate_factor(x, dt, &dR);
      const double phi = q_trial - three_G * x - sy * R;
      if (std::fabs(phi) <= tol) break;
      if (phi > 0.0)
        lo = x;
      else
        hi = x;
      const double dphi = -three_G - H * R - sy * dR;
      double xn = (dphi < 0.0) ? x - phi / dphi : lo - 1.0;
      if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
      if (hi - lo <= 4e-16 * hi) {
        x = xn;
        break;
      }
      x = xn;
    }
    return x;
  }

  PrincipalReturn return_map(const double e_trial[3], double eps_p_n, double dt) const {
    PrincipalReturn r;
    const double ev = e_trial[0] + e_trial[1] + e_trial[2];
    const double em = ev / 3.0;
    const double ed[3] = {e_trial[0] - em, e_trial[1] - em, e_trial[2] - em};
    const double p = (lambda + 2.0 / 3.0 * G) * ev;
    // q = sqrt(3/2 s:s) with s = 2 G ed
    const double q_trial =
        2.0 * G * std::sqrt(1.5 * (ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2]));
    double H;
    const double sy = flow_stress(eps_p_n, &H);
    const double f = q_trial - sy;
    r.kappa = eps_p_n;
    if (!(f > 1e-12 * sy) || q_trial <= 0.0) {
      for (int i = 0; i < 3; ++i) {
        r.tau[i] = p + 2.0 * G * ed[i];
        r.e_el[i] = e_trial[i];
      }
      r.yielded = false;
      return r;
    }
    double dgamma;
    if (law == HardeningLaw::Linear && hardening_modulus >= 0.0 && !(jc_C > 0.0 && dt > 0.0))
      dgamma = f / (3.0 * G + hardening_modulus);
    else
      dgamma = solve_dgamma(q_trial, eps_p_n, f, dt);
    const double factor = 1.0 - 3.0 * G * dgamma / q_trial;
    for (int i = 0; i < 3; ++i) {
      r.e_el[i] = em + factor * ed[i];
      r.tau[i] = p + 2.0 * G * factor * ed[i];
    }
    r.kappa = eps_p_n + dgamma;
    r.yielded = true;
    return r;
  }
};

// Empty if the von Mises constants in m are usable, else a message naming the offending key.
inline std::string von_mises_param_error(const VonMisesParams& m) {
  auto finite = [](double x) { return std::isfinite(x); };
  switch (m.hardening) {
    case HardeningLaw::Linear:
      if (!(m.yield_stress > 0.0) || !finite(m.yield_stress))
        return "yield_stress must be positive and finite";
      if (!finite(m.hardening_modulus)) return "hardening_modulus must be finite";
      break;
    case HardeningLaw::Tabulated: {
      const auto& c = m.hardening_curve;
      if (c.empty())
        return "hardening_curve must have at least one [eq_plastic_strain, stress] point";
      if (c[0].first != 0.0) return "hardening_curve must start at eq_plastic_strain = 0";
      if (!(c[0].second > 0.0)) return "hardening_curve: the initial yield stress must be positive";
      for (std::size_t i = 0; i < c.size(); ++i) {
        if (!finite(c[i].first) || !finite(c[i].second))
          return "hardening_curve: point " + std::to_string(i + 1) + " is not finite";
        if (c[i].second < 0.0)
          return "hardening_curve: point " + std::to_string(i + 1) + " has a negative stress";
        if (i > 0 && !(c[i].first > c[i - 1].first))
          return "hardening_curve: eq_plastic_strain must increase strictly (point " +
                 std::to_string(i + 1) + ")";
      }
      break;
    }
    case HardeningLaw::Swift:
      if (!(m.swift_K > 0.0) || !finite(m.swift_K)) return "swift_K must be positive and finite";
      if (!(m.swift_eps0 > 0.0) || !finite(m.swift_eps0))
        return "swift_eps0 must be positive and finite";
      if (!(m.swift_n >= 0.0) || !finite(m.swift_n)) return "swift_n must be >= 0 and finite";
      break;
  }
  if (!(m.jc_C >= 0.0) || !finite(m.jc_C)) return "jc_C must be >= 0 and finite";
  if (!(m.jc_epsdot0 > 0.0) || !finite(m.jc_epsdot0)) return "jc_epsdot0 must be positive";
  return {};
}

// The return-mapping model of a von Mises material (call von_mises_param_error first).
inline VonMises make_von_mises(const MaterialBase& e, const VonMisesParams& m) {
  VonMises v;
  v.lambda = e.lame_lambda();
  v.G = e.shear_modulus();
  v.law = m.hardening;
  v.yield_stress = m.yield_stress;
  v.hardening_modulus = m.hardening_modulus;
  v.curve = m.hardening_curve;
  v.swift_K = m.swift_K;
  v.swift_eps0 = m.swift_eps0;
  v.swift_n = m.swift_n;
  v.jc_C = m.jc_C;
  v.jc_epsdot0 = m.jc_epsdot0;
  return v;
}

// The scene model `von_mises` (docs/SCENES.md, [[materials]]).
struct VonMisesMaterial {
  static constexpr const char* name = "von_mises";
  using Params = VonMisesParams;
  using Kernel = VonMises;
  static std::vector<std::string> keys() {
    return {"yield_stress", "hardening_modulus", "hardening_curve",  "swift_k",
            "swift_eps0",   "swift_n",           "rate_coefficient", "reference_strain_rate"};
  }
  static std::string check(const MaterialBase&, const Params& p) {
    return von_mises_param_error(p);
  }
  static Kernel compile(const MaterialBase& e, const Params& p) { return make_von_mises(e, p); }

  // Linear (hardening_modulus), a tabulated curve (hardening_curve), or Swift's power law
  // (swift_k, swift_eps0, swift_n); an optional Johnson-Cook rate factor.
  static Params read(const MaterialBase&, MaterialKeys& k) {
    Params m;
    const bool has_curve = k.has("hardening_curve");
    const bool has_swift = k.has("swift_k") || k.has("swift_eps0") || k.has("swift_n");
    const bool has_linear = k.has("hardening_modulus");
    if (int(has_curve) + int(has_swift) + int(has_linear) > 1)
      k.fail_entry(
          "give one hardening law: 'hardening_modulus' (linear), 'hardening_curve' (tabulated) "
          "or 'swift_k', 'swift_eps0', 'swift_n' (power law)");
    if (has_curve) {
      m.hardening = HardeningLaw::Tabulated;
      m.hardening_curve =
          k.pairs("hardening_curve",
                  "must be a non-empty array of [equivalent_plastic_strain, stress] pairs",
                  "each point must be [equivalent_plastic_strain, stress] (two numbers)");
      k.record("hardening_curve", m.hardening_curve);
      if (k.has("yield_stress"))
        k.fail("yield_stress",
               "is given by the first point of 'hardening_curve'; remove one of them");
      m.yield_stress = m.hardening_curve.front().second;
    } else if (has_swift) {
      m.hardening = HardeningLaw::Swift;
      m.swift_K = k.positive("swift_k");
      m.swift_eps0 = k.positive("swift_eps0");
      m.swift_n = k.positive("swift_n");
      m.yield_stress = m.swift_K * std::pow(m.swift_eps0, m.swift_n);
      if (k.has("yield_stress"))
        k.fail("yield_stress", "is swift_k * swift_eps0^swift_n for the Swift law; remove it");
      k.record("swift_k", m.swift_K);
      k.record("swift_eps0", m.swift_eps0);
      k.record("swift_n", m.swift_n);
    } else {
      m.hardening = HardeningLaw::Linear;
      m.yield_stress = k.positive("yield_stress");
      m.hardening_modulus = k.number("hardening_modulus", 0.0);
      k.record("yield_stress", m.yield_stress);
      k.record("hardening_modulus", m.hardening_modulus);
    }
    if (k.has("rate_coefficient") || k.has("reference_strain_rate")) {
      m.jc_C = k.number("rate_coefficient", 0.0);
      if (m.jc_C < 0.0) k.fail("rate_coefficient", "must be >= 0, got " + format_shortest(m.jc_C));
      m.jc_epsdot0 = k.positive("reference_strain_rate", 1.0);
      k.record("rate_coefficient", m.jc_C);
      k.record("reference_strain_rate", m.jc_epsdot0);
    }
    const std::string err = von_mises_param_error(m);
    if (!err.empty()) k.fail_entry(err);
    return m;
  }

  // The lines `femdem check` prints for the model (each indented by four spaces).
  static std::string describe(const MaterialBase&, const Params& m) {
    std::string s;
    switch (m.hardening) {
      case HardeningLaw::Linear:
        s = "    yield stress " + format_g(m.yield_stress) + " Pa, linear hardening " +
            format_g(m.hardening_modulus) + " Pa\n";
        break;
      case HardeningLaw::Tabulated:
        s = "    tabulated hardening, " + std::to_string(m.hardening_curve.size()) +
            " points, yield stress " + format_g(m.yield_stress) + " Pa\n";
        break;
      case HardeningLaw::Swift:
        s = "    Swift hardening " + format_g(m.swift_K) + " (" + format_g(m.swift_eps0) +
            " + eps_p)^" + format_g(m.swift_n) + " Pa, yield stress " + format_g(m.yield_stress) +
            " Pa\n";
        break;
    }
    if (m.jc_C > 0.0)
      s += "    Johnson-Cook rate factor C = " + format_g(m.jc_C) + ", reference rate " +
           format_g(m.jc_epsdot0) + " 1/s\n";
    return s;
  }
};

}  // namespace femdem
