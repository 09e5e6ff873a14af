// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/output_fields.hpp"

#include <cmath>

#include "materials/hencky.hpp"

namespace femdem {

namespace {
// a face's area shares of its six nodes, as the wall contact lumps them (HRZ)
constexpr double kFaceShare[6] = {1.0 / 19, 1.0 / 19, 1.0 / 19, 16.0 / 57, 16.0 / 57, 16.0 / 57};
}  // namespace

OutputFields::OutputFields(const Model& m) : faces_(boundary_faces(m.conn)) {
  // boundary faces around each node (CSR), with the node's share of each
  const std::size_t nn = m.X.size() / 3;
  node_face_start_.assign(nn + 1, 0);
  for (const BoundaryFace& f : faces_)
    for (int k = 0; k < 6; ++k)
      ++node_face_start_[static_cast<std::size_t>(m.conn[static_cast<std::size_t>(
                             f.element)][kTet10Faces[static_cast<std::size_t>(f.face)][k]]) +
                         1];
  for (std::size_t n = 0; n < nn; ++n) node_face_start_[n + 1] += node_face_start_[n];
  node_faces_.resize(node_face_start_[nn]);
  node_face_share_.resize(node_face_start_[nn]);
  std::vector<std::size_t> fill(node_face_start_.begin(), node_face_start_.end() - 1);
  for (std::size_t i = 0; i < faces_.size(); ++i)
    for (int k = 0; k < 6; ++k) {
      const auto node = static_cast<std::size_t>(m.conn[static_cast<std::size_t>(
          faces_[i].element)][kTet10Faces[static_cast<std::size_t>(faces_[i].face)][k]]);
      node_faces_[fill[node]] = i;
      node_face_share_[fill[node]++] = kFaceShare[k];
    }
  node_volume_.assign(nn, 0.0);
  for (std::size_t e = 0; e < m.conn.size(); ++e) {
    double v = 0.0;
    for (int g = 0; g < 4; ++g) v += m.gauss_weight[4 * e + g];
    for (std::int32_t n : m.conn[e]) node_volume_[static_cast<std::size_t>(n)] += v;
  }
}

void OutputFields::log_strain(const Model& m, std::vector<double>& strain6) const {
  strain6.assign(6 * m.conn.size(), 0.0);
  for (std::size_t e = 0; e < m.conn.size(); ++e) {
    const Tet10& el = m.conn[e];
    for (int g = 0; g < 4; ++g) {
      const double* dN = m.dNdX.data() + 120 * e + 30 * g;
      double F[3][3] = {};
      for (int a = 0; a < 10; ++a) {
        const double* x = m.x.data() + 3 * static_cast<std::size_t>(el[a]);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) F[i][j] += x[i] * dN[3 * a + j];
      }
      // b = F F^T (xx yy zz xy yz xz)
      auto dot = [&](int i, int j) {
        return F[i][0] * F[j][0] + F[i][1] * F[j][1] + F[i][2] * F[j][2];
      };
      const double b[6] = {dot(0, 0), dot(1, 1), dot(2, 2), dot(0, 1), dot(1, 2), dot(0, 2)};
      const PrincipalStrains p = principal_log_strains(b);
      double s[6];
      assemble_from_principal(p.e, p.n, s);
      for (int k = 0; k < 6; ++k) strain6[6 * e + k] += 0.25 * s[k];
    }
  }
}

void OutputFields::nodal_stress(const Model& m, const std::vector<double>& element_stress6,
                                std::vector<double>& nodal6) const {
  nodal6.assign(6 * node_volume_.size(), 0.0);
  for (std::size_t e = 0; e < m.conn.size(); ++e) {
    double v = 0.0;
    for (int g = 0; g < 4; ++g) v += m.gauss_weight[4 * e + g];
    for (std::int32_t n : m.conn[e])
      for (int k = 0; k < 6; ++k)
        nodal6[6 * static_cast<std::size_t>(n) + k] += v * element_stress6[6 * e + k];
  }
  for (std::size_t n = 0; n < node_volume_.size(); ++n)
    if (node_volume_[n] > 0.0)
      for (int k = 0; k < 6; ++k) nodal6[6 * n + k] /= node_volume_[n];
}

void OutputFields::contact_pressure(const Model& m, std::vector<double>& pressure) const {
  // Nodal forces are not a traction: with lumped contact the corner and mid-edge nodes of a face
  // under a uniform pressure carry forces far from their shares of it. So each boundary face's
  // pressure is its normal force over its area, each of its nodes giving it the share of the
  // node's force that the face has of the node's area facing the same way (the faces around
  // the node weighted by max(0, n_i . n_face): at an edge of the body a force on one side is
  // not spread onto the other); a node then takes the area-weighted mean of its faces' values.
  const std::size_t nn = node_volume_.size(), nf = faces_.size();
  pressure.assign(nn, 0.0);
  face_normal_.resize(3 * nf);
  face_area_.resize(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    const Tet10& el = m.conn[static_cast<std::size_t>(faces_[i].element)];
    const auto& fl = kTet10Faces[static_cast<std::size_t>(faces_[i].face)];
    auto P = [&](int k) {
      const double* x = m.x.data() + 3 * static_cast<std::size_t>(el[fl[k]]);
      return Vec3(x[0], x[1], x[2]);
    };
    const Vec3 a = 0.5 * (P(1) - P(0)).cross(P(2) - P(0));  // current, flat, outward
    face_area_[i] = a.norm();
    const Vec3 n = face_area_[i] > 0.0 ? Vec3(a / face_area_[i]) : Vec3::Zero();
    for (int k = 0; k < 3; ++k) face_normal_[3 * i + k] = n[k];
  }
  weight_.assign(nn, 0.0);
  for (std::size_t j = 0; j < nf; ++j) {
    if (!(face_area_[j] > 0.0)) continue;
    const double* nj = face_normal_.data() + 3 * j;
    const Tet10& el = m.conn[static_cast<std::size_t>(faces_[j].element)];
    const auto& fl = kTet10Faces[static_cast<std::size_t>(faces_[j].face)];
    double p = 0.0;  // -(normal force on the face) / its area
    for (int k = 0; k < 6; ++k) {
      const std::size_t node = static_cast<std::size_t>(el[fl[k]]);
      double facing = 0.0;  // the node's area share facing like face j
      for (std::size_t c = node_face_start_[node]; c < node_face_start_[node + 1]; ++c) {
        const std::size_t i = node_faces_[c];
        const double* ni = face_normal_.data() + 3 * i;
        const double cos_ij = ni[0] * nj[0] + ni[1] * nj[1] + ni[2] * nj[2];
        if (cos_ij > 0.0) facing += node_face_share_[c] * face_area_[i] * cos_ij;
      }
      const double* fc = m.f_contact.data() + 3 * node;
      if (facing > 0.0)
        p -= kFaceShare[k] * face_area_[j] * (fc[0] * nj[0] + fc[1] * nj[1] + fc[2] * nj[2]) /
             facing;
    }
    p /= face_area_[j];
    for (int k = 0; k < 6; ++k) {
      const std::size_t node = static_cast<std::size_t>(el[fl[k]]);
      pressure[node] += face_area_[j] * p;
      weight_[node] += face_area_[j];
    }
  }
  for (std::size_t n = 0; n < nn; ++n)
    if (weight_[n] > 0.0) pressure[n] /= weight_[n];
}

void OutputFields::body_velocity(const Model& m, std::vector<double>& velocity3) const {
  velocity3.assign(3 * node_volume_.size(), 0.0);
  for (const Body& b : m.bodies) {
    Vec3 p = Vec3::Zero();
    double mass = 0.0;
    for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
      const std::size_t i = static_cast<std::size_t>(n);
      p += m.mass[i] * Vec3(m.v[3 * i], m.v[3 * i + 1], m.v[3 * i + 2]);
      mass += m.mass[i];
    }
    const Vec3 v = mass > 0.0 ? Vec3(p / mass) : Vec3::Zero();
    for (std::int32_t n = b.first_node; n < b.first_node + b.node_count; ++n)
      for (int k = 0; k < 3; ++k) velocity3[3 * static_cast<std::size_t>(n) + k] = v[k];
  }
}

}  // namespace femdem
