// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a scene describes, resolved and checked by the scene reader (io/), before the engine
// builds its flat arrays from it. Plain data; every value has its default here.
#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "elements/fbar_mode.hpp"
#include "elements/tet10_mesh.hpp"
#include "engine/wall_motion.hpp"
#include "materials/material_params.hpp"

namespace femdem {

struct SimulationSettings {
  double end_time = 0.0;  // required
  // Fraction of the stable step; 0: the default of the estimate (safety()). The assembled
  // estimate is measured on the current shapes and contacts and was within 25 % of the true
  // limit, on the safe side, on every test (tests/engine/test_stable_step.cpp), so 0.8 of it
  // leaves that margin for what changes between estimates; the element bound is a bound of the
  // undeformed linear system that distorted elements and contact can break, so 0.5 of it (at
  // 0.8 a sphere-on-wall impact with a stiff wall gained 1 % energy, 6e-5 at 0.65, 1e-5 at 0.5).
  double time_step_safety = 0.0;
  double time_step = 0.0;  // > 0: fixed step (still checked against the stable step)
  // How the stable step is estimated (engine/stable_step/): `assembled` measures the highest
  // frequency of the whole model (elements at their current shape and the contact springs) by
  // Lanczos iterations every stable_step_interval steps, and scales the element-and-contact
  // bound between estimates by what it found; `element` is that bound alone.
  enum class StableStep { assembled, element };
  StableStep stable_step = StableStep::assembled;
  int stable_step_interval = 100;
  static constexpr double kAssembledSafety = 0.8, kElementSafety = 0.5;
  double safety() const {
    if (time_step_safety > 0.0) return time_step_safety;
    return stable_step == StableStep::assembled ? kAssembledSafety : kElementSafety;
  }
  // Contact springs are resolved at no more than contact_time_step_safety of their own limit
  // whatever the safety: a penalty switches on within a step and is not smooth, and measured on
  // flush faces pressed together the energy balance grows from 0.7 % at 0.5 to 2.4 % at 0.8
  // (tests/engine/test_contact_time_step.cpp). Both stable-step estimates count every contact
  // spring (safety / contact_time_step_safety)^2 times stiffer, so a contact-led mode takes the
  // step of contact_time_step_safety and an element-led one the full safety; a fixed time_step
  // is checked against the limit itself. A settling scene whose contacts close slowly (the
  // armour layer: the same energy balance at 0.8, 1.36 times fewer steps; docs/PERFORMANCE.md)
  // may raise it; above the safety it is the safety.
  static constexpr double kContactSafety = 0.5;  // the default
  double contact_time_step_safety = kContactSafety;
  double contact_stiffness_margin() const {
    if (time_step > 0.0) return 1.0;
    const double r = safety() / contact_time_step_safety;
    return r > 1.0 ? r * r : 1.0;
  }
  // The fraction of their own limit at which contact springs are resolved (at most the safety).
  double contact_safety() const { return std::min(safety(), contact_time_step_safety); }
  double output_interval = 0.0;  // 0: end_time / 50
  // [output] fields: the optional results fields to write (engine/output_fields.hpp)
  std::vector<std::string> output_fields;
  double history_interval = 0.0;  // 0: output_interval / 20
  // Checkpoints (checkpoint.h5 in the output folder, for femdem resume): every this many
  // simulated seconds (0: not by simulated time) and every this many wall seconds (0: not by
  // wall time); one is also written on SIGINT/SIGTERM, at rest and before the last steps.
  double checkpoint_interval = 0.0;
  double checkpoint_wall_interval = 600.0;
  // The run stops as unstable (InstabilityError) once |energy balance error| exceeds this
  // fraction (0: never): a step far above the stable one can create energy without diverging.
  // Not lower by default: the first touch of a soft, damped wall (tests StopAtRest) passes 5 %
  // for a while in a run that is sound.
  double energy_balance_limit = 0.25;
  Vec3 gravity = Vec3::Zero();
  int threads = 0;  // 0: all cores
  // Artificial bulk viscosity coefficients (0: off); 0.06 and 1.5 are the values explicit codes
  // use for impacts and shocks.
  double bulk_viscosity_linear = 0.0;
  double bulk_viscosity_quadratic = 0.0;
  // Selective mass scaling (0: off). Elements whose stable step would make the step fall below
  // this get extra mass, just enough to keep it there. Explicit codes offer it because a few
  // crushed elements (the foot of a Taylor bar) otherwise set the step of the whole model; the
  // added mass is reported and should stay a small fraction of the body's.
  double mass_scaling_time_step = 0.0;
  // Mass scaling that has to add more than this fraction of a body's mass during the run is
  // keeping a crushed element alive, not smoothing a few small ones: the run stops (exit 3).
  double mass_scaling_limit = 0.1;
  // Deformation damping (0: off): every node of a free body is pulled towards the body's rigid
  // motion (the velocity field of its linear and angular momentum) by -alpha m (v - v_rigid),
  // so vibrations die out while the bodies' translation and spin are untouched (thesis 2.3.4:
  // damping must not act on the rigid motion of the discrete elements). A mode of angular
  // frequency omega gets the damping ratio alpha / (2 omega).
  double deformation_damping = 0.0;  // alpha, 1/s
  // Stop at rest (0: off): end the run once the kinetic energy has stayed below this fraction
  // of its peak for rest_hold_time, so that a settling scene needs no guessed end_time.
  double rest_kinetic_fraction = 0.0;
  double rest_hold_time = 0.0;  // s; 0: one output interval
  // Distributed runs: at each frame, when the busiest rank's work (held elements and contact
  // pairs) exceeds the mean by at least this fraction, the bodies are dealt to the ranks again
  // from their current centroids (docs/ARCHITECTURE.md, "Distributed runs"); negative: never.
  double rebalance_threshold = 0.1;
};

struct BodySpec {
  std::string name;
  int material = -1;  // index into ModelSpec::materials
  Tet10Mesh mesh;     // already rotated and placed
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();  // rad/s about the body's initial centre of mass
  bool fixed = false;
  // F-bar variant; unset: default_fbar_mode(material)
  std::optional<FbarMode> fbar;
};

struct WallSpec {
  std::string name;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3(0, 0, 1);  // normalised by the reader; bodies live on the + side
  Vec3 velocity = Vec3::Zero();
  // Non-empty: the velocity follows this history instead (engine/wall_motion.hpp) and
  // `velocity` is ignored.
  std::vector<VelocityPoint> velocity_history;
  double friction = 0.0;
  // Rolling resistance mu_r of bodies on this wall (engine/rolling_resistance.hpp); < 0:
  // ContactSettings::rolling_resistance's. A rough base (grains glued on a plane) traps a grain
  // rolling over it where a smooth plane of the same friction lets it roll on.
  double rolling_resistance = -1.0;
  // > 0: this wall's factor; 0: ContactSettings::penalty_factor's; < 0 ("auto"): automatic
  double penalty_factor = 0.0;
  // Fraction of critical damping of each node's contact spring. 0 keeps contact elastic; a
  // high-speed impact on soft (yielding) material needs some, or the light corner nodes of the
  // impact face bounce off the wall into the body.
  double damping = 0.0;
  // Non-empty: a force-driven wall (a punch under a prescribed load). It is a rigid body of
  // mass `mass` that moves along its normal only, pushed by force_history(t) along the normal
  // (towards the bodies) and held back by the contact forces of the bodies; `velocity` then is
  // its initial velocity (along the normal). Integrated with the nodes' central difference.
  std::vector<ForcePoint> force_history;
  double mass = 0.0;
  // A wall of finite axial extent (the side of a die whose mouth a compact is ejected through,
  // a tube lifted off a granular column): it acts only on nodes whose coordinate p . bound_axis
  // lies in [bound_min, bound_max] as the wall stands at t = 0; the extent moves with the wall.
  bool bounded = false;
  Vec3 bound_axis = Vec3(0, 0, 1);
  double bound_min = -std::numeric_limits<double>::infinity();
  double bound_max = std::numeric_limits<double>::infinity();
  // A thin wall (a tube's side): it acts only on nodes less than `thickness` behind its plane;
  // what lies further behind is on its other side. Infinite: a half-space, as a floor is.
  double thickness = std::numeric_limits<double>::infinity();
  // > 0: a studded wall (engine/wall_bumps.hpp): hemispheres of this diameter centred on the
  // plane at the nodes of a hexagonal lattice of spacing `bump_spacing`, the rough plane of glued
  // beads. Only on a half-space wall (not bounded, not thin).
  double bump_diameter = 0.0;
  double bump_spacing = 0.0;
};

// Region of a body's reference configuration whose nodes a constraint acts on.
// Nodes: a node set named in the body's mesh file (a gmsh physical point, curve or surface).
struct RegionSpec {
  enum class Kind { All, Box, Plane, Nodes } kind = Kind::All;
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();
  Vec3 plane_point = Vec3::Zero(), plane_normal = Vec3(0, 0, 1);
  double tolerance = 0.0;           // 0: 1e-6 of the body's bounding-box diagonal
  std::string node_set;             // Nodes: its name
  std::vector<std::int32_t> nodes;  // Nodes: the body's node indices (0 = its first node)
};

struct ConstraintSpec {
  int body = -1;
  RegionSpec region;
  std::array<bool, 3> fix = {false, false, false};
  std::optional<Vec3> velocity;  // prescribed velocity of the selected nodes (all components)
};

// A pair of bodies whose contact friction differs from ContactSettings::friction.
struct ContactPairSpec {
  int body_a = -1, body_b = -1;
  double friction = 0.0;
};

struct ContactSettings {
  // The laws by name (contact/contact_laws.hpp, whose names these point to): between bodies,
  // and between bodies and walls.
  std::string_view law = "penalty_potential";
  std::string_view wall_law = "penalty";
  // > 0: penalty = factor * E of the stiffer side (the thesis' k = aE); 0: the automatic
  // stiffness of engine/contact_stiffness.hpp
  double penalty_factor = 0.0;
  double friction = 0.0;  // Coulomb coefficient between bodies
  // Fraction of critical damping of every contact between two bodies or a body and a wall,
  // acting on the bodies' rigid motion (engine/impact_damping.hpp): sets the restitution of an
  // impact, e = exp(-pi xi / sqrt(1 - xi^2)) for a linear contact. 0: elastic impacts.
  double impact_damping = 0.0;
  // Rolling resistance coefficient mu_r (engine/rolling_resistance.hpp): a moment mu_r R N
  // against the relative rolling at every contact patch. 0: off.
  double rolling_resistance = 0.0;
  // The deepest overlap allowed at t = 0, between bodies or behind a wall, as a fraction of the
  // element size there (engine/initial_overlap.hpp): a packing's round-off, not a scene error.
  double initial_overlap = 0.01;
  std::vector<ContactPairSpec> pairs;
  // Friction coefficient between two bodies: a pair's own, else the common one.
  double friction_between(int a, int b) const {
    for (const ContactPairSpec& p : pairs)
      if ((p.body_a == a && p.body_b == b) || (p.body_a == b && p.body_b == a)) return p.friction;
    return friction;
  }
};

// The F-bar variant a body gets when its scene does not say: off for every material. On the
// Taylor bar plain TET10 meets the thesis' numbers on three meshes, while the volume-based
// variants let the impact-face corner node fold into the rod (a TET10's volume does not depend
// on its corner nodes, so their pressure stiffness vanishes) and the sub-tet variant overshoots
// the base radius by 4 % (docs/VALIDATION.md, section 4).
inline FbarMode default_fbar_mode(const MaterialParams&) {
  return FbarMode::Off;
}

// A closed-die compaction (the scene's [compaction] section): which walls are the punch, the
// bottom and the die, the die's cross-section, and which bodies are the powder. Indices into
// ModelSpec::walls and ModelSpec::bodies. The die axis is the bottom wall's normal.
struct CompactionSpec {
  int punch = -1;
  int bottom = -1;
  std::vector<int> die_walls;
  double area = 0.0;        // die cross-section, m^2
  double perimeter = 0.0;   // die cross-section perimeter, m (0: no radial pressure)
  std::vector<int> powder;  // bodies; empty: every body that is not fixed
  // Range of mean punch pressure over which the Heckel and Kawakita lines are fitted (loading
  // part only). fit_min_pressure 0 means 0.2 x the largest pressure; max 0 the largest.
  double fit_min_pressure = 0.0;
  double fit_max_pressure = 0.0;
};

struct ModelSpec {
  std::string title;
  SimulationSettings simulation;
  std::vector<MaterialParams> materials;
  std::vector<BodySpec> bodies;
  std::vector<WallSpec> walls;
  std::vector<ConstraintSpec> constraints;
  ContactSettings contact;
  std::optional<CompactionSpec> compaction;
};

}  // namespace femdem
