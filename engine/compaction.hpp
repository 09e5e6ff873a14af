// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Closed-die compaction results (the scene's [compaction] section, docs/OUTPUTS.md): what a
// history row holds (punch travel and force, mean punch pressure, relative density from the
// deformed meshes, die-wall pressure, solid-volume ratio) and the two classical fits of the
// compaction curve, Heckel (1961) and Kawakita & Luedde (1971).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/model_spec.hpp"
#include "engine/state_archive.hpp"

namespace femdem {

class Simulation;

struct CompactionSample {
  double punch_displacement = 0.0;  // travel towards the bottom since t = 0, m
  double punch_force = 0.0;         // force of the powder on the punch, along the die axis, N
  double punch_pressure = 0.0;      // punch_force / die cross-section, Pa
  double bottom_force = 0.0;        // force of the powder on the bottom, against the axis, N
  double die_normal_force = 0.0;    // outward normal force of the powder on the die walls, N
  double die_axial_force = 0.0;     // force of the powder on the die walls towards the bottom, N
  double radial_pressure = 0.0;     // die_normal_force / (perimeter x height), Pa
  double height = 0.0;              // punch to bottom along the axis, m
  double solid_volume = 0.0;        // current volume of the powder bodies, m^3
  double relative_density = 0.0;    // solid_volume / (area x height)
  double volume_ratio = 0.0;        // solid_volume / its value at t = 0
  double column_strain = 0.0;       // Kawakita's C = (V0 - V) / V0 of the column area x height
};

class CompactionMonitor {
 public:
  // spec's indices refer to the simulation's walls and bodies; an empty powder list means every
  // body that is not fixed. Records V0 and the initial column height from the current state.
  CompactionMonitor(const Simulation& sim, const CompactionSpec& spec);
  // The bodies whose volume is the powder's (per body: 1 for the powder).
  static std::vector<std::uint8_t> powder_of(const Model& m, const CompactionSpec& spec);
  const std::vector<std::uint8_t>& powder() const { return powder_; }
  // From the walls of `sim` and the powder's solid volume now (Simulation::bodies_volume of
  // powder(): on the ranks of a distributed run, a sum they make together).
  CompactionSample sample(const Simulation& sim, double solid_volume) const;
  const CompactionSpec& spec() const { return spec_; }
  double initial_solid_volume() const { return v0_; }
  // Saves or loads what it recorded at t = 0 (a resumed run measures against the same start).
  void exchange_state(StateArchive& a) {
    const StateArchive::Scope scope(a, "compaction");
    a.value("v0", v0_);
    a.value("h0", h0_);
    a.value("punch0", punch0_);
  }

 private:
  CompactionSpec spec_;
  std::vector<std::uint8_t> powder_;  // per body: 1 for the powder
  double v0_ = 0.0;                   // initial solid volume
  double h0_ = 0.0;                   // initial column height
  double punch0_ = 0.0;               // initial punch position along the axis
};

struct LineFit {
  double slope = 0.0, intercept = 0.0, r2 = 0.0;
  int points = 0;  // 0: too few points; the numbers are then NaN
};
// Least squares y = slope x + intercept (centred sums, so offsets do not cost digits); R^2 is
// 1 - residual / total sum of squares.
LineFit fit_line(std::span<const double> x, std::span<const double> y);

// Heckel: ln(1 / (1 - D)) = K P + A over the samples with p_min <= P <= p_max and 0 < D < 1.
struct HeckelFit {
  double K = 0.0, A = 0.0, yield_pressure = 0.0, r2 = 0.0;  // yield pressure = 1 / K
  int points = 0;
};
HeckelFit fit_heckel(std::span<const double> P, std::span<const double> D, double p_min,
                     double p_max);

// Kawakita: P / C = P / a + 1 / (a b) over the samples with p_min <= P <= p_max and C > 0.
struct KawakitaFit {
  double a = 0.0, b = 0.0, r2 = 0.0;
  int points = 0;
};
KawakitaFit fit_kawakita(std::span<const double> P, std::span<const double> C, double p_min,
                         double p_max);

}  // namespace femdem
