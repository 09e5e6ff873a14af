// SPDX-License-Identifier: GPL-3.0-or-later
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

#include "engine/errors.hpp"
#include "io/packing/packing.hpp"
#include "io/packing/packing_internal.hpp"

namespace femdem {

namespace packing_detail {

[[noreturn]] void bad(const std::string& key, const std::string& message) {
  throw InputError(message, {}, 0, 0, key);
}

std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a TOML float
  return s;
}

bool is_lattice(const std::string& a) {
  return a == "simple_cubic" || a == "body_centred_cubic" || a == "face_centred_cubic";
}

double lognormal_mu(const PackingParams& p) {
  // mean of exp(N(mu, s^2)) is exp(mu + s^2 / 2)
  return std::log(p.diameter_mean) - 0.5 * p.sigma * p.sigma;
}

// Largest and smallest diameters the distribution can produce.
double max_diameter(const PackingParams& p) {
  return p.distribution == "monodisperse" ? p.diameter : p.diameter_max;
}
double min_diameter(const PackingParams& p) {
  return p.distribution == "monodisperse" ? p.diameter : p.diameter_min;
}

}  // namespace packing_detail

using packing_detail::Container;
using packing_detail::is_lattice;
using packing_detail::lognormal_mu;
using packing_detail::max_diameter;
using packing_detail::min_diameter;
using packing_detail::num;

// ---------------------------------------------------------------------------------------------
// Parameters

std::optional<PackingParamError> check_packing_params(const PackingParams& p) {
  auto err = [](std::string key, std::string msg) {
    return std::optional<PackingParamError>(PackingParamError{std::move(key), std::move(msg)});
  };
  auto finite_positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (p.container != "box" && p.container != "cylinder")
    return err("container", "unknown container '" + p.container + "': use \"box\" or \"cylinder\"");
  if (p.container == "box") {
    if (!(finite_positive(p.size.x()) && finite_positive(p.size.y()) &&
          finite_positive(p.size.z())))
      return err("size", "the box needs three positive lengths [lx, ly, lz]");
  } else {
    if (!finite_positive(p.radius)) return err("radius", "the cylinder needs a positive radius");
    if (!finite_positive(p.height)) return err("height", "the cylinder needs a positive height");
  }
  const bool lattice = is_lattice(p.arrangement);
  if (!lattice && p.arrangement != "random")
    return err("arrangement", "unknown arrangement '" + p.arrangement +
                                  "': use \"random\", \"simple_cubic\", \"body_centred_cubic\" or "
                                  "\"face_centred_cubic\"");
  if (p.count < 0 || p.count > 1000000)
    return err("count",
               "must lie in [0, 1000000] (0: every lattice site), got " + std::to_string(p.count));
  if (!lattice && p.count < 1)
    return err("count", "a random packing needs the number of particles (count >= 1)");
  if (p.distribution == "monodisperse") {
    if (!finite_positive(p.diameter)) return err("diameter", "must be positive");
  } else if (p.distribution == "uniform") {
    if (lattice) return err("distribution", "a lattice needs monodisperse particles");
    if (!finite_positive(p.diameter_min)) return err("diameter_min", "must be positive");
    if (!(std::isfinite(p.diameter_max) && p.diameter_max > p.diameter_min))
      return err("diameter_max", "must be larger than diameter_min");
  } else if (p.distribution == "lognormal") {
    if (lattice) return err("distribution", "a lattice needs monodisperse particles");
    if (!finite_positive(p.diameter_mean)) return err("diameter_mean", "must be positive");
    if (!(finite_positive(p.sigma) && p.sigma <= 2.0))
      return err("sigma", "the standard deviation of ln d must lie in (0, 2]");
    if (p.diameter_min < 0.0 || !std::isfinite(p.diameter_min))
      return err("diameter_min", "must be positive (or 0 for the default mean * exp(-3 sigma))");
    if (p.diameter_max < 0.0 || !std::isfinite(p.diameter_max))
      return err("diameter_max", "must be positive (or 0 for the default mean * exp(3 sigma))");
    const PackingParams q = resolve_packing_params(p);
    if (!(q.diameter_max > q.diameter_min))
      return err("diameter_max", "must be larger than diameter_min");
    // The clip window must hold at least 1 % of the distribution, or redrawing takes forever.
    const double mu = lognormal_mu(q);
    auto cdf = [&](double d) {
      return 0.5 * std::erfc(-(std::log(d) - mu) / (q.sigma * std::sqrt(2.0)));
    };
    if (cdf(q.diameter_max) - cdf(q.diameter_min) < 0.01)
      return err("diameter_min",
                 "the clip window [diameter_min, diameter_max] holds less than 1 % of the "
                 "distribution");
  } else {
    return err("distribution", "unknown distribution '" + p.distribution +
                                   "': use \"monodisperse\", \"uniform\" or \"lognormal\"");
  }
  const PackingParams q = resolve_packing_params(p);
  const double dmax = max_diameter(q), dmin = min_diameter(q);
  if (dmax / dmin > 20.0)
    return err("diameter_max", "the largest diameter may be at most 20 times the smallest");
  const Container box(q);
  const double width = box.cylinder ? 2.0 * box.radius : std::min(box.hi.x(), box.hi.y());
  if (dmax > width * (1.0 + 1e-12) || dmax > box.hi.z() * (1.0 + 1e-12))
    return err(p.distribution == "monodisperse" ? "diameter" : "diameter_max",
               "the largest particle (" + num(dmax) + " m) does not fit in the container");
  if (!lattice) {
    // The settling's neighbour grid numbers its cells (one largest diameter wide) in 20 bits
    // across: a container wider than that is no packing anyone settles (found by fuzzing: a
    // cylinder of radius 1e13 m for three 2 mm grains overflowed the cell index).
    const bool cyl = p.container == "cylinder";
    const double across = cyl ? 2.0 * p.radius : std::max(p.size.x(), p.size.y());
    const double high = cyl ? p.height : p.size.z();
    const double limit = packing_detail::kMaxRandomContainerDiameters;
    if (!(across / dmax <= limit) || !(high / dmax <= limit))
      return err(cyl ? (across / dmax > limit ? "radius" : "height") : "size",
                 "the container is " + num(std::max(across, high) / dmax) +
                     " largest particle diameters across; a random packing allows at most " +
                     num(limit));
  }
  if (p.shape.empty()) return err("shape", "must not be empty");
  for (char c : p.shape)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return err("shape",
                 "'" + p.shape + "': a shape name has only letters, digits, '_', '-', '.'");
  if (!p.orientation.empty() && p.orientation != "identity" && p.orientation != "random")
    return err("orientation",
               "unknown orientation '" + p.orientation + "': use \"identity\" or \"random\"");
  if (!(std::isfinite(p.friction) && p.friction >= 0.0 && p.friction <= 10.0))
    return err("friction", "must lie in [0, 10]");
  return std::nullopt;
}

PackingParams resolve_packing_params(PackingParams p) {
  if (p.orientation.empty()) p.orientation = p.shape == "sphere" ? "identity" : "random";
  if (p.distribution == "lognormal") {
    if (p.diameter_min == 0.0) p.diameter_min = p.diameter_mean * std::exp(-3.0 * p.sigma);
    if (p.diameter_max == 0.0) p.diameter_max = p.diameter_mean * std::exp(3.0 * p.sigma);
  }
  return p;
}

std::string packing_params_text(const PackingParams& in) {
  const PackingParams p = resolve_packing_params(in);
  std::ostringstream os;
  os << "container = \"" << p.container << "\"\n";
  if (p.container == "box")
    os << "size = [" << num(p.size.x()) << ", " << num(p.size.y()) << ", " << num(p.size.z())
       << "]\n";
  else
    os << "radius = " << num(p.radius) << "\nheight = " << num(p.height) << "\n";
  os << "arrangement = \"" << p.arrangement << "\"\n";
  os << "count = " << p.count << "\n";
  os << "distribution = \"" << p.distribution << "\"\n";
  if (p.distribution == "monodisperse") os << "diameter = " << num(p.diameter) << "\n";
  if (p.distribution == "lognormal")
    os << "diameter_mean = " << num(p.diameter_mean) << "\nsigma = " << num(p.sigma) << "\n";
  if (p.distribution != "monodisperse")
    os << "diameter_min = " << num(p.diameter_min) << "\ndiameter_max = " << num(p.diameter_max)
       << "\n";
  os << "seed = " << p.seed << "\n";
  os << "shape = \"" << p.shape << "\"\n";
  os << "orientation = \"" << p.orientation << "\"\n";
  if (p.arrangement == "random") os << "friction = " << num(p.friction) << "\n";
  return os.str();
}

}  // namespace femdem
