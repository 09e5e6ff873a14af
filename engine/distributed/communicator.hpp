// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The ranks of a distributed run, and the few things they do together (docs/ARCHITECTURE.md,
// "Distributed runs"): add exact sums, take minima, agree on a flag, and pass the ghost nodes'
// values from their owners. MPI (Open MPI) is behind this interface: only communicator.cpp
// includes mpi.h. MPI is started only when the program was launched by mpirun (or a batch
// system's launcher), so a plain `femdem run` never touches it and runs as one rank.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/distributed/local_part.hpp"
#include "engine/exact_sum.hpp"

namespace femdem {

// Some ranks failed before the ranks' first step together (reading the scene or the checkpoint,
// building the model or a part), as all ranks agreed (Communicator::report_start_failure):
// thrown on the ranks that did not fail, which then exit with `code` and say nothing (the
// lowest failing rank says why).
struct RanksFailed : std::runtime_error {
  RanksFailed(int exit_code, int failed_rank, const std::string& message)
      : std::runtime_error(message), code(exit_code), rank(failed_rank) {}
  int code;
  int rank;
};

class Communicator {
 public:
  // True when a launcher started this process as one of several ranks (its environment says so).
  static bool launched_by_mpi();
  // This process's rank as its launcher's environment gives it (before MPI starts), or -1.
  static int launcher_rank();
  // The world of this run: on first use starts MPI if launched by mpirun (and stops it at
  // exit), else a world of one rank.
  static Communicator& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  // How many of the ranks run on this machine (they share its cores).
  int size_here() const { return size_here_; }

  // Every rank gets the totals of the ranks' accumulators (their limbs added as integers: exact).
  void sum(std::span<ExactSum> sums) const;
  double min(double x) const;
  // Element by element over the ranks.
  void min(std::span<double> x) const;
  std::int64_t min(std::int64_t x) const;
  bool all(bool flag) const;
  // The ghost nodes' values from their owners: `width` doubles per node of `part`, in local
  // numbering; each rank sends its owned nodes that others hold and receives its ghosts.
  void exchange(const LocalPart& part, double* values, int width) const;
  // The same along any lists: each rank sends from[send[i]] to `rank` and puts what it receives
  // at to[receive[i]] (`width` doubles each; from and to may be the same array).
  void exchange(std::span<const LocalPart::Neighbour> lists, const double* from, double* to,
                int width) const;
  // Messages of any size with a few ranks: to[k] goes to ranks[k], and from[k] comes back from
  // it (every rank named must name this one in turn).
  std::vector<std::vector<std::byte>> exchange_bytes(
      std::span<const int> ranks, const std::vector<std::vector<std::byte>>& to) const;
  // Every rank gets every rank's bytes, in rank order (its own included).
  std::vector<std::vector<std::byte>> all_gather(std::span<const std::byte> mine) const;
  // Rank r gets to_each[r] of every rank, in rank order (to_each has size() entries).
  std::vector<std::vector<std::byte>> all_to_all(
      const std::vector<std::vector<std::byte>>& to_each) const;
  // Rank 0 gets every rank's bytes, in rank order (its own first); the others get nothing.
  std::vector<std::vector<std::byte>> gather(std::span<const std::byte> mine) const;
  // Every rank gets rank 0's bytes (any size).
  void broadcast(std::vector<std::byte>& bytes) const;
  // Every rank gets rank 0's `bytes` bytes at `data` (a fixed-size message: a command).
  void broadcast(void* data, std::size_t bytes) const;
  // Stops every rank with `code` (what a failing rank calls, so that none waits for it forever).
  [[noreturn]] void abort(int code) const;

  // The start. Each rank reads its input by itself, and one may fail where the others do not (a
  // file it cannot read); had it stopped, the others would wait in their first collective call
  // forever. So the first collective call of every rank first agrees that no rank has failed
  // (else it throws RanksFailed), and a rank that fails before its first collective call reports
  // here instead, with its exit code and message: every rank learns the lowest failing rank's,
  // which this returns. Called once, before any other collective call (else it returns this
  // rank's own failure without asking the others).
  RanksFailed report_start_failure(int code, const std::string& message) const;
  // Whether the ranks have agreed to start; from then on a rank that fails alone stops them all.
  bool started() const { return started_; }
  // Whether the ranks are ending together (rank 0 sent, or this rank received, the command to
  // stop): a rank may then end with its own exit code without stopping the others.
  bool ending() const { return ending_; }
  void set_ending() const { ending_ = true; }

 private:
  Communicator(int rank, int size, int size_here)
      : rank_(rank), size_(size), size_here_(size_here) {}
  // The start agreement of a rank that has not failed (at its first collective call).
  void start() const;
  int rank_ = 0, size_ = 1, size_here_ = 1;
  mutable bool started_ = false, ending_ = false;
};

}  // namespace femdem
