// SPDX-License-Identifier: GPL-3.0-or-later
// Turns a ModelSpec into the engine's flat arrays.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "elements/tet10_frequency.hpp"
#include "elements/tet10_shape.hpp"
#include "elements/tet10_surface.hpp"
#include "engine/errors.hpp"
#include "engine/gather_map.hpp"
#include "engine/simulation.hpp"

namespace femdem {
namespace {

// Reference gradients and weights of one element; returns false if det J0 <= 0 anywhere.
// jinv (9): J0^-1 if J0 is the same at the 4 Gauss points (to 1e-13 of its size: a
// straight-sided element, whose J0 is constant since it is linear in the natural coordinates),
// else left alone; `straight` says which.
bool reference_gradients(const std::vector<Vec3>& nodes, const Tet10& el, double* dNdX, double* w,
                         double& min_detJ, double& volume, double* jinv, bool& straight) {
  volume = 0.0;
  min_detJ = HUGE_VAL;
  Eigen::Matrix3d J_first;
  double J_spread = 0.0;
  for (int g = 0; g < tet10::kGauss; ++g) {
    const auto dxi = tet10::shape_derivatives(tet10::gauss_point(g));
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();  // J(i,k) = dX_i / dxi_k
    for (int a = 0; a < 10; ++a)
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) J(i, k) += nodes[el[a]][i] * dxi[a][k];
    const double det = J.determinant();
    min_detJ = std::min(min_detJ, det);
    if (!(det > 0.0)) return false;
    if (g == 0) J_first = J;
    J_spread = std::max(J_spread, (J - J_first).cwiseAbs().maxCoeff());
    const Eigen::Matrix3d Jinv = J.inverse();
    if (g == 0)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) jinv[3 * k + j] = Jinv(k, j);
    for (int a = 0; a < 10; ++a)
      for (int j = 0; j < 3; ++j) {
        double v = 0.0;
        for (int k = 0; k < 3; ++k) v += dxi[a][k] * Jinv(k, j);
        dNdX[g * 30 + 3 * a + j] = v;
      }
    w[g] = det / 24.0;  // reference tet volume 1/6, 4 equal weights
    volume += w[g];
  }
  straight = J_spread <= 1e-13 * J_first.cwiseAbs().maxCoeff();
  if (!straight)
    for (int k = 0; k < 9; ++k) jinv[k] = 0.0;
  return true;
}

bool in_region(const RegionSpec& r, const Vec3& p, double tol) {
  switch (r.kind) {
    case RegionSpec::Kind::All:
      return true;
    case RegionSpec::Kind::Box:
      return (p.array() >= r.box_min.array() - tol).all() &&
             (p.array() <= r.box_max.array() + tol).all();
    case RegionSpec::Kind::Plane:
      return std::fabs((p - r.plane_point).dot(r.plane_normal.normalized())) <= tol;
    case RegionSpec::Kind::Nodes:
      return false;  // selected by index (apply_constraint)
  }
  return false;
}

// The arrays of a model of nn nodes and ne elements, zeroed (positions follow the bodies).
void allocate(Model& m, std::int32_t nn, std::int32_t ne) {
  m.node_count = nn;
  m.element_count = ne;
  m.X.resize(3 * nn);
  m.v.assign(3 * nn, 0.0);
  m.mass.assign(nn, 0.0);
  m.node_body.resize(nn);
  m.dof_mode.assign(3 * nn, 0);
  m.dof_velocity.assign(3 * nn, 0.0);
  m.f_int.assign(3 * nn, 0.0);
  m.f_contact.assign(3 * nn, 0.0);
  m.conn.resize(ne);
  m.element_body.resize(ne);
  m.element_material.resize(ne);
  m.dNdX.resize(static_cast<std::size_t>(ne) * 120);
  m.gauss_weight.resize(static_cast<std::size_t>(ne) * 4);
  m.straight_sided.assign(ne, 0);
  m.inverse_jacobian.assign(static_cast<std::size_t>(ne) * 9, 0.0);
  m.frequency_factor.resize(ne);
  m.stress.assign(static_cast<std::size_t>(ne) * 24, 0.0);
  m.states.assign(ne, ElementStates{});
  m.element_fbar.assign(ne, FbarMode::Off);
  m.subtet_volume0.assign(ne, 0.0);
  m.strain_energy_density.assign(static_cast<std::size_t>(ne) * 4, 0.0);
}

// The body's nodes and elements into the model's arrays: positions, connectivity, reference
// gradients and weights, lumped (HRZ) masses. Throws InputError on a bad mesh.
void add_mesh(Model& m, const BodySpec& bs, std::int32_t bi, Body& body) {
  const MaterialParams& mat = m.materials.at(bs.material);
  const std::int32_t node0 = body.first_node, elem0 = body.first_element;
  for (std::int32_t i = 0; i < body.node_count; ++i) {
    for (int k = 0; k < 3; ++k) m.X[3 * (node0 + i) + k] = bs.mesh.nodes[i][k];
    m.node_body[node0 + i] = bi;
  }
  std::string bad;
  int bad_count = 0;
  for (std::int32_t e = 0; e < body.element_count; ++e) {
    const Tet10& local = bs.mesh.elements[e];
    Tet10 global;
    for (int a = 0; a < 10; ++a) {
      if (local[a] < 0 || local[a] >= body.node_count)
        throw InputError("element " + std::to_string(e) + " refers to node " +
                             std::to_string(local[a]) + " which does not exist",
                         {}, 0, 0, "bodies." + bs.name + ".mesh");
      global[a] = local[a] + node0;
    }
    const std::int32_t ge = elem0 + e;
    m.conn[ge] = global;
    m.element_body[ge] = bi;
    m.element_material[ge] = bs.material;
    m.element_fbar[ge] = body.fbar;
    {
      double X0[30];
      for (int a = 0; a < 10; ++a)
        for (int k = 0; k < 3; ++k) X0[3 * a + k] = bs.mesh.nodes[local[a]][k];
      m.subtet_volume0[ge] = tet10::subtet_volume(X0);
    }
    double min_det = 0.0, vol = 0.0;
    double* dN = m.dNdX.data() + static_cast<std::size_t>(ge) * 120;
    double* w = m.gauss_weight.data() + static_cast<std::size_t>(ge) * 4;
    bool straight = false;
    if (!reference_gradients(bs.mesh.nodes, local, dN, w, min_det, vol,
                             m.inverse_jacobian.data() + 9 * static_cast<std::size_t>(ge),
                             straight)) {
      if (bad_count++ == 0) bad = std::to_string(e);
      continue;
    }
    m.straight_sided[ge] = straight;
    const double me = mat.density * vol;
    for (int a = 0; a < 10; ++a)
      m.mass[global[a]] += me * (a < 4 ? tet10::kHrzCorner : tet10::kHrzMidEdge);
    body.mass += me;
    body.reference_volume += vol;
  }
  if (bad_count > 0)
    throw InputError(std::to_string(bad_count) +
                         " inverted or degenerate element(s) (det J <= 0 at a "
                         "Gauss point), the first is element " +
                         bad + " (0-based, in mesh order)",
                     {}, 0, 0, "bodies." + bs.name + ".mesh");
}

// Stable-step factor of each of the body's elements: omega_max * h0 / c_d; at run time
// omega = factor * c_d / h(t).
void set_frequency_factors(Model& m, const Body& body) {
  const MaterialParams& mat = m.materials.at(body.material);
  const double lambda = mat.lame_lambda(), G = mat.shear_modulus();
  const double cd = std::sqrt(mat.p_wave_modulus() / mat.density);
  const std::int32_t elem0 = body.first_element;
#pragma omp parallel for schedule(static)
  for (std::int32_t e = 0; e < body.element_count; ++e) {
    const std::int32_t ge = elem0 + e;
    const double* dN = m.dNdX.data() + static_cast<std::size_t>(ge) * 120;
    const double* w = m.gauss_weight.data() + static_cast<std::size_t>(ge) * 4;
    const double vol = w[0] + w[1] + w[2] + w[3];
    const double omega = tet10_max_frequency(dN, w, mat.density * vol, lambda, G);
    double xe[12];
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) xe[3 * a + k] = m.X[3 * m.conn[ge][a] + k];
    // corner altitude, recomputed the same way as in the time loop
    const double* p = xe;
    Vec3 p0(p[0], p[1], p[2]), p1(p[3], p[4], p[5]), p2(p[6], p[7], p[8]), p3(p[9], p[10], p[11]);
    const double v6 = (p1 - p0).dot((p2 - p0).cross(p3 - p0));
    const double a2 =
        std::max(std::max((p1 - p0).cross(p2 - p0).norm(), (p1 - p0).cross(p3 - p0).norm()),
                 std::max((p2 - p0).cross(p3 - p0).norm(), (p2 - p1).cross(p3 - p1).norm()));
    const double h0 = v6 / a2;
    m.frequency_factor[ge] = omega * h0 / cd;
  }
}

// Initial velocity: translation plus rotation about the initial centre of mass (a fixed body's
// nodes are held instead).
void set_initial_velocity(Model& m, const BodySpec& bs, const Body& body) {
  const std::int32_t node0 = body.first_node;
  Vec3 com = Vec3::Zero();
  for (std::int32_t i = 0; i < body.node_count; ++i)
    com += m.mass[node0 + i] *
           Vec3(m.X[3 * (node0 + i)], m.X[3 * (node0 + i) + 1], m.X[3 * (node0 + i) + 2]);
  com /= body.mass;
  for (std::int32_t i = 0; i < body.node_count; ++i) {
    const std::int32_t n = node0 + i;
    const Vec3 r = Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]) - com;
    const Vec3 vel = bs.velocity + bs.angular_velocity.cross(r);
    for (int k = 0; k < 3; ++k) m.v[3 * n + k] = bs.fixed ? 0.0 : vel[k];
    if (bs.fixed)
      for (int k = 0; k < 3; ++k) m.dof_mode[3 * n + k] = 1;
  }
}

// The body's boundary: its surface nodes with their share of area (HRZ lumping of the 6-node
// face: corner A/19, mid-edge 16A/57) and the depth of the element behind the face (3V/A of the
// corner tet), for wall contact; and its contact sub-tets, for contact between bodies.
void add_boundary(Model& m, std::int32_t bi, Body& body) {
  const std::int32_t elem0 = body.first_element;
  std::vector<Tet10> global_elems(m.conn.begin() + elem0,
                                  m.conn.begin() + elem0 + body.element_count);
  const auto faces = boundary_faces(global_elems);
  std::map<std::int32_t, std::pair<double, double>> node_area_depth;  // node -> (area, depth)
  std::map<std::int32_t, double> element_depth;  // element -> its least boundary-face depth
  for (const auto& f : faces) {
    const Tet10& el = global_elems[f.element];
    const auto& fl = kTet10Faces[f.face];
    auto P = [&](int a) {
      const auto n = el[a];
      return Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    };
    const double area = 0.5 * (P(fl[1]) - P(fl[0])).cross(P(fl[2]) - P(fl[0])).norm();
    const double v6 = (P(1) - P(0)).dot((P(2) - P(0)).cross(P(3) - P(0)));
    const double depth = v6 / (2.0 * area);
    const auto [at, fresh] = element_depth.try_emplace(f.element, depth);
    if (!fresh) at->second = std::min(at->second, depth);
    for (int k = 0; k < 6; ++k) {
      auto& ad = node_area_depth.try_emplace(el[fl[k]], 0.0, HUGE_VAL).first->second;
      ad.first += area * (k < 3 ? 1.0 / 19.0 : 16.0 / 57.0);
      ad.second = std::min(ad.second, depth);
    }
  }
  // contact sub-tets: per element, those of its 8 with three nodes on one of its boundary
  // faces (each boundary triangle belongs to exactly one)
  std::map<std::int32_t, unsigned> element_subtets;  // element -> bit mask over kSubTets
  for (const auto& f : faces) {
    const auto& fl = kTet10Faces[f.face];
    unsigned& mask = element_subtets[f.element];
    for (int s = 0; s < 8; ++s) {
      int on_face = 0;
      for (int a = 0; a < 4; ++a)
        on_face += std::count(fl.begin(), fl.end(), tet10::kSubTets[s][a]) > 0;
      if (on_face == 3) mask |= 1u << s;
    }
  }
  for (const auto& [e, mask] : element_subtets) {
    const Tet10& el = global_elems[e];
    for (int s = 0; s < 8; ++s) {
      if (!(mask & (1u << s))) continue;
      std::array<std::int32_t, 4> t;
      for (int a = 0; a < 4; ++a) t[a] = el[tet10::kSubTets[s][a]];
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          const Vec3 d(m.X[3 * t[a]] - m.X[3 * t[b]], m.X[3 * t[a] + 1] - m.X[3 * t[b] + 1],
                       m.X[3 * t[a] + 2] - m.X[3 * t[b] + 2]);
          const double len = d.norm();
          if (m.contact_tet_min_edge == 0.0 || len < m.contact_tet_min_edge)
            m.contact_tet_min_edge = len;
        }
      m.contact_tets.push_back(t);
      m.contact_tet_body.push_back(bi);
      m.contact_tet_depth.push_back(element_depth.at(e));
    }
  }
  for (const auto& [n, ad] : node_area_depth) {
    body.surface_nodes.push_back(n);
    m.surface.push_back({n, bi, ad.first, ad.second});
  }
}

// A constraint on the nodes of its body in its region (selected in the reference
// configuration). Throws InputError when the region selects no node.
void apply_constraint(Model& m, const ConstraintSpec& c) {
  const Body& body = m.bodies.at(c.body);
  Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
  for (std::int32_t n = body.first_node; n < body.first_node + body.node_count; ++n) {
    const Vec3 p(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double tol = c.region.tolerance > 0.0 ? c.region.tolerance : 1e-6 * (hi - lo).norm();
  int selected = 0;
  std::vector<char> in_set;
  if (c.region.kind == RegionSpec::Kind::Nodes) {
    in_set.assign(static_cast<std::size_t>(body.node_count), 0);
    for (std::int32_t i : c.region.nodes)
      if (i < 0 || i >= body.node_count)
        throw InputError("node set '" + c.region.node_set + "' refers to node " +
                             std::to_string(i) + ", beyond the " + std::to_string(body.node_count) +
                             " of body '" + body.name + "'",
                         {}, 0, 0, "constraints");
      else
        in_set[static_cast<std::size_t>(i)] = 1;
  }
  for (std::int32_t n = body.first_node; n < body.first_node + body.node_count; ++n) {
    const Vec3 p(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    if (in_set.empty() ? !in_region(c.region, p, tol)
                       : !in_set[static_cast<std::size_t>(n - body.first_node)])
      continue;
    ++selected;
    for (int k = 0; k < 3; ++k) {
      if (c.velocity) {
        m.dof_mode[3 * n + k] = 2;
        m.dof_velocity[3 * n + k] = (*c.velocity)[k];
        m.v[3 * n + k] = (*c.velocity)[k];
      } else if (c.fix[k]) {
        m.dof_mode[3 * n + k] = 1;
        m.v[3 * n + k] = 0.0;
      }
    }
  }
  if (selected == 0)
    throw InputError("the region selects no node of body '" + body.name + "'", {}, 0, 0,
                     "constraints");
}

Wall make_wall(const WallSpec& ws, const ContactSettings& contact) {
  Wall w;
  w.name = ws.name;
  w.point0 = w.point = ws.point;
  w.normal = ws.normal.normalized();
  w.velocity = ws.velocity;
  w.velocity_history = ws.velocity_history;
  if (!w.velocity_history.empty()) w.velocity = history_velocity(w.velocity_history, 0.0);
  w.step_velocity = w.velocity;
  w.friction = ws.friction;
  w.rolling_resistance =
      ws.rolling_resistance >= 0.0 ? ws.rolling_resistance : contact.rolling_resistance;
  // (0 in the model: the automatic stiffness)
  w.penalty_factor = ws.penalty_factor > 0.0   ? ws.penalty_factor
                     : ws.penalty_factor < 0.0 ? 0.0
                                               : contact.penalty_factor;
  w.damping = ws.damping;
  w.force_history = ws.force_history;
  w.mass = ws.mass;
  if (w.force_driven()) {
    if (!(w.mass > 0.0))
      throw InputError("a wall with a force_history needs a positive mass", {}, 0, 0,
                       "walls." + ws.name + ".mass");
    // it moves along its normal only
    w.velocity = ws.velocity.dot(w.normal) * w.normal;
    w.step_velocity = w.velocity;
  }
  w.bounded = ws.bounded;
  w.bound_axis = ws.bound_axis.normalized();
  w.bound_min = ws.bound_min;
  w.bound_max = ws.bound_max;
  w.thickness = ws.thickness;
  if (ws.bump_diameter > 0.0) {
    if (ws.bounded || std::isfinite(ws.thickness))
      throw InputError("bumps are for a half-space wall, not a bounded or thin one", {}, 0, 0,
                       "walls." + ws.name + ".bumps");
    w.bumps.radius = 0.5 * ws.bump_diameter;
    w.bumps.spacing = ws.bump_spacing;
    w.bumps.orient(w.normal);
  }
  return w;
}

}  // namespace

void build_gather_map(Model& m) {
  const std::int32_t nn = m.node_count, ne = m.element_count;
  m.node_elem_offset.assign(nn + 1, 0);
  for (std::int32_t e = 0; e < ne; ++e)
    for (int a = 0; a < 10; ++a) ++m.node_elem_offset[m.conn[e][a] + 1];
  for (std::int32_t n = 0; n < nn; ++n) m.node_elem_offset[n + 1] += m.node_elem_offset[n];
  m.node_elem_slot.resize(m.node_elem_offset[nn]);
  std::vector<std::int32_t> fill(m.node_elem_offset.begin(), m.node_elem_offset.end() - 1);
  for (std::int32_t e = 0; e < ne; ++e)
    for (int a = 0; a < 10; ++a) m.node_elem_slot[fill[m.conn[e][a]]++] = e * 10 + a;
}

Model build_model(const ModelSpec& spec) {
  Model m;
  m.title = spec.title;
  m.settings = spec.simulation;
  m.contact = spec.contact;
  m.materials = spec.materials;
  std::int32_t nn = 0, ne = 0;
  for (const auto& b : spec.bodies) {
    nn += static_cast<std::int32_t>(b.mesh.nodes.size());
    ne += static_cast<std::int32_t>(b.mesh.elements.size());
  }
  allocate(m, nn, ne);

  std::int32_t node0 = 0, elem0 = 0;
  for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
    const BodySpec& bs = spec.bodies[i];
    const auto bi = static_cast<std::int32_t>(i);
    Body body;
    body.name = bs.name;
    body.material = bs.material;
    body.fixed = bs.fixed;
    body.fbar = bs.fbar.value_or(default_fbar_mode(spec.materials.at(bs.material)));
    body.first_node = node0;
    body.node_count = static_cast<std::int32_t>(bs.mesh.nodes.size());
    body.first_element = elem0;
    body.element_count = static_cast<std::int32_t>(bs.mesh.elements.size());
    if (body.element_count == 0)
      throw InputError("the mesh has no elements", {}, 0, 0, "bodies." + bs.name + ".mesh");
    add_mesh(m, bs, bi, body);
    set_frequency_factors(m, body);
    set_initial_velocity(m, bs, body);
    add_boundary(m, bi, body);
    m.bodies.push_back(std::move(body));
    node0 += m.bodies.back().node_count;
    elem0 += m.bodies.back().element_count;
  }

  for (const auto& c : spec.constraints) apply_constraint(m, c);
  for (std::int32_t n = 0; n < nn; ++n)
    for (int k = 0; k < 3; ++k)
      if (m.dof_mode[3 * n + k] == 1) m.v[3 * n + k] = 0.0;
  for (const auto& ws : spec.walls) m.walls.push_back(make_wall(ws, spec.contact));
  build_gather_map(m);
  m.x = m.X;
  return m;
}

}  // namespace femdem
