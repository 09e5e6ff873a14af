// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/compaction.hpp"

#include <cmath>
#include <limits>

#include "engine/simulation.hpp"

namespace femdem {

std::vector<std::uint8_t> CompactionMonitor::powder_of(const Model& m, const CompactionSpec& spec) {
  std::vector<std::uint8_t> powder(m.bodies.size(), 0);
  if (spec.powder.empty()) {
    for (std::size_t b = 0; b < m.bodies.size(); ++b) powder[b] = m.bodies[b].fixed ? 0 : 1;
  } else {
    for (int b : spec.powder) powder[static_cast<std::size_t>(b)] = 1;
  }
  return powder;
}

CompactionMonitor::CompactionMonitor(const Simulation& sim, const CompactionSpec& spec)
    : spec_(spec), powder_(powder_of(sim.model(), spec)) {
  const Model& m = sim.model();
  const Vec3 n = m.walls[spec_.bottom].normal;
  v0_ = sim.bodies_volume(powder_);
  punch0_ = m.walls[spec_.punch].point.dot(n);
  h0_ = (m.walls[spec_.punch].point - m.walls[spec_.bottom].point).dot(n);
}

CompactionSample CompactionMonitor::sample(const Simulation& sim, double solid_volume) const {
  const Model& m = sim.model();
  const Wall& punch = m.walls[spec_.punch];
  const Wall& bottom = m.walls[spec_.bottom];
  const Vec3 n = bottom.normal;  // the die axis, from the bottom into the powder
  CompactionSample s;
  s.height = (punch.point - bottom.point).dot(n);
  s.punch_displacement = punch0_ - punch.point.dot(n);
  // wall forces are those the bodies exert on the walls
  s.punch_force = punch.force.dot(n);
  s.bottom_force = -bottom.force.dot(n);
  s.punch_pressure = s.punch_force / spec_.area;
  for (const int wi : spec_.die_walls) {
    const Wall& w = m.walls[wi];
    s.die_normal_force -= w.force.dot(w.normal);
    s.die_axial_force -= w.force.dot(n);
  }
  const double wetted = spec_.perimeter * s.height;
  s.radial_pressure =
      wetted > 0.0 ? s.die_normal_force / wetted : std::numeric_limits<double>::quiet_NaN();
  s.solid_volume = solid_volume;
  const double column = spec_.area * s.height;
  s.relative_density =
      column > 0.0 ? s.solid_volume / column : std::numeric_limits<double>::quiet_NaN();
  s.volume_ratio = s.solid_volume / v0_;
  s.column_strain = (h0_ - s.height) / h0_;  // the area is constant: (V0 - V) / V0 = 1 - h / h0
  return s;
}

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  LineFit f;
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) {
    f.slope = f.intercept = f.r2 = std::numeric_limits<double>::quiet_NaN();
    return f;
  }
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = x[i] - mx, dy = y[i] - my;
    sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
  }
  if (!(sxx > 0.0)) {
    f.slope = f.intercept = f.r2 = std::numeric_limits<double>::quiet_NaN();
    return f;
  }
  f.points = static_cast<int>(n);
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  double res = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - (f.slope * x[i] + f.intercept);
    res += r * r;
  }
  f.r2 = syy > 0.0 ? 1.0 - res / syy : 1.0;
  return f;
}

HeckelFit fit_heckel(std::span<const double> P, std::span<const double> D, double p_min,
                     double p_max) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < std::min(P.size(), D.size()); ++i) {
    if (!(P[i] >= p_min && P[i] <= p_max && D[i] > 0.0 && D[i] < 1.0)) continue;
    x.push_back(P[i]);
    y.push_back(std::log(1.0 / (1.0 - D[i])));
  }
  const LineFit l = fit_line(x, y);
  HeckelFit h;
  h.K = l.slope;
  h.A = l.intercept;
  h.yield_pressure = 1.0 / l.slope;
  h.r2 = l.r2;
  h.points = l.points;
  return h;
}

KawakitaFit fit_kawakita(std::span<const double> P, std::span<const double> C, double p_min,
                         double p_max) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < std::min(P.size(), C.size()); ++i) {
    if (!(P[i] >= p_min && P[i] <= p_max && P[i] > 0.0 && C[i] > 0.0)) continue;
    x.push_back(P[i]);
    y.push_back(P[i] / C[i]);
  }
  const LineFit l = fit_line(x, y);
  KawakitaFit k;
  // slope 1 / a, intercept 1 / (a b)
  k.a = 1.0 / l.slope;
  k.b = l.slope / l.intercept;
  k.r2 = l.r2;
  k.points = l.points;
  return k;
}

}  // namespace femdem
