// SPDX-License-Identifier: GPL-3.0-or-later
#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"
#include "materials/piecewise_drucker_prager.hpp"
#include "materials/von_mises.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

namespace {

const std::vector<std::string> kAvailableModels = {"elastic", "von_mises", "drucker_prager",
                                                   "mohr_coulomb", "piecewise_drucker_prager"};
const std::vector<std::string> kPlannedModels = {};
const std::vector<std::string> kCones = {"outer", "inner", "plane_strain", "inscribed"};

}  // namespace

void Reader::read_materials(const toml::table& root, ModelSpec& spec, toml::array& out) const {
  std::set<std::string> names;
  for (const auto& [tp, p] : entries(root, "materials")) {
    const toml::table& t = *tp;
    // The model decides which keys are allowed, so it comes first.
    const std::string model = string(t, "model", p, &t);
    const toml::node* mn = t.get("model");
    if (std::find(kPlannedModels.begin(), kPlannedModels.end(), model) != kPlannedModels.end())
      fail(mn, dotted(p, "model"),
           "material model '" + model + "' is not available yet in this version (available: " +
               join(kAvailableModels) + ")");
    if (std::find(kAvailableModels.begin(), kAvailableModels.end(), model) ==
        kAvailableModels.end()) {
      std::vector<std::string> all = kAvailableModels;
      all.insert(all.end(), kPlannedModels.begin(), kPlannedModels.end());
      fail(mn, dotted(p, "model"),
           "unknown material model '" + model + "'" + did_you_mean(model, all) +
               "; available: " + join(kAvailableModels));
    }
    std::vector<std::string> keys = {"name", "model", "density", "youngs_modulus", "poisson_ratio"};
    if (model == "von_mises")
      keys.insert(keys.end(),
                  {"yield_stress", "hardening_modulus", "hardening_curve", "swift_k", "swift_eps0",
                   "swift_n", "rate_coefficient", "reference_strain_rate"});
    if (model == "mohr_coulomb" || model == "drucker_prager")
      keys.insert(keys.end(), {"cohesion", "friction_angle", "dilatancy_angle",
                               "cohesion_hardening_modulus", "residual_cohesion"});
    if (model == "drucker_prager") keys.push_back("cone");
    if (model == "piecewise_drucker_prager")
      keys.insert(keys.end(), {"pieces", "dilatancy", "dilatancy_angle"});
    check_keys(t, p, keys, "for model '" + model + "'");
    MaterialParams m;
    m.name = entry_name(t, p, names, "material");
    m.model = model == "von_mises"                  ? MaterialModel::VonMises
              : model == "mohr_coulomb"             ? MaterialModel::MohrCoulomb
              : model == "drucker_prager"           ? MaterialModel::DruckerPrager
              : model == "piecewise_drucker_prager" ? MaterialModel::PiecewiseDruckerPrager
                                                    : MaterialModel::Elastic;
    m.density = positive(t, "density", p, std::nullopt, &t);
    m.youngs_modulus = positive(t, "youngs_modulus", p, std::nullopt, &t);
    m.poisson_ratio = number(t, "poisson_ratio", p, std::nullopt, &t);
    if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
      fail(t.get("poisson_ratio"), dotted(p, "poisson_ratio"),
           "must lie in (-1, 0.5), got " + format_number(m.poisson_ratio));
    toml::table o;
    o.insert_or_assign("name", m.name);
    o.insert_or_assign("model", model);
    o.insert_or_assign("density", m.density);
    o.insert_or_assign("youngs_modulus", m.youngs_modulus);
    o.insert_or_assign("poisson_ratio", m.poisson_ratio);
    if (m.model == MaterialModel::VonMises) read_von_mises(t, p, m, o);
    if (m.model == MaterialModel::MohrCoulomb || m.model == MaterialModel::DruckerPrager)
      read_frictional(t, p, m, o);
    if (m.model == MaterialModel::PiecewiseDruckerPrager) read_piecewise(t, p, m, o);
    spec.materials.push_back(m);
    out.push_back(std::move(o));
  }
}

// von Mises hardening: linear (hardening_modulus), a tabulated curve (hardening_curve), or
// Swift's power law (swift_k, swift_eps0, swift_n); optional Johnson-Cook rate factor.
void Reader::read_von_mises(const toml::table& t, const std::string& p, MaterialParams& m,
                            toml::table& o) const {
  const bool has_curve = t.contains("hardening_curve");
  const bool has_swift = t.contains("swift_k") || t.contains("swift_eps0") || t.contains("swift_n");
  const bool has_linear = t.contains("hardening_modulus");
  if (int(has_curve) + int(has_swift) + int(has_linear) > 1)
    fail(&t, p,
         "give one hardening law: 'hardening_modulus' (linear), 'hardening_curve' (tabulated) "
         "or 'swift_k', 'swift_eps0', 'swift_n' (power law)");
  if (has_curve) {
    m.hardening = HardeningLaw::Tabulated;
    const toml::node* cn = t.get("hardening_curve");
    const toml::array* arr = cn->as_array();
    if (!arr || arr->empty())
      fail(cn, dotted(p, "hardening_curve"),
           "must be a non-empty array of [equivalent_plastic_strain, stress] pairs");
    toml::array co;
    for (const toml::node& pt : *arr) {
      const toml::array* pair = pt.as_array();
      if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number())
        fail(&pt, dotted(p, "hardening_curve"),
             "each point must be [equivalent_plastic_strain, stress] (two numbers)");
      const double e = (*pair)[0].value<double>().value(), y = (*pair)[1].value<double>().value();
      m.hardening_curve.emplace_back(e, y);
      co.push_back(toml::array{e, y});
    }
    o.insert_or_assign("hardening_curve", std::move(co));
    if (t.contains("yield_stress"))
      fail(t.get("yield_stress"), dotted(p, "yield_stress"),
           "is given by the first point of 'hardening_curve'; remove one of them");
    m.yield_stress = m.hardening_curve.front().second;
  } else if (has_swift) {
    m.hardening = HardeningLaw::Swift;
    m.swift_K = positive(t, "swift_k", p, std::nullopt, &t);
    m.swift_eps0 = positive(t, "swift_eps0", p, std::nullopt, &t);
    m.swift_n = positive(t, "swift_n", p, std::nullopt, &t);
    m.yield_stress = m.swift_K * std::pow(m.swift_eps0, m.swift_n);
    if (t.contains("yield_stress"))
      fail(t.get("yield_stress"), dotted(p, "yield_stress"),
           "is swift_k * swift_eps0^swift_n for the Swift law; remove it");
    o.insert_or_assign("swift_k", m.swift_K);
    o.insert_or_assign("swift_eps0", m.swift_eps0);
    o.insert_or_assign("swift_n", m.swift_n);
  } else {
    m.hardening = HardeningLaw::Linear;
    m.yield_stress = positive(t, "yield_stress", p, std::nullopt, &t);
    m.hardening_modulus = number(t, "hardening_modulus", p, 0.0, &t);
    o.insert_or_assign("yield_stress", m.yield_stress);
    o.insert_or_assign("hardening_modulus", m.hardening_modulus);
  }
  if (t.contains("rate_coefficient") || t.contains("reference_strain_rate")) {
    m.jc_C = number(t, "rate_coefficient", p, 0.0, &t);
    if (m.jc_C < 0.0)
      fail(t.get("rate_coefficient"), dotted(p, "rate_coefficient"),
           "must be >= 0, got " + format_number(m.jc_C));
    m.jc_epsdot0 = positive(t, "reference_strain_rate", p, 1.0, &t);
    o.insert_or_assign("rate_coefficient", m.jc_C);
    o.insert_or_assign("reference_strain_rate", m.jc_epsdot0);
  }
  const std::string err = von_mises_param_error(m);
  if (!err.empty()) fail(&t, p, err);
}

// Mohr-Coulomb and Drucker-Prager: cohesion and friction angle, dilatancy (default associated),
// linear cohesion hardening/softening, and for Drucker-Prager the cone matched to Mohr-Coulomb.
void Reader::read_frictional(const toml::table& t, const std::string& p, MaterialParams& m,
                             toml::table& o) const {
  m.cohesion = number(t, "cohesion", p, std::nullopt, &t);
  if (!(m.cohesion >= 0.0))
    fail(t.get("cohesion"), dotted(p, "cohesion"),
         "must be >= 0, got " + format_number(m.cohesion));
  m.friction_angle = number(t, "friction_angle", p, std::nullopt, &t);
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 90.0))
    fail(t.get("friction_angle"), dotted(p, "friction_angle"),
         "must lie in [0, 90) degrees, got " + format_number(m.friction_angle));
  m.dilatancy_angle = number(t, "dilatancy_angle", p, m.friction_angle, &t);
  if (!(m.dilatancy_angle >= 0.0 && m.dilatancy_angle <= m.friction_angle))
    fail(t.get("dilatancy_angle"), dotted(p, "dilatancy_angle"),
         "must lie in [0, friction_angle = " + format_number(m.friction_angle) + "] degrees, got " +
             format_number(m.dilatancy_angle));
  if (m.friction_angle == 0.0 && m.cohesion == 0.0)
    fail(t.get("cohesion"), dotted(p, "cohesion"),
         "and friction_angle are both 0: the material has no strength");
  m.cohesion_hardening_modulus = number(t, "cohesion_hardening_modulus", p, 0.0, &t);
  m.residual_cohesion = number(t, "residual_cohesion", p, 0.0, &t);
  if (t.contains("residual_cohesion") && !(m.cohesion_hardening_modulus < 0.0))
    fail(t.get("residual_cohesion"), dotted(p, "residual_cohesion"),
         "is the floor of a softening cohesion: it needs cohesion_hardening_modulus < 0");
  if (!(m.residual_cohesion >= 0.0 && m.residual_cohesion <= m.cohesion))
    fail(t.get("residual_cohesion"), dotted(p, "residual_cohesion"),
         "must lie in [0, cohesion], got " + format_number(m.residual_cohesion));
  o.insert_or_assign("cohesion", m.cohesion);
  o.insert_or_assign("friction_angle", m.friction_angle);
  o.insert_or_assign("dilatancy_angle", m.dilatancy_angle);
  o.insert_or_assign("cohesion_hardening_modulus", m.cohesion_hardening_modulus);
  if (m.cohesion_hardening_modulus < 0.0)
    o.insert_or_assign("residual_cohesion", m.residual_cohesion);
  if (m.model == MaterialModel::DruckerPrager) {
    const std::string cone = opt_string(t, "cone", p).value_or("outer");
    if (std::find(kCones.begin(), kCones.end(), cone) == kCones.end())
      fail(t.get("cone"), dotted(p, "cone"),
           "unknown cone '" + cone + "'" + did_you_mean(cone, kCones) +
               "; available: " + join(kCones) +
               " (matched to Mohr-Coulomb in compression, tension, plane strain, "
               "or inside the whole hexagon)");
    m.cone = cone == "inner"          ? DruckerPragerCone::Inner
             : cone == "plane_strain" ? DruckerPragerCone::PlaneStrain
             : cone == "inscribed"    ? DruckerPragerCone::Inscribed
                                      : DruckerPragerCone::Outer;
    o.insert_or_assign("cone", cone);
  }
  const std::string err = m.model == MaterialModel::MohrCoulomb ? mohr_coulomb_param_error(m)
                                                                : drucker_prager_param_error(m);
  if (!err.empty())
    fail(t.contains("cohesion_hardening_modulus") ? t.get("cohesion_hardening_modulus") : &t,
         dotted(p, "cohesion_hardening_modulus"), err);
}

// The thesis' piece-wise Drucker-Prager (sec. 5.8): pieces [[A, B], ...] from the tension apex
// to high pressure, and a constant dilatancy (A_bar directly, or from an angle with the outer
// cone's formula).
void Reader::read_piecewise(const toml::table& t, const std::string& p, MaterialParams& m,
                            toml::table& o) const {
  const toml::node* pn = t.get("pieces");
  if (!pn) fail(&t, dotted(p, "pieces"), "is required for model 'piecewise_drucker_prager'");
  const toml::array* arr = pn->as_array();
  if (!arr || arr->empty())
    fail(pn, dotted(p, "pieces"), "must be a non-empty array of [A, B] pairs (B in Pa)");
  toml::array po;
  for (const toml::node& pt : *arr) {
    const toml::array* pair = pt.as_array();
    if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number())
      fail(&pt, dotted(p, "pieces"), "each piece must be [A, B] (two numbers, B in Pa)");
    const double a = (*pair)[0].value<double>().value(), b = (*pair)[1].value<double>().value();
    m.pieces.emplace_back(a, b);
    po.push_back(toml::array{a, b});
  }
  if (t.contains("dilatancy") && t.contains("dilatancy_angle"))
    fail(t.get("dilatancy_angle"), dotted(p, "dilatancy_angle"),
         "give either 'dilatancy' (A_bar) or 'dilatancy_angle', not both");
  if (t.contains("dilatancy_angle")) {
    const double psi = number(t, "dilatancy_angle", p, 0.0, &t);
    if (!(psi >= 0.0 && psi < 90.0))
      fail(t.get("dilatancy_angle"), dotted(p, "dilatancy_angle"),
           "must lie in [0, 90) degrees, got " + format_number(psi));
    double xi;
    drucker_prager_cone(DruckerPragerCone::Outer, psi * std::numbers::pi / 180.0,
                        &m.pieces_dilatancy, &xi);
  } else {
    m.pieces_dilatancy = number(t, "dilatancy", p, 0.0, &t);
  }
  o.insert_or_assign("pieces", std::move(po));
  o.insert_or_assign("dilatancy", m.pieces_dilatancy);
  const std::string err = piecewise_drucker_prager_param_error(m);
  if (!err.empty()) {
    const bool dil = err.rfind("dilatancy", 0) == 0;
    fail(dil ? (t.contains("dilatancy") ? t.get("dilatancy") : &t) : pn,
         dotted(p, dil ? "dilatancy" : "pieces"), err);
  }
}

}  // namespace femdem::scene
