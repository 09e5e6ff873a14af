// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/rank_group.hpp"

#include <chrono>
#include <cstring>
#include <exception>
#include <optional>

#include "engine/distributed/local_part.hpp"
#include "engine/errors.hpp"

namespace femdem {

RankGroup::RankGroup(const Model& whole, const Communicator& comm)
    : comm_(comm), partition_(partition_model(whole, comm.size())) {
  if (comm.rank() != 0) whole_ = whole;
  dist_.comm = &comm_;
  build_part(whole);
}

void RankGroup::build_part(const Model& whole) {
  local_.reset();
  dist_.part = local_part(whole, partition_, comm_.rank(), ghost_layers(whole));
  Model local = local_model(whole, dist_.part);
  Simulation::check_distributable(local, dist_.part);  // (before the first collective call)
  local_ = std::make_unique<Simulation>(std::move(local), dist_);
  ghosts_sent_.clear();
  std::int64_t sent = 0;
  for (const LocalPart::Neighbour& n : dist_.part.neighbours)
    sent += static_cast<std::int64_t>(n.send.size());
  const auto* bytes = reinterpret_cast<const std::byte*>(&sent);
  for (const std::vector<std::byte>& b : comm_.gather({bytes, sizeof sent})) {
    std::int64_t n = 0;
    std::memcpy(&n, b.data(), sizeof n);
    ghosts_sent_.push_back(n);
  }
}

RankGroup::~RankGroup() {
  if (comm_.rank() == 0 && !stopped_) {
    try {
      stop();
    } catch (...) {  // (nothing to do about a failing message while unwinding)
    }
  }
}

void RankGroup::send(Command c, double dt_limit) {
  Message m{c, dt_limit};
  comm_.broadcast(&m, sizeof m);
}

namespace {

// Adds the wall-clock time of its scope to `total`.
class Timed {
 public:
  explicit Timed(double& total) : total_(total), t0_(std::chrono::steady_clock::now()) {}
  ~Timed() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

void RankGroup::step(double dt_limit, Simulation& view) {
  const Timed t(times_.step_s);
  send(Command::step, dt_limit);
  local_->step(dt_limit);
  view.follow_clock(*local_);
}

void RankGroup::body_motions(std::vector<BodyState>& out) {
  const Timed t(times_.body_motions_s);
  send(Command::body_motions);
  local_->body_motions(out);
}

void RankGroup::sample(HistorySample& s) {
  const Timed t(times_.sample_s);
  send(Command::sample);
  take_sample(*local_, s);
  if (!volume_of_.empty()) volume_ = local_->bodies_volume(volume_of_);
}

void RankGroup::gather(Simulation& view, GatheredState what, ElementStressFigures* element_stress) {
  const Timed t(times_.gather_s);
  send(what == GatheredState::outputs ? Command::gather_outputs
       : what == GatheredState::frame ? Command::gather_frame
                                      : Command::gather_everything);
  gather_state(*local_, dist_, partition_, &view, what, element_stress);
}

void RankGroup::scatter(Simulation& view) {
  send(Command::scatter);
  scatter_state(&view, *local_, dist_);
}

void RankGroup::measure_work(std::vector<double>* work, std::vector<double>* body_pairs) {
  const std::size_t bodies = local_->model().bodies.size();
  std::vector<double> mine(1 + bodies, 0.0);
  const BodyContact& contact = local_->body_contact();
  mine[0] = static_cast<double>(dist_.part.elements.size()) +
            kPairWork * static_cast<double>(contact.candidate_pairs());
  contact.count_pairs_per_body(std::span<double>(mine).subspan(1));
  const auto* bytes = reinterpret_cast<const std::byte*>(mine.data());
  const auto all = comm_.gather({bytes, mine.size() * sizeof(double)});
  if (comm_.rank() != 0) return;
  work->clear();
  body_pairs->assign(bodies, 0.0);
  for (const std::vector<std::byte>& b : all) {
    std::vector<double> theirs(1 + bodies);
    std::memcpy(theirs.data(), b.data(), theirs.size() * sizeof(double));
    work->push_back(theirs[0]);
    for (std::size_t k = 0; k < bodies; ++k) (*body_pairs)[k] += theirs[1 + k];
  }
}

RankGroup::Rebalance RankGroup::rebalance(Simulation& view, double threshold) {
  Rebalance r;
  if (threshold < 0.0) return r;
  const Timed t(times_.rebalance_s);
  send(Command::measure_work);
  std::vector<double> work, body_pairs;
  measure_work(&work, &body_pairs);
  double total = 0.0, most = 0.0;
  for (double w : work) total += w, most = std::max(most, w);
  r.imbalance = most / (total / static_cast<double>(work.size())) - 1.0;
  if (!(r.imbalance >= threshold)) return r;
  for (double& p : body_pairs) p *= kPairWork;
  Partition next = partition_model(view.model(), comm_.size(), body_pairs);
  for (std::size_t e = 0; e < next.element_rank.size(); ++e)
    r.moved += next.element_rank[e] != partition_.element_rank[e];
  if (r.moved == 0) return r;
  r.dealt = true;
  send(Command::redeal);
  redeal(&view, std::move(next.element_rank));
  return r;
}

void RankGroup::redeal(Simulation* view, std::vector<std::int32_t> element_rank) {
  // the whole state on rank 0, the new partition to every rank, each part built again and
  // given its rows of that state
  gather_state(*local_, dist_, partition_, view, GatheredState::everything);
  // (the others' element_rank is empty until the broadcast)
  std::vector<std::byte> bytes(element_rank.size() * sizeof(std::int32_t));
  if (!bytes.empty()) std::memcpy(bytes.data(), element_rank.data(), bytes.size());
  comm_.broadcast(bytes);
  element_rank.resize(bytes.size() / sizeof(std::int32_t));
  if (!bytes.empty()) std::memcpy(element_rank.data(), bytes.data(), bytes.size());
  const Model& whole = view ? view->model() : *whole_;
  partition_ = partition_from(whole, comm_.size(), std::move(element_rank));
  build_part(whole);
  scatter_state(view, *local_, dist_);
}

void RankGroup::stop() {
  stopped_ = true;
  send(Command::stop);
  comm_.set_ending();  // (rank 0 may now end with its own exit code)
}

void RankGroup::follow() {
  std::optional<InstabilityError> unstable;
  for (;;) {
    Message m;
    comm_.broadcast(&m, sizeof m);
    switch (m.command) {
      case Command::step:
        try {
          local_->step(m.dt_limit);
        } catch (const InstabilityError& e) {
          // every rank finds it in the same step (its checks are collective); rank 0 writes
          // the outputs, then stops the others
          unstable = e;
        }
        break;
      case Command::body_motions:
        local_->body_motions(motions_);
        break;
      case Command::sample:
        take_sample(*local_, sample_);
        if (!volume_of_.empty()) volume_ = local_->bodies_volume(volume_of_);
        break;
      case Command::gather_outputs:
        gather_state(*local_, dist_, partition_, nullptr, GatheredState::outputs);
        break;
      case Command::gather_frame:
        gather_state(*local_, dist_, partition_, nullptr, GatheredState::frame);
        break;
      case Command::gather_everything:
        gather_state(*local_, dist_, partition_, nullptr, GatheredState::everything);
        break;
      case Command::scatter:
        scatter_state(nullptr, *local_, dist_);
        break;
      case Command::measure_work:
        measure_work(nullptr, nullptr);
        break;
      case Command::redeal:
        redeal(nullptr, {});
        break;
      case Command::stop:
        stopped_ = true;
        comm_.set_ending();
        if (unstable) throw *unstable;
        return;
    }
  }
}

}  // namespace femdem
