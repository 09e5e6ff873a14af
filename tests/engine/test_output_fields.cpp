// SPDX-License-Identifier: GPL-3.0-or-later
// The optional results fields (engine/output_fields.hpp) against closed-form values: the Hencky
// strain of a homogeneous stretch and rotation, the nodal average of a uniform stress, the
// contact pressure of a uniform traction (lumped as the wall contact lumps it; rotated; free
// faces zero) and the bodies' centre-of-mass velocities.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/output_fields.hpp"
#include "engine/simulation.hpp"
#include "support/steel_boxes.hpp"

using namespace femdem;

namespace {

Model unit_box_model(int bodies = 1) {
  return build_model(test::steel_boxes(bodies, 3));
}

Eigen::Matrix3d rotation() {
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
}

}  // namespace

TEST(OutputFields, LogStrainOfAStretchAndRotationIsRLnURt) {
  Model m = unit_box_model();
  const Eigen::Matrix3d R = rotation();
  const Eigen::Matrix3d U = Eigen::Vector3d(1.2, 0.9, 1.05).asDiagonal();
  for (int n = 0; n < m.node_count; ++n) {
    const Vec3 X(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    const Vec3 x = R * U * X;
    for (int k = 0; k < 3; ++k) m.x[3 * n + k] = x[k];
  }
  const Eigen::Matrix3d expected =
      R * Eigen::Vector3d(std::log(1.2), std::log(0.9), std::log(1.05)).asDiagonal() *
      R.transpose();
  std::vector<double> e6;
  OutputFields(m).log_strain(m, e6);
  ASSERT_EQ(e6.size(), 6 * m.conn.size());
  const int idx[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  for (std::size_t e = 0; e < m.conn.size(); ++e)
    for (int k = 0; k < 6; ++k)
      ASSERT_NEAR(e6[6 * e + k], expected(idx[k][0], idx[k][1]), 1e-12) << e << " " << k;
}

TEST(OutputFields, NodalStressOfAUniformStressIsThatStress) {
  const Model m = unit_box_model();
  const double s[6] = {1e6, -2e6, 3e6, 4e5, -5e5, 6e5};
  std::vector<double> element(6 * m.conn.size());
  for (std::size_t e = 0; e < m.conn.size(); ++e)
    for (int k = 0; k < 6; ++k) element[6 * e + k] = s[k];
  std::vector<double> nodal;
  OutputFields(m).nodal_stress(m, element, nodal);
  ASSERT_EQ(nodal.size(), 6u * m.node_count);
  for (int n = 0; n < m.node_count; ++n)
    for (int k = 0; k < 6; ++k) ASSERT_NEAR(nodal[6 * n + k], s[k], 1e-9 * std::abs(s[k]));
}

// A uniform pressure p on the face z = 1, as nodal forces lumped by area share (what the wall
// contact gives a flat face pressed evenly: 1/19 of a face's area at each corner, 16/57 at each
// mid-edge node), in a box turned by R: every node of that face reads p, every other node 0.
TEST(OutputFields, ContactPressureOfAUniformTractionOnARotatedBox) {
  Model m = unit_box_model();
  const Eigen::Matrix3d R = rotation();
  for (int n = 0; n < m.node_count; ++n) {
    const Vec3 x = R * Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    for (int k = 0; k < 3; ++k) m.x[3 * n + k] = x[k];
  }
  const double p = 3e7;
  const Vec3 normal = R * Vec3(0, 0, 1);
  std::vector<double> share(m.node_count, 0.0);
  for (const BoundaryFace& f : boundary_faces(m.conn)) {
    const Tet10& el = m.conn[f.element];
    const auto& fl = kTet10Faces[f.face];
    bool top = true;
    for (int k = 0; k < 6; ++k) top = top && std::abs(m.X[3 * el[fl[k]] + 2] - 1.0) < 1e-12;
    if (!top) continue;
    const auto X = [&](int k) { return Vec3(m.X[3 * el[fl[k]]], m.X[3 * el[fl[k]] + 1], 0.0); };
    const double area = 0.5 * std::abs((X(1) - X(0)).cross(X(2) - X(0)).z());
    for (int k = 0; k < 6; ++k) share[el[fl[k]]] += area * (k < 3 ? 1.0 / 19 : 16.0 / 57);
  }
  std::fill(m.f_contact.begin(), m.f_contact.end(), 0.0);
  for (int n = 0; n < m.node_count; ++n)
    for (int k = 0; k < 3; ++k) m.f_contact[3 * n + k] = -p * share[n] * normal[k];
  std::vector<double> pressure;
  OutputFields(m).contact_pressure(m, pressure);
  int on_top = 0;
  for (int n = 0; n < m.node_count; ++n) {
    const bool top = std::abs(m.X[3 * n + 2] - 1.0) < 1e-12;
    const bool edge =
        top && (std::abs(m.X[3 * n]) < 1e-12 || std::abs(m.X[3 * n] - 1) < 1e-12 ||
                std::abs(m.X[3 * n + 1]) < 1e-12 || std::abs(m.X[3 * n + 1] - 1) < 1e-12);
    if (top && !edge) {
      ++on_top;
      EXPECT_NEAR(pressure[n], p, 1e-9 * p) << n;
    } else if (!top) {
      // a node of a side face next to the top one shares faces with it: its value is the
      // area-weighted mean over its faces, between 0 and p; elsewhere 0
      EXPECT_GE(pressure[n], -1e-9 * p);
      EXPECT_LE(pressure[n], p * (1 + 1e-9));
      if (m.X[3 * n + 2] < 0.5) {
        EXPECT_EQ(pressure[n], 0.0) << n;
      }
    }
  }
  EXPECT_EQ(on_top, 5 * 5);  // the interior of the 7 x 7 node grid of the top face
}

TEST(OutputFields, BodyVelocityIsEachBodysCentreOfMassVelocity) {
  Model m = unit_box_model(2);
  // body 0 translates, body 1 spins about its centre and drifts
  for (int n = 0; n < m.node_count; ++n) {
    const Vec3 X(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    const bool second = X.x() > 1.5;
    const Vec3 v =
        second ? Vec3(0, 0, 5).cross(X - Vec3(2.5, 0.5, 0.5)) + Vec3(0, 1, 0) : Vec3(1, 2, 3);
    for (int k = 0; k < 3; ++k) m.v[3 * n + k] = v[k];
  }
  std::vector<double> v;
  OutputFields(m).body_velocity(m, v);
  // a rigid motion's centre-of-mass velocity: w x (X_com - c) + drift, X_com of the lumped masses
  Vec3 moment = Vec3::Zero();
  double mass = 0.0;
  for (int n = 0; n < m.node_count; ++n)
    if (m.X[3 * n] > 1.5) {
      moment += m.mass[n] * Vec3(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
      mass += m.mass[n];
    }
  const Vec3 spun = Vec3(0, 0, 5).cross(moment / mass - Vec3(2.5, 0.5, 0.5)) + Vec3(0, 1, 0);
  for (int n = 0; n < m.node_count; ++n) {
    const bool second = m.X[3 * n] > 1.5;
    const Vec3 expected = second ? spun : Vec3(1, 2, 3);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(v[3 * n + k], expected[k], 1e-12) << n;
  }
}
