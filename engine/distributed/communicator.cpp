// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/communicator.hpp"

// the C API only: Open MPI's and MPICH's mpi.h pull in the old C++ bindings otherwise
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace femdem {
namespace {

// the launchers' environment: Open MPI's mpirun, PMIx (Slurm, Open MPI 5), PMI (MPICH, Slurm)
bool has_env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0';
}

void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

// reused between calls: no allocation per step once the sizes are known
std::vector<std::vector<double>>& send_buffers() {
  static std::vector<std::vector<double>> b;
  return b;
}
std::vector<std::vector<double>>& receive_buffers() {
  static std::vector<std::vector<double>> b;
  return b;
}

}  // namespace

namespace {

// The agreed failure: every rank gets the exit code and message of rank `from`.
RanksFailed share_failure(int from, int code, std::string message) {
  MPI_Bcast(&code, 1, MPI_INT, from, MPI_COMM_WORLD);
  std::uint64_t n = message.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, from, MPI_COMM_WORLD);
  message.resize(n);
  MPI_Bcast(message.data(), static_cast<int>(n), MPI_CHAR, from, MPI_COMM_WORLD);
  return RanksFailed(code, from, message);
}

}  // namespace

void Communicator::start() const {
  if (started_ || size_ == 1) return;
  started_ = true;
  int lowest = size_;  // (no failure here)
  MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (lowest < size_) throw share_failure(lowest, 0, {});
}

RanksFailed Communicator::report_start_failure(int code, const std::string& message) const {
  if (started_ || size_ == 1) return RanksFailed(code, rank_, message);
  started_ = true;
  int lowest = rank_;
  MPI_Allreduce(MPI_IN_PLACE, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return share_failure(lowest, code, lowest == rank_ ? message : std::string());
}

bool Communicator::launched_by_mpi() {
  return has_env("OMPI_COMM_WORLD_SIZE") || has_env("PMIX_RANK") || has_env("PMI_SIZE");
}

int Communicator::launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (has_env(name)) return std::atoi(std::getenv(name));
  return -1;
}

Communicator& Communicator::world() {
  static Communicator w = [] {
    if (!launched_by_mpi()) return Communicator(0, 1, 1);
    int provided = 0;
    // OpenMP threads inside each rank; only the main thread talks to the other ranks
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit(finalize_at_exit);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Comm here;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &here);
    int size_here = 1;
    MPI_Comm_size(here, &size_here);
    MPI_Comm_free(&here);
    return Communicator(rank, size, size_here);
  }();
  return w;
}

void Communicator::sum(std::span<ExactSum> sums) const {
  start();
  if (size_ == 1 || sums.empty()) return;
  constexpr int kd = ExactSum::kDigits;
  std::vector<std::int64_t> limbs(sums.size() * kd);
  std::vector<double> specials(sums.size());
  for (std::size_t k = 0; k < sums.size(); ++k) {
    const ExactSum::Limbs l = sums[k].normalized_limbs();
    std::copy(l.begin(), l.end(), limbs.begin() + static_cast<std::ptrdiff_t>(k * kd));
    specials[k] = sums[k].special();
  }
  // integers add exactly in any order; the special values (inf, NaN) too
  MPI_Allreduce(MPI_IN_PLACE, limbs.data(), static_cast<int>(limbs.size()), MPI_INT64_T, MPI_SUM,
                MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, specials.data(), static_cast<int>(specials.size()), MPI_DOUBLE,
                MPI_SUM, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    ExactSum::Limbs l;
    std::copy_n(limbs.begin() + static_cast<std::ptrdiff_t>(k * kd), kd, l.begin());
    sums[k] = ExactSum::from_limbs(l, specials[k]);
  }
}

double Communicator::min(double x) const {
  start();
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return x;
}

void Communicator::min(std::span<double> x) const {
  start();
  if (size_ > 1 && !x.empty())
    MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(x.size()), MPI_DOUBLE, MPI_MIN,
                  MPI_COMM_WORLD);
}

std::int64_t Communicator::min(std::int64_t x) const {
  start();
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
  return x;
}

bool Communicator::all(bool flag) const {
  start();
  int f = flag ? 1 : 0;
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &f, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  return f != 0;
}

void Communicator::exchange(const LocalPart& part, double* values, int width) const {
  exchange(part.neighbours, values, values, width);
}

void Communicator::exchange(std::span<const LocalPart::Neighbour> lists, const double* from,
                            double* to, int width) const {
  start();
  if (size_ == 1 || lists.empty()) return;
  auto& send = send_buffers();
  auto& recv = receive_buffers();
  const std::size_t nb = lists.size();
  send.resize(nb);
  recv.resize(nb);
  std::vector<MPI_Request> requests(2 * nb);
  constexpr int kTag = 23;
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = lists[k];
    recv[k].resize(n.receive.size() * width);
    MPI_Irecv(recv[k].data(), static_cast<int>(recv[k].size()), MPI_DOUBLE, n.rank, kTag,
              MPI_COMM_WORLD, &requests[k]);
  }
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = lists[k];
    std::vector<double>& b = send[k];
    b.resize(n.send.size() * width);
    for (std::size_t i = 0; i < n.send.size(); ++i)
      for (int c = 0; c < width; ++c)
        b[i * width + c] = from[static_cast<std::size_t>(n.send[i]) * width + c];
    MPI_Isend(b.data(), static_cast<int>(b.size()), MPI_DOUBLE, n.rank, kTag, MPI_COMM_WORLD,
              &requests[nb + k]);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = lists[k];
    for (std::size_t i = 0; i < n.receive.size(); ++i)
      for (int c = 0; c < width; ++c)
        to[static_cast<std::size_t>(n.receive[i]) * width + c] = recv[k][i * width + c];
  }
}

std::vector<std::vector<std::byte>> Communicator::exchange_bytes(
    std::span<const int> ranks, const std::vector<std::vector<std::byte>>& to) const {
  start();
  std::vector<std::vector<std::byte>> from(ranks.size());
  if (size_ == 1 || ranks.empty()) return from;
  constexpr int kTag = 25;
  std::vector<MPI_Request> sent(ranks.size());
  for (std::size_t k = 0; k < ranks.size(); ++k)
    MPI_Isend(to[k].data(), static_cast<int>(to[k].size()), MPI_BYTE, ranks[k], kTag,
              MPI_COMM_WORLD, &sent[k]);
  // (the sizes are the senders': each message is probed for its length before it is received)
  for (std::size_t k = 0; k < ranks.size(); ++k) {
    MPI_Status status;
    MPI_Probe(ranks[k], kTag, MPI_COMM_WORLD, &status);
    int n = 0;
    MPI_Get_count(&status, MPI_BYTE, &n);
    from[k].resize(static_cast<std::size_t>(n));
    MPI_Recv(from[k].data(), n, MPI_BYTE, ranks[k], kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  MPI_Waitall(static_cast<int>(sent.size()), sent.data(), MPI_STATUSES_IGNORE);
  return from;
}

std::vector<std::vector<std::byte>> Communicator::all_gather(
    std::span<const std::byte> mine) const {
  start();
  std::vector<std::vector<std::byte>> all(static_cast<std::size_t>(size_));
  if (size_ == 1) {
    all[0].assign(mine.begin(), mine.end());
    return all;
  }
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(size_), offsets(size_ + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<std::byte> joined(static_cast<std::size_t>(offsets[size_]));
  MPI_Allgatherv(mine.data(), n, MPI_BYTE, joined.data(), counts.data(), offsets.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r)
    all[r].assign(joined.begin() + offsets[r], joined.begin() + offsets[r + 1]);
  return all;
}

std::vector<std::vector<std::byte>> Communicator::all_to_all(
    const std::vector<std::vector<std::byte>>& to_each) const {
  start();
  std::vector<std::vector<std::byte>> from(static_cast<std::size_t>(size_));
  if (size_ == 1) {
    from[0] = to_each.at(0);
    return from;
  }
  std::vector<int> send_counts(size_), send_offsets(size_ + 1, 0), recv_counts(size_),
      recv_offsets(size_ + 1, 0);
  for (int r = 0; r < size_; ++r) {
    send_counts[r] = static_cast<int>(to_each.at(r).size());
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r) recv_offsets[r + 1] = recv_offsets[r] + recv_counts[r];
  std::vector<std::byte> out(static_cast<std::size_t>(send_offsets[size_])),
      in(static_cast<std::size_t>(recv_offsets[size_]));
  for (int r = 0; r < size_; ++r)
    std::copy(to_each[r].begin(), to_each[r].end(), out.begin() + send_offsets[r]);
  MPI_Alltoallv(out.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, in.data(),
                recv_counts.data(), recv_offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r)
    from[r].assign(in.begin() + recv_offsets[r], in.begin() + recv_offsets[r + 1]);
  return from;
}

namespace {

// Messages of any size, in pieces MPI's int counts can name.
constexpr std::size_t kPiece = std::size_t{1} << 30;
constexpr int kBytesTag = 24;

void send_bytes(std::span<const std::byte> b, int to) {
  std::uint64_t n = b.size();
  MPI_Send(&n, 1, MPI_UINT64_T, to, kBytesTag, MPI_COMM_WORLD);
  for (std::size_t at = 0; at < b.size(); at += kPiece)
    MPI_Send(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, to,
             kBytesTag, MPI_COMM_WORLD);
}

std::vector<std::byte> receive_bytes(int from) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, kBytesTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<std::byte> b(n);
  for (std::size_t at = 0; at < b.size(); at += kPiece)
    MPI_Recv(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, from,
             kBytesTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return b;
}

}  // namespace

std::vector<std::vector<std::byte>> Communicator::gather(std::span<const std::byte> mine) const {
  start();
  std::vector<std::vector<std::byte>> all;
  if (rank_ != 0) {
    send_bytes(mine, 0);
    return all;
  }
  all.emplace_back(mine.begin(), mine.end());
  for (int r = 1; r < size_; ++r) all.push_back(receive_bytes(r));
  return all;
}

void Communicator::broadcast(std::vector<std::byte>& bytes) const {
  start();
  if (size_ == 1) return;
  std::uint64_t n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  bytes.resize(n);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    MPI_Bcast(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, 0,
              MPI_COMM_WORLD);
}

void Communicator::broadcast(void* data, std::size_t bytes) const {
  start();
  if (size_ > 1) MPI_Bcast(data, static_cast<int>(bytes), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void Communicator::abort(int code) const {
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace femdem
