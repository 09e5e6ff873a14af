// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a law for contact between two bodies is given and gives back, for one candidate pair of
// contact sub-tetrahedra (one of each body) in one step. The engine (engine/body_contact.cpp)
// finds the candidate pairs, keeps each pair's friction spring, sums the outcomes in a fixed
// order and sizes the stable step from `stiffness`; the law only evaluates. A law is a struct
//   struct MyLaw {
//     static constexpr const char* name = "my_law";  // the scene's [contact] law
//     static void evaluate(const PairInput&, PairSpring&, PairOutcome&);
//   };
// in its own file, listed in contact/contact_laws.hpp. evaluate() runs concurrently for
// different pairs: it must touch nothing but its arguments.
#include <array>
#include <cstdint>

namespace femdem {

// A contact sub-tetrahedron's corner positions, gathered by the engine once per step.
using TetPositions = std::array<std::array<double, 3>, 4>;

// One pair: tetrahedron a of one body, b of the other, read from the model's arrays.
struct PairInput {
  const TetPositions* corners_a = nullptr;  // positions of tet_a's corners, now
  const TetPositions* corners_b = nullptr;
  // node velocities (half step), 3 per node: tet_a's corners index v_a, tet_b's v_b (the same
  // array in one process; on a rank of a distributed run a tet of another rank's body reads
  // the velocities received for it)
  const double* v_a = nullptr;
  const double* v_b = nullptr;
  std::array<std::int32_t, 4> tet_a{}, tet_b{};  // corner nodes
  double penalty = 0.0;   // Pa: [contact] penalty_factor x E of the stiffer side
  double friction = 0.0;  // Coulomb coefficient of the two bodies
  double step_dt = 0.0;   // the step the tangential motion is integrated over
};

// The pair's history, carried from step to step while it stays a candidate.
struct PairSpring {
  double stick[3] = {0, 0, 0};   // friction spring stretch
  double stick_stiffness = 0.0;  // its stiffness the last step it touched
  bool stretched() const { return stick[0] != 0.0 || stick[1] != 0.0 || stick[2] != 0.0; }
};

struct PairOutcome {
  bool touching = false;
  double force[24];          // on the 4 corners of a, then the 4 of b (only when touching)
  double energy = 0.0;       // stored in the pair now
  double dissipated = 0.0;   // by friction over the step (also when it stopped touching)
  double stiffness = 0.0;    // added to each of the 8 corners' nodes for the stable step
  double penetration = 0.0;  // overlap depth, for the history's contact.max_penetration
  // For impact damping (engine/impact_damping.hpp): the normal force on b, where it acts and
  // the pair's normal stiffness.
  double normal_force_b[3];
  double centroid[3];
  double secant = 0.0;
};

}  // namespace femdem
