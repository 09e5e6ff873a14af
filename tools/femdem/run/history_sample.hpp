// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One history sample of a run: everything a history.csv row shows, read from the simulation
// once, then handed to the column table (history_columns.hpp) and to the run monitors.
#include <optional>
#include <vector>

#include "engine/compaction.hpp"
#include "engine/simulation.hpp"

namespace femdem {

struct BodySample {
  BodyState motion;                   // Simulation::body_motion
  double max_principal_stress = 0.0;  // over the body's Gauss points, Pa, tension positive
};

struct WallSample {
  Vec3 force = Vec3::Zero();          // of the bodies on the wall
  Vec3 position = Vec3::Zero();       // the wall's point
  double penetration = 0.0;           // of its deepest node, m
  double penetration_per_size = 0.0;  // the largest depth over the node's element depth
};

struct HistorySample {
  double time = 0.0, dt = 0.0;
  Energies energies;
  double balance_error = 0.0;
  std::vector<BodySample> bodies;
  std::vector<WallSample> walls;
  std::optional<double> max_penetration;       // when bodies can touch each other
  double max_penetration_per_size = 0.0;       // of the body pairs
  std::optional<CompactionSample> compaction;  // when the scene has [compaction]
  // scratch of take_sample
  std::vector<BodyState> motions;
  std::vector<double> tensions;
};

// Fills `s` from the simulation now (reusing its vectors), all but the compaction columns,
// which the caller samples (and times) itself. In a distributed run every rank calls it on its
// part (tools/femdem/run/rank_group.hpp), and `s` is complete on rank 0.
inline void take_sample(const Simulation& sim, HistorySample& s) {
  const Model& m = sim.model();
  s.time = sim.time();
  s.dt = sim.dt();
  s.energies = sim.energies();
  s.balance_error = sim.balance_error();
  s.bodies.resize(m.bodies.size());
  sim.body_samples(s.motions, s.tensions);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) s.bodies[b] = {s.motions[b], s.tensions[b]};
  s.walls.resize(m.walls.size());
  for (std::size_t w = 0; w < m.walls.size(); ++w)
    s.walls[w] = {sim.wall_force(static_cast<int>(w)), sim.wall_position(static_cast<int>(w)),
                  sim.wall_contact().max_penetration(w),
                  sim.wall_contact().max_penetration_per_size(w)};
  if (sim.body_contact().active()) {
    s.max_penetration = sim.body_contact().max_penetration();
    s.max_penetration_per_size = sim.body_contact().max_penetration_per_size();
  }
}

}  // namespace femdem
