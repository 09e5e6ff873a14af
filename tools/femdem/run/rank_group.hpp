// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A run on several ranks (`mpirun -np N femdem run SCENE`; docs/ARCHITECTURE.md, "Distributed
// runs"). Every rank steps its part of the model. Rank 0 also keeps a Simulation of the whole
// model that it never steps: the run loop reads it and writes the outputs and checkpoints from
// it, as in one process, after gathering into it what they need. Rank 0 leads: each of its
// calls below is a command the other ranks, in follow(), carry out with it, so that every rank
// calls the same collective operations in the same order.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/distributed/communicator.hpp"
#include "engine/distributed/partition.hpp"
#include "engine/distributed/state_transfer.hpp"
#include "engine/simulation.hpp"
#include "tools/femdem/run/history_sample.hpp"

namespace femdem {

class RankGroup {
 public:
  // Every rank: cuts `whole` among the ranks and builds this rank's part (collective: the part's
  // stable step). Throws InputError when the model cannot be split this many ways or holds what
  // distributed runs cannot do yet (the same on every rank).
  RankGroup(const Model& whole, const Communicator& comm);
  // Rank 0: tells the others to stop, if no stop() was called (an error on rank 0 only).
  ~RankGroup();
  RankGroup(const RankGroup&) = delete;
  RankGroup& operator=(const RankGroup&) = delete;

  int ranks() const { return comm_.size(); }
  // Rank 0: how many ghost nodes each rank sends its neighbours every step (their positions and
  // velocities: 48 bytes a node), in rank order.
  const std::vector<std::int64_t>& ghosts_sent() const { return ghosts_sent_; }
  // Rank 0: wall-clock seconds spent so far in its commands (the steps with their exchanges,
  // the per-step body motions, the gathers for outputs and checkpoints).
  struct Times {
    double step_s = 0.0, body_motions_s = 0.0, sample_s = 0.0, gather_s = 0.0, rebalance_s = 0.0;
  };
  const Times& times() const { return times_; }
  const Partition& partition() const { return partition_; }
  const Simulation& part() const { return *local_; }

  // Rank 0's commands (`view`: its whole-model Simulation).
  // One step of every part; the view takes the part's time and step.
  void step(double dt_limit, Simulation& view);
  // Every body's motion (Simulation::body_motions) on rank 0.
  void body_motions(std::vector<BodyState>& out);
  // The view takes the ranks' state (GatheredState); for a frame, `element_stress` takes the
  // elements' stress figures (engine/distributed/state_transfer.hpp).
  void gather(Simulation& view, GatheredState what, ElementStressFigures* element_stress = nullptr);
  // A history row's figures (take_sample) from the parts, on rank 0, and the volume of the
  // bodies of measure_volume_of() (the compaction columns: powder_volume()).
  void sample(HistorySample& s);
  // Every rank, before the first sample: the bodies (a mask per body) whose deformed volume
  // each sample measures.
  void measure_volume_of(std::vector<std::uint8_t> bodies) { volume_of_ = std::move(bodies); }
  double powder_volume() const { return volume_; }
  // Every part takes its state from the view (after it read a checkpoint).
  void scatter(Simulation& view);
  // Measures each rank's work (held elements + kPairWork x listed contact pairs) and, when the
  // busiest exceeds the mean by at least `threshold` (>= 0), deals the bodies again by the
  // bisection of their current centroids in the view (current after a frame's gather),
  // weighted the same way; if that gives another partition, every rank takes its new part's
  // state from the view (as a resume on another number of ranks does, so the run's bits do
  // not change). Returns what it found.
  struct Rebalance {
    double imbalance = 0.0;  // busiest rank's work over the mean, minus 1
    bool dealt = false;      // a new partition was taken
    std::int64_t moved = 0;  // elements that changed rank
  };
  Rebalance rebalance(Simulation& view, double threshold);
  // Work a candidate contact pair costs, in element updates: a pair costs about 0.1 us a step
  // (4 % touching at 1.5 us, the rest rejected at 40 ns: docs/PERFORMANCE.md), an element
  // 0.35 us.
  static constexpr double kPairWork = 0.3;
  void stop();

  // The other ranks: carry out rank 0's commands until it stops. Rethrows an InstabilityError
  // of a step once rank 0 has written its outputs and stopped.
  void follow();

 private:
  enum class Command : int {
    step,
    body_motions,
    sample,
    gather_outputs,
    gather_frame,
    gather_everything,
    scatter,
    measure_work,
    redeal,
    stop
  };
  struct Message {
    Command command = Command::stop;
    double dt_limit = 0.0;
  };
  void send(Command c, double dt_limit = 0.0);
  // Every rank: its work and its pairs per body, gathered on rank 0 (work per rank, the bodies'
  // pairs summed).
  void measure_work(std::vector<double>* work, std::vector<double>* body_pairs);
  // Every rank: takes the partition rank 0 broadcasts (element_rank, on rank 0) and its part's
  // state from the view (rank 0's; null elsewhere).
  void redeal(Simulation* view, std::vector<std::int32_t> element_rank);
  void build_part(const Model& whole);

  const Communicator& comm_;
  std::optional<Model> whole_;  // the others': the whole model, to cut again (rank 0 has the view)
  Partition partition_;
  Distribution dist_;
  std::unique_ptr<Simulation> local_;
  std::vector<BodyState> motions_;  // followers' scratch
  HistorySample sample_;
  std::vector<std::uint8_t> volume_of_;
  double volume_ = 0.0;
  std::vector<std::int64_t> ghosts_sent_;
  Times times_;
  bool stopped_ = false;
};

}  // namespace femdem
