// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/rank_group.hpp"

#include <cstring>
#include <exception>
#include <optional>

#include "engine/distributed/local_part.hpp"
#include "engine/errors.hpp"

namespace femdem {

RankGroup::RankGroup(const Model& whole, const Communicator& comm)
    : comm_(comm), partition_(partition_model(whole, comm.size())) {
  dist_.part = local_part(whole, partition_, comm.rank(), ghost_layers(whole));
  dist_.comm = &comm_;
  local_ = std::make_unique<Simulation>(local_model(whole, dist_.part), dist_);
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

void RankGroup::step(double dt_limit, Simulation& view) {
  send(Command::step, dt_limit);
  local_->step(dt_limit);
  view.follow_clock(*local_);
}

void RankGroup::body_motions(std::vector<BodyState>& out) {
  send(Command::body_motions);
  local_->body_motions(out);
}

void RankGroup::gather(Simulation& view, GatheredState what) {
  send(what == GatheredState::outputs ? Command::gather_outputs : Command::gather_everything);
  gather_state(*local_, dist_, partition_, &view, what);
}

void RankGroup::scatter(Simulation& view) {
  send(Command::scatter);
  scatter_state(&view, *local_, dist_);
}

void RankGroup::stop() {
  stopped_ = true;
  send(Command::stop);
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
      case Command::gather_outputs:
        gather_state(*local_, dist_, partition_, nullptr, GatheredState::outputs);
        break;
      case Command::gather_everything:
        gather_state(*local_, dist_, partition_, nullptr, GatheredState::everything);
        break;
      case Command::scatter:
        scatter_state(nullptr, *local_, dist_);
        break;
      case Command::stop:
        stopped_ = true;
        if (unstable) throw *unstable;
        return;
    }
  }
}

}  // namespace femdem
