// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Impact damping: a dashpot between the rigid motions of two bodies in contact (or a body and a
// wall), so that an impact loses energy as real ones do (a restitution below 1) while contact
// stays a penalty potential.
//
// Why on the rigid motion. Penalty contact is elastic: a unit that strikes a slope gives back
// what it took, and a layer of tumbling units never settles. A dashpot per contact node or per
// pair of contact tetrahedra would have to be sized by the light nodes it acts on (c ~ sqrt(k
// m_node)): it then hardly changes the restitution of a body (the wall `damping` changes that of
// a dropped sphere by 1e-3), and sized by the body's mass it is unstable on those nodes. Here
// each contact patch (the touching pairs between two bodies, summed: engine/contact_patch.hpp)
// gets one force along its normal at its centre,
//   f = -c v_n,   c = 2 xi sqrt(k m_eff),   1/m_eff = sum over the two bodies of
//                                           1/M + (r x n) . I^-1 (r x n),
// with v_n the normal relative velocity of the two rigid motions at the centre, k the patch's
// normal stiffness and m_eff the mass the two bodies oppose along the normal there. It is put on
// each body as a rigid load (engine/rigid_motion.hpp): it changes momentum and angular
// momentum, not the deformation, its explicit stability limit is that of a body on its contact
// spring (2 xi omega dt < 2), and momentum is exchanged exactly (equal and opposite). For a
// linear contact a damping ratio xi gives the restitution e = exp(-pi xi / sqrt(1 - xi^2)). It
// never pulls: the damping force is kept above minus the patch's elastic force, so a separating
// patch is not held. Its work, f v_n <= 0, is contact dissipation.
//
// The patch loads of one step (this damping and the rolling resistance,
// engine/rolling_resistance.hpp) share the bodies' rigid motions and are put on the nodes
// together: prepare_patch_loads, then each load, then apply_patch_loads.
#include <cstdint>
#include <vector>

#include "engine/contact_patch.hpp"
#include "engine/exact_sum.hpp"
#include "engine/model.hpp"
#include "engine/rigid_motion.hpp"

namespace femdem {

// The per-body work space of the patch loads, kept between steps (sized to the bodies once).
struct PatchLoads {
  std::vector<RigidMotion> rigid;   // the rigid motions computed this step
  std::vector<std::uint8_t> known;  // rigid[b] is this step's
  std::vector<Vec3> force, moment;  // the loads on each body, summed over its patches
  // The loads' power (<= 0) and their reactions on the walls (3 per wall), summed exactly over
  // the patches counted here: all in one process; on a rank of a distributed run, where a
  // patch between two ranks' bodies is on both, those of its first body
  // (engine/distributed/patch_motions.hpp). Reset by prepare_patch_loads.
  std::vector<std::uint8_t> counted;  // per patch (empty: every patch)
  ExactSum power;
  std::vector<ExactSum> wall_force;
  bool counts(std::size_t patch) const { return counted.empty() || counted[patch]; }
  void resize(std::size_t bodies) {
    rigid.assign(bodies, RigidMotion{});
    known.assign(bodies, 0);
    force.assign(bodies, Vec3::Zero());
    moment.assign(bodies, Vec3::Zero());
  }
  // adds force f at point x to body b's load
  void add(std::int32_t b, const Vec3& x, const Vec3& f) {
    force[b] += f;
    moment[b] += (x - rigid[b].centre).cross(f);
  }
};

// The rigid motions of the free bodies of the patches that act (each a pass over its nodes, in
// parallel over bodies: the same bits with any thread count), from the velocities of the coming
// full step, predicted from the half-step velocities and the last accelerations (v + half_dt
// accel): the integrator's kinetic energy sees a force work with the full-step velocity, and a
// dashpot taken at the half step would be off by c dt / 2m of its work, 1 % for a strong impact
// damping. The loads start at zero.
void prepare_patch_loads(const Model& m, const std::vector<ContactPatch>& patches,
                         const std::vector<double>& accel, double half_dt, PatchLoads& s);

// Adds the impact damping forces of the patches to the loads, their reactions on the walls to
// s.wall_force and their power (<= 0) to s.power. Each body's patches are summed into one
// resultant and moment, so that its nodes are visited once however many bodies and walls it
// touches.
void damp_impacts(const Model& m, double ratio, const std::vector<ContactPatch>& patches,
                  PatchLoads& s);

// Puts each body's summed load on its nodes as a rigid load (added to m.f_contact).
void apply_patch_loads(Model& m, PatchLoads& s);

// Whether a patch acts (it has a normal force and a stiffness).
inline bool patch_acts(const ContactPatch& p) {
  return p.force_on_a.norm() > 0.0 && p.weight > 0.0 && p.stiffness > 0.0;
}

}  // namespace femdem
