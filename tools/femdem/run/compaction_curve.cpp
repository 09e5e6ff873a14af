// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/compaction_curve.hpp"

#include <algorithm>
#include <cmath>

namespace femdem {

CompactionCurve::CompactionCurve(const CompactionMonitor& monitor, double expected_rows)
    : monitor_(monitor) {
  curve_.reserve(static_cast<std::size_t>(std::min(1e6, expected_rows)) + 2);
}

CompactionSummary CompactionCurve::summarise() const {
  CompactionSummary out;
  const std::vector<CompactionSample>& curve = curve_;
  if (curve.empty()) return out;
  std::size_t peak = 0;
  double max_force = -HUGE_VAL, max_density = -HUGE_VAL, max_radial = -HUGE_VAL, max_dv = 0.0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const CompactionSample& c = curve[i];
    if (c.punch_pressure > curve[peak].punch_pressure) peak = i;
    max_force = std::max(max_force, c.punch_force);
    max_density = std::max(max_density, c.relative_density);
    max_radial = std::max(max_radial, c.radial_pressure);
    max_dv = std::max(max_dv, std::fabs(c.volume_ratio - 1.0));
  }
  const CompactionSample &first = curve.front(), &last = curve.back();
  const double p_max = curve[peak].punch_pressure;
  const CompactionSpec& spec = monitor_.spec();
  const double lo = spec.fit_min_pressure > 0.0 ? spec.fit_min_pressure : 0.2 * p_max;
  const double hi = spec.fit_max_pressure > 0.0 ? spec.fit_max_pressure : p_max;
  out.max_punch_pressure = p_max;
  out.max_punch_force = max_force;
  out.max_radial_pressure = max_radial;
  out.initial_relative_density = first.relative_density;
  out.final_relative_density = last.relative_density;
  out.max_relative_density = max_density;
  out.relative_density_at_max_pressure = curve[peak].relative_density;
  out.final_punch_displacement = last.punch_displacement;
  out.initial_solid_volume = monitor_.initial_solid_volume();
  out.final_volume_change = last.volume_ratio - 1.0;
  out.max_abs_volume_change = max_dv;
  // the fits use the loading part: the rows up to the largest punch pressure
  std::vector<double> P, D, C;
  for (std::size_t i = 0; i <= peak; ++i) {
    P.push_back(curve[i].punch_pressure);
    D.push_back(curve[i].relative_density);
    C.push_back(curve[i].column_strain);
  }
  out.fit_pressure_min = lo;
  out.fit_pressure_max = hi;
  out.heckel = fit_heckel(P, D, lo, hi);
  out.kawakita = fit_kawakita(P, C, lo, hi);
  return out;
}

}  // namespace femdem
