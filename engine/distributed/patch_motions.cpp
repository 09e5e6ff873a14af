// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/patch_motions.hpp"

#include <algorithm>
#include <cstring>

namespace femdem {
namespace {

// A rigid motion as it travels: the body, then 28 numbers.
constexpr int kNumbers = 28;
struct Travelling {
  std::int32_t body = 0;
  double numbers[kNumbers];
};

Travelling pack(std::int32_t body, const RigidMotion& r) {
  Travelling t;
  t.body = body;
  double* d = t.numbers;
  *d++ = r.mass;
  for (const Vec3* v : {&r.centre, &r.velocity, &r.angular_velocity})
    for (int k = 0; k < 3; ++k) *d++ = (*v)[k];
  for (const Eigen::Matrix3d* a : {&r.inertia, &r.inertia_inverse})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) *d++ = (*a)(i, j);
  return t;
}

RigidMotion unpack(const Travelling& t) {
  RigidMotion r;
  const double* d = t.numbers;
  r.mass = *d++;
  for (Vec3* v : {&r.centre, &r.velocity, &r.angular_velocity})
    for (int k = 0; k < 3; ++k) (*v)[k] = *d++;
  for (Eigen::Matrix3d* a : {&r.inertia, &r.inertia_inverse})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) (*a)(i, j) = *d++;
  return r;
}

}  // namespace

void share_patch_motions(const Model& m, const Distribution& dist,
                         const std::vector<ContactPatch>& patches, PatchLoads& s) {
  const Communicator& comm = *dist.comm;
  const std::vector<std::int32_t>& body_rank = dist.part.body_rank;
  const int me = comm.rank();
  s.counted.assign(patches.size(), 0);
  // (rank, body) pairs: this rank's body to send to that rank
  std::vector<std::pair<int, std::int32_t>> out;
  for (std::size_t q = 0; q < patches.size(); ++q) {
    const ContactPatch& p = patches[q];
    s.counted[q] = body_rank[p.body_a] == me;
    if (p.body_b < 0 || !patch_acts(p)) continue;
    for (const auto& [mine, theirs] :
         {std::pair{p.body_a, p.body_b}, std::pair{p.body_b, p.body_a}})
      if (body_rank[mine] == me && body_rank[theirs] != me && !m.bodies[mine].fixed)
        out.emplace_back(body_rank[theirs], mine);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  std::vector<std::vector<std::byte>> to(comm.size());
  for (const auto& [rank, body] : out) {
    const Travelling t = pack(body, s.rigid[body]);
    const auto* b = reinterpret_cast<const std::byte*>(&t);
    to[rank].insert(to[rank].end(), b, b + sizeof t);
  }
  for (const std::vector<std::byte>& from : comm.all_to_all(to))
    for (std::size_t at = 0; at + sizeof(Travelling) <= from.size(); at += sizeof(Travelling)) {
      Travelling t;
      std::memcpy(&t, from.data() + at, sizeof t);
      s.rigid[t.body] = unpack(t);
      s.known[t.body] = 1;
      s.force[t.body].setZero();
      s.moment[t.body].setZero();
    }
}

}  // namespace femdem
