// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The engine's state: flat arrays over all nodes and elements of all bodies.
// Nodes and elements of body b are the contiguous ranges [first_node, first_node + node_count)
// and [first_element, first_element + element_count).
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "elements/tet10_mesh.hpp"
#include "engine/element_update/element_states.hpp"
#include "engine/model_spec.hpp"
#include "engine/wall_bumps.hpp"
#include "materials/finite_strain_update.hpp"

namespace femdem {

struct Body {
  std::string name;
  int material = -1;
  bool fixed = false;
  FbarMode fbar = FbarMode::Off;
  std::int32_t first_node = 0, node_count = 0;
  std::int32_t first_element = 0, element_count = 0;
  double mass = 0.0;  // sum of lumped nodal masses = rho V0
  double reference_volume = 0.0;
  std::vector<std::int32_t> surface_nodes;  // global node ids on the boundary
};

struct Wall {
  std::string name;
  Vec3 point0 = Vec3::Zero();  // at t = 0
  Vec3 point = Vec3::Zero();   // now
  Vec3 normal = Vec3(0, 0, 1);
  Vec3 velocity = Vec3::Zero();  // now
  // Non-empty: the wall follows this velocity history, point = point0 + its exact integral.
  std::vector<VelocityPoint> velocity_history;
  // Mean velocity over the last step (displacement / step), what the nodes' half-step
  // velocities are measured against; equals `velocity` for a wall moving steadily.
  Vec3 step_velocity = Vec3::Zero();
  double friction = 0.0;
  double rolling_resistance = 0.0;  // mu_r of bodies on it (the contact's unless the wall sets one)
  double penalty_factor = 0.0;      // 0: automatic (engine/contact_stiffness.hpp)
  double damping = 0.0;             // fraction of critical damping of each node's contact spring
  Vec3 force = Vec3::Zero();        // force the bodies exert on the wall, last step
  // Force-driven wall (WallSpec::force_history non-empty): mass, and its acceleration along the
  // normal at the last force evaluation. `velocity` is then its whole-step velocity.
  std::vector<ForcePoint> force_history;
  double mass = 0.0;
  double accel = 0.0;
  // finite axial extent (WallSpec::bounded): [bound_min, bound_max] along the unit bound_axis
  // where the wall stands at t = 0; the extent travels with the wall (a tube that is lifted
  // along its axis releases what lies below its lower end)
  bool bounded = false;
  Vec3 bound_axis = Vec3(0, 0, 1);
  double bound_min = 0.0, bound_max = 0.0;
  // how far behind its plane the wall reaches (WallSpec::thickness; infinite: a half-space)
  double thickness = HUGE_VAL;
  // a studded wall (WallSpec::bump_diameter): hemispheres on its plane, moving with it
  WallBumps bumps;
  bool force_driven() const { return !force_history.empty(); }

  // How a node at p is pushed out of the wall: by `depth` (> 0; <= 0: free) along `normal`.
  // A plain wall is a half-space: the depth behind its plane, along its normal. A bounded or
  // thin wall is a rigid plate, the slab between its plane and `thickness` behind it and between
  // the ends of its extent; a node inside it is pushed out through the nearest of those faces.
  // The penalty energy k depth^2 / 2 is then continuous where the faces meet, so an end that
  // slides past a node (a tube lifted off a column) neither cuts into it nor lets it go with a
  // jump, and a node behind the plate's back face (outside a tube) is pushed outwards.
  // A studded wall (a half-space, never bounded or thin) pushes a node out of the plane or of
  // the nearest bump, whichever it lies deeper in, the bump along the radius from its centre:
  // the depth, and so the penalty energy, stays continuous.
  struct Push {
    double depth = 0.0;
    Vec3 normal = Vec3::UnitZ();
  };
  Push push(const Vec3& p) const {
    Push out{(point - p).dot(normal), normal};
    if (bumps.present()) {
      const WallBumps::Inside in = bumps.nearest(p, point, normal);
      return in.depth > out.depth ? Push{in.depth, in.normal} : out;
    }
    if (!(out.depth > 0.0)) return out;
    const double back = thickness - out.depth;
    if (back < out.depth) out = {back, -normal};
    if (bounded) {
      const double s = (p - (point - point0)).dot(bound_axis);
      const double below = s - bound_min, above = bound_max - s;
      if (below < out.depth) out = {below, -bound_axis};
      if (above < out.depth) out = {above, bound_axis};
    }
    return out;
  }
  // How far in front of its plane the wall reaches (its bumps' height): a node further than
  // this in front of the plane is free.
  double relief() const { return bumps.radius; }
};

// Per boundary node of a body that can touch walls: its share of the surface area and the depth
// of the element behind it; the wall penalty stiffness is wall_modulus * area / depth
// (engine/contact_stiffness.hpp).
struct SurfaceNode {
  std::int32_t node = 0;
  std::int32_t body = 0;
  double area = 0.0;
  double depth = 0.0;
};

struct Model {
  std::string title;
  SimulationSettings settings;
  ContactSettings contact;
  std::vector<MaterialParams> materials;
  std::vector<Body> bodies;
  std::vector<Wall> walls;
  // Whether any contact has rolling resistance (the bodies' or a wall's own), and whether the
  // contacts are summed into patches for loads on the rigid motions (that, or impact damping).
  bool resists_rolling() const {
    if (contact.rolling_resistance > 0.0) return true;
    for (const Wall& w : walls)
      if (w.rolling_resistance > 0.0) return true;
    return false;
  }
  bool patch_loads() const { return contact.impact_damping > 0.0 || resists_rolling(); }

  // --- nodes (3 doubles per node for vectors) ---
  std::int32_t node_count = 0;
  std::vector<double> X;          // reference coordinates
  std::vector<double> x;          // current coordinates
  std::vector<double> v;          // velocity (at the half step between updates)
  std::vector<double> f_int;      // internal force (element stresses), gathered
  std::vector<double> f_contact;  // contact force: walls and other bodies
  std::vector<double> mass;       // lumped (HRZ), one per node
  std::vector<std::int32_t> node_body;
  std::vector<std::uint8_t> dof_mode;  // 3 per node: 0 free, 1 fixed, 2 prescribed velocity
  std::vector<double> dof_velocity;    // 3 per node: prescribed velocity where dof_mode == 2

  // --- elements ---
  std::int32_t element_count = 0;
  std::vector<Tet10> conn;
  std::vector<std::int32_t> element_body;
  std::vector<std::int32_t> element_material;
  // Reference shape-function gradients dN/dX at the 4 Gauss points (4 x 10 x 3) and the
  // Gauss weights times det J0 (4): 124 doubles per element.
  std::vector<double> dNdX;
  std::vector<double> gauss_weight;
  // Straight-sided elements (constant reference Jacobian J0: mid-edge nodes at the midpoints)
  // have J0^-1 here (9 per element, row-major; zeros for a curved element), from which the
  // SIMD update forms dN/dX itself (engine/element_update/element_update.hpp).
  std::vector<std::uint8_t> straight_sided;
  std::vector<double> inverse_jacobian;
  // Stable-step shape factor per element: omega_max * h0 / c_d, from the element eigenproblem.
  std::vector<double> frequency_factor;

  std::vector<FbarMode> element_fbar;
  std::vector<double> subtet_volume0;  // reference volume of the 8 sub-tets (FbarMode::SubTet)

  // --- Gauss-point state (4 per element) ---
  std::vector<ElementStates> states;  // plastic deformation and equivalent plastic strain
  // Cauchy stress, [element][component][Gauss point], components xx yy zz xy yz xz
  std::vector<double> stress;
  std::vector<double> strain_energy_density;  // per reference volume

  // --- node -> (element, local node) map for the deterministic gather (CSR) ---
  std::vector<std::int32_t> node_elem_offset;  // node_count + 1
  std::vector<std::int32_t> node_elem_slot;    // element * 10 + local node

  std::vector<SurfaceNode> surface;

  // Contact between bodies acts on the linear sub-tetrahedra of the TET10 elements that touch a
  // body's boundary: the 4 (of 8, elements/tet10_shape.hpp kSubTets) that each carry one of the
  // 4 triangles a 6-node boundary face splits into. Global node ids, body per sub-tet.
  std::vector<std::array<std::int32_t, 4>> contact_tets;
  std::vector<std::int32_t> contact_tet_body;
  // Per contact sub-tet, the depth of its element behind the boundary face (3V/A, reference
  // configuration): the element size overlaps are reported against.
  std::vector<double> contact_tet_depth;
  // Smallest edge of a contact sub-tet in the reference configuration: sets the broadphase
  // buffer.
  double contact_tet_min_edge = 0.0;
};

}  // namespace femdem
