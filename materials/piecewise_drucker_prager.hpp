// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The thesis' generalised piece-wise linear Drucker-Prager model (sec. 5.8, eqs 5.3-5.13), in
// principal elastic log strains.
//
// The yield surface in the meridian plane (p = tr(tau)/3 tension positive, q = sqrt(J2)) is the
// convex polyline of n pieces  q = B_k - A_k p,  k = 1..n, ordered from the tension apex to
// high pressure (A_1 > A_2 > ... > A_n >= 0): Phi(p, q) = q - min_k (B_k - A_k p). Piece 1
// extends to its apex p = B_1 / A_1, piece n to infinite pressure. Flow is deviatoric-plus-
// constant-dilatancy, g = q + A_bar p, the same for every piece (sec. 5.8.2):
//   dgamma = Phi_k / (G + K A_k A_bar),  q = q_trial - G dgamma,  p = p_trial - K A_bar dgamma.
// Every return moves along the same direction (-G, -K A_bar) in the (q, p) plane, so
//   g = K A_bar q - G p
// is constant along it (eq. 5.13). Its values g_k at the corners, and at the apex, increase
// monotonically along the polyline, so the piece a trial state returns to is the k with
// g_(k-1) <= g_trial <= g_k (a binary search; trials below the apex's g go to the apex). The
// corners need no treatment of their own: a trial whose g equals a corner's returns to that
// corner from both neighbouring pieces, so the return is continuous there. The thesis' printed
// algorithm returns with (A[i], B[i]) of the pressure search; the piece is the g-search's k
// (notes seed002-part2 sec. 3.7). With A_bar = 0, g = -G p: the return keeps p and the piece is
// the one over p_trial. With A_n = 0 the surface ends in a von Mises cylinder; one piece with
// A = 0 is von Mises with B = sigma_y / sqrt3. Perfectly plastic: the history variable counts
// the multiplier (kappa += dgamma).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "materials/drucker_prager.hpp"
#include "materials/finite_strain_update.hpp"
#include "materials/hencky.hpp"
#include "materials/material_base.hpp"
#include "materials/material_keys.hpp"

namespace femdem {

struct PiecewiseDruckerPrager {
  double K = 0.0, G = 0.0;
  double A_bar = 0.0;         // dilatancy, constant over the pieces
  std::vector<double> A, B;   // pieces, tension apex first
  std::vector<double> g_end;  // g at the high-pressure end of piece k (n - 1 corners)
  double p_apex = std::numeric_limits<double>::infinity();  // B_1 / A_1 (none if A_1 = 0)
  double g_apex = -std::numeric_limits<double>::infinity();

  // Builds the corner table; call after setting K, G, A_bar, A, B (validated).
  void prepare() {
    const std::size_t n = A.size();
    g_end.assign(n > 0 ? n - 1 : 0, 0.0);
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const double p = (B[k] - B[k + 1]) / (A[k] - A[k + 1]);
      g_end[k] = K * A_bar * (B[k] - A[k] * p) - G * p;
    }
    if (n > 0 && A[0] > 0.0) {
      p_apex = B[0] / A[0];
      g_apex = -G * p_apex;
    }
  }

  // q of the yield surface at pressure p (negative beyond the apex).
  double q_limit(double p) const {
    double q = B[0] - A[0] * p;
    for (std::size_t k = 1; k < A.size(); ++k) q = std::min(q, B[k] - A[k] * p);
    return q;
  }

  PrincipalReturn return_map(const double e_trial[3], double kappa_n, double /*dt*/) const {
    PrincipalReturn r;
    const MeridianTrial trial = meridian_trial(e_trial, K, G);
    const double p_trial = trial.p, q_trial = trial.q;
    const double phi = q_trial - q_limit(p_trial);
    r.kappa = kappa_n;
    r.yielded = phi > 1e-12 * (q_trial + std::fabs(A[0] * p_trial) + B[0]);
    double p = p_trial, factor = 1.0;
    if (r.yielded) {
      const double g = K * A_bar * q_trial - G * p_trial;
      if (g <= g_apex) {
        p = p_apex;
        factor = 0.0;
        r.kappa = kappa_n + q_trial / G;
      } else {
        const std::size_t k = static_cast<std::size_t>(
            std::upper_bound(g_end.begin(), g_end.end(), g) - g_end.begin());
        const double dgamma = (q_trial + A[k] * p_trial - B[k]) / (G + K * A[k] * A_bar);
        factor = q_trial > 0.0 ? std::fmax(0.0, 1.0 - G * dgamma / q_trial) : 0.0;
        p = p_trial - K * A_bar * dgamma;
        r.kappa = kappa_n + dgamma;
      }
    }
    meridian_result(trial, p, factor, K, G, r.tau, r.e_el);
    return r;
  }
};

// A piece-wise Drucker-Prager material's constants as the scene gives them: pieces [A, B] (B in
// Pa), tension apex first, and the constant dilatancy A_bar of its flow potential.
struct PiecewiseDruckerPragerParams {
  std::vector<std::pair<double, double>> pieces;
  double pieces_dilatancy = 0.0;
};

// Empty if the pieces of m describe a convex surface, else a message for the key `pieces`.
inline std::string piecewise_drucker_prager_param_error(const PiecewiseDruckerPragerParams& m) {
  const auto& pc = m.pieces;
  if (pc.empty()) return "pieces must hold at least one [A, B] pair";
  for (std::size_t k = 0; k < pc.size(); ++k) {
    const std::string which = "piece " + std::to_string(k + 1);
    if (!std::isfinite(pc[k].first) || !std::isfinite(pc[k].second))
      return which + " is not finite";
    if (!(pc[k].first >= 0.0)) return which + ": A must be >= 0";
    if (!(pc[k].second > 0.0)) return which + ": B must be > 0";
    if (k > 0 && !(pc[k].first < pc[k - 1].first))
      return which +
             ": A must decrease strictly from piece to piece (a convex surface, "
             "tension apex first)";
  }
  // each piece must own a segment: the corners' pressures must decrease, the first one lie
  // below the apex, and q be positive there
  double p_prev =
      pc[0].first > 0.0 ? pc[0].second / pc[0].first : std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < pc.size(); ++k) {
    const double p = (pc[k].second - pc[k + 1].second) / (pc[k].first - pc[k + 1].first);
    if (!(p < p_prev))
      return "pieces " + std::to_string(k + 1) + " and " + std::to_string(k + 2) +
             " meet at p = " + std::to_string(p) +
             " Pa, not below the previous corner (or the apex): one of them never reaches the "
             "surface; B must grow enough from piece to piece";
    p_prev = p;
  }
  // The plastic work rate is dgamma (q + A_bar p) = dgamma (B_k + (A_bar - A_k) p) on piece k:
  // non-negative at every pressure only if A_bar <= A_n.
  if (!(m.pieces_dilatancy >= 0.0 && m.pieces_dilatancy <= pc.back().first))
    return "dilatancy must lie in [0, A of the last piece = " + std::to_string(pc.back().first) +
           "]: a larger one makes the plastic work negative at high pressure";
  return {};
}

inline PiecewiseDruckerPrager make_piecewise_drucker_prager(const MaterialBase& e,
                                                            const PiecewiseDruckerPragerParams& m) {
  PiecewiseDruckerPrager d;
  d.K = e.bulk_modulus();
  d.G = e.shear_modulus();
  d.A_bar = m.pieces_dilatancy;
  for (const auto& [a, b] : m.pieces) {
    d.A.push_back(a);
    d.B.push_back(b);
  }
  d.prepare();
  return d;
}

// The scene model `piecewise_drucker_prager` (the thesis' sec. 5.8; docs/SCENES.md).
struct PiecewiseDruckerPragerMaterial {
  static constexpr const char* name = "piecewise_drucker_prager";
  using Params = PiecewiseDruckerPragerParams;
  using Kernel = PiecewiseDruckerPrager;
  static std::vector<std::string> keys() { return {"pieces", "dilatancy", "dilatancy_angle"}; }
  static std::string check(const MaterialBase&, const Params& p) {
    return piecewise_drucker_prager_param_error(p);
  }
  static Kernel compile(const MaterialBase& e, const Params& p) {
    return make_piecewise_drucker_prager(e, p);
  }
  // pieces [[A, B], ...] from the tension apex to high pressure, and a constant dilatancy (A_bar
  // directly, or from an angle with the outer cone's formula).
  static Params read(const MaterialBase&, MaterialKeys& k) {
    Params m;
    if (!k.has("pieces")) k.fail("pieces", "is required for model 'piecewise_drucker_prager'");
    m.pieces = k.pairs("pieces", "must be a non-empty array of [A, B] pairs (B in Pa)",
                       "each piece must be [A, B] (two numbers, B in Pa)");
    if (k.has("dilatancy") && k.has("dilatancy_angle"))
      k.fail("dilatancy_angle", "give either 'dilatancy' (A_bar) or 'dilatancy_angle', not both");
    if (k.has("dilatancy_angle")) {
      const double psi = k.number("dilatancy_angle", 0.0);
      if (!(psi >= 0.0 && psi < 90.0))
        k.fail("dilatancy_angle", "must lie in [0, 90) degrees, got " + format_shortest(psi));
      double xi;
      drucker_prager_cone(DruckerPragerCone::Outer, psi * 3.14159265358979323846 / 180.0,
                          &m.pieces_dilatancy, &xi);
    } else {
      m.pieces_dilatancy = k.number("dilatancy", 0.0);
    }
    k.record("pieces", m.pieces);
    k.record("dilatancy", m.pieces_dilatancy);
    const std::string err = piecewise_drucker_prager_param_error(m);
    if (!err.empty()) k.fail(err.rfind("dilatancy", 0) == 0 ? "dilatancy" : "pieces", err);
    return m;
  }
  static std::string describe(const MaterialBase&, const Params& m) {
    std::string s = "    " + std::to_string(m.pieces.size()) + " pieces [A, B Pa]:";
    for (const auto& [a, b] : m.pieces) s += " [" + format_g(a) + ", " + format_g(b) + "]";
    return s + ", dilatancy " + format_g(m.pieces_dilatancy) + "\n";
  }
};

}  // namespace femdem
