// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/communicator.hpp"

// the C API only: Open MPI's and MPICH's mpi.h pull in the old C++ bindings otherwise
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

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

bool Communicator::launched_by_mpi() {
  return has_env("OMPI_COMM_WORLD_SIZE") || has_env("PMIX_RANK") || has_env("PMI_SIZE");
}

Communicator& Communicator::world() {
  static Communicator w = [] {
    if (!launched_by_mpi()) return Communicator(0, 1);
    int provided = 0;
    // OpenMP threads inside each rank; only the main thread talks to the other ranks
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit(finalize_at_exit);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return Communicator(rank, size);
  }();
  return w;
}

void Communicator::sum(std::span<ExactSum> sums) const {
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
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return x;
}

std::int64_t Communicator::min(std::int64_t x) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
  return x;
}

bool Communicator::all(bool flag) const {
  int f = flag ? 1 : 0;
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &f, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  return f != 0;
}

void Communicator::exchange(const LocalPart& part, double* values, int width) const {
  if (size_ == 1 || part.neighbours.empty()) return;
  auto& send = send_buffers();
  auto& recv = receive_buffers();
  const std::size_t nb = part.neighbours.size();
  send.resize(nb);
  recv.resize(nb);
  std::vector<MPI_Request> requests(2 * nb);
  constexpr int kTag = 23;
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = part.neighbours[k];
    recv[k].resize(n.receive.size() * width);
    MPI_Irecv(recv[k].data(), static_cast<int>(recv[k].size()), MPI_DOUBLE, n.rank, kTag,
              MPI_COMM_WORLD, &requests[k]);
  }
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = part.neighbours[k];
    std::vector<double>& b = send[k];
    b.resize(n.send.size() * width);
    for (std::size_t i = 0; i < n.send.size(); ++i)
      for (int c = 0; c < width; ++c)
        b[i * width + c] = values[static_cast<std::size_t>(n.send[i]) * width + c];
    MPI_Isend(b.data(), static_cast<int>(b.size()), MPI_DOUBLE, n.rank, kTag, MPI_COMM_WORLD,
              &requests[nb + k]);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  for (std::size_t k = 0; k < nb; ++k) {
    const LocalPart::Neighbour& n = part.neighbours[k];
    for (std::size_t i = 0; i < n.receive.size(); ++i)
      for (int c = 0; c < width; ++c)
        values[static_cast<std::size_t>(n.receive[i]) * width + c] = recv[k][i * width + c];
  }
}

void Communicator::abort(int code) const {
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

}  // namespace femdem
