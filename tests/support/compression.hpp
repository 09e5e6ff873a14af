// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A finished run of scenes/mc_cylinder_compression.toml (or a coarser copy via --set): the
// theoretical peak from the run's resolved scene (run.log), and the axial stress-strain curve
// from history.csv. Shared by the fast and the long compression tests.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/history_csv.hpp"

namespace femdem::test {

struct CompressionRun {
  std::string model;  // "mohr_coulomb" or "von_mises"
  double cohesion = 0.0, friction_angle = 0.0, yield_stress = 0.0;
  double radius = 0.0, length = 0.0;
  double theory_peak = 0.0;                  // Pa
  double theory_band_angle = 0.0;            // degrees to the horizontal, 45 + phi / 2
  std::vector<double> time, strain, stress;  // stress: compression positive, Pa
};

// The number after "key = " on the first line of the resolved scene that has it (the scene has
// one material and one body), or in the body's inline mesh table.
inline double resolved_number(const std::string& text, const std::string& key) {
  const std::regex re("(^|[\\s{,])" + key + " = ([-+0-9.eE]+)");
  std::smatch m;
  if (!std::regex_search(text, m, re)) throw std::runtime_error("run.log: no " + key);
  return std::stod(m[2]);
}

inline CompressionRun read_compression_run(const std::filesystem::path& out) {
  CompressionRun r;
  std::ifstream in(out / "run.log");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto b = text.find("# resolved scene"), e = text.find("# end of resolved scene");
  if (b == std::string::npos || e == std::string::npos)
    throw std::runtime_error("run.log: no resolved scene");
  text = text.substr(b, e - b);
  std::smatch m;
  if (!std::regex_search(text, m, std::regex("model = \"([a-z_]+)\"")))
    throw std::runtime_error("run.log: no material model");
  r.model = m[1];
  r.radius = resolved_number(text, "radius");
  r.length = resolved_number(text, "length");
  if (r.model == "mohr_coulomb") {
    r.cohesion = resolved_number(text, "cohesion");
    r.friction_angle = resolved_number(text, "friction_angle");
    const double phi = r.friction_angle * std::numbers::pi / 180.0;
    r.theory_peak = 2.0 * r.cohesion * std::cos(phi) / (1.0 - std::sin(phi));
  } else {
    r.yield_stress = resolved_number(text, "yield_stress");
    r.theory_peak = r.yield_stress;
  }
  r.theory_band_angle = 45.0 + 0.5 * r.friction_angle;

  auto h = read_history(out / "history.csv");
  const double area = std::numbers::pi * r.radius * r.radius;
  const auto &fb = h.at("bottom.force_z"), &ft = h.at("top.force_z");
  const auto &zb = h.at("bottom.position_z"), &zt = h.at("top.position_z");
  r.time = h.at("time");
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    r.stress.push_back(0.5 * (ft[i] - fb[i]) / area);
    r.strain.push_back(1.0 - (zt[i] - zb[i]) / r.length);
  }
  return r;
}

// The largest axial stress up to `window` axial strain: the peak of the curve. Past the elastic
// limit (1.1e-4 here) the section grows as the material flows, so the wall force over the initial
// section keeps rising slowly although the true stress does not; 1.2e-3 (ten times the elastic
// limit, the range of the thesis' zoomed figure 4.28) keeps that growth below 0.2 %.
inline double peak_stress(const CompressionRun& r, double window = 1.2e-3) {
  double peak = 0.0;
  for (std::size_t i = 0; i < r.stress.size(); ++i)
    if (r.strain[i] <= window) peak = std::max(peak, r.stress[i]);
  return peak;
}

}  // namespace femdem::test
