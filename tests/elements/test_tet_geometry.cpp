// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>

#include "elements/tet_geometry.hpp"
#include "io/mesh/mesh_generators.hpp"

using namespace femdem;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kDeg = 180.0 / kPi;

// A single straight TET10 on the given corners.
Tet10Mesh single(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Tet10Mesh m;
  m.nodes = {a, b, c, d};
  for (const auto& e : kTet10Edges) m.nodes.push_back(0.5 * (m.nodes[e[0]] + m.nodes[e[1]]));
  m.elements.push_back({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  return m;
}

}  // namespace

TEST(TetGeometry, RegularTetrahedron) {
  const double a = 2.0;
  const Vec3 p0(0, 0, 0), p1(a, 0, 0), p2(a / 2, a * std::sqrt(3.0) / 2, 0),
      p3(a / 2, a * std::sqrt(3.0) / 6, a * std::sqrt(2.0 / 3.0));
  EXPECT_NEAR(tet_signed_volume(p0, p1, p2, p3), a * a * a / (6 * std::sqrt(2.0)), 1e-14);
  for (double A : tet_face_areas(p0, p1, p2, p3)) EXPECT_NEAR(A, std::sqrt(3.0) / 4 * a * a, 1e-14);
  EXPECT_NEAR(tet_min_altitude(p0, p1, p2, p3), a * std::sqrt(2.0 / 3.0), 1e-14);
  for (double t : tet_dihedral_angles(p0, p1, p2, p3))
    EXPECT_NEAR(t, std::acos(1.0 / 3) * kDeg, 1e-9);
  EXPECT_NEAR(tet_aspect_ratio(p0, p1, p2, p3), 1.0, 1e-14);
  // Negative orientation flips the sign only.
  EXPECT_NEAR(tet_signed_volume(p0, p2, p1, p3), -a * a * a / (6 * std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(tet_aspect_ratio(p0, p2, p1, p3), 1.0, 1e-14);
}

TEST(TetGeometry, ReferenceTetrahedron) {
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_NEAR(tet_signed_volume(o, x, y, z), 1.0 / 6, 1e-15);
  const auto A = tet_face_areas(o, x, y, z);
  EXPECT_NEAR(A[0], std::sqrt(3.0) / 2, 1e-15);  // opposite the origin
  EXPECT_NEAR(A[1], 0.5, 1e-15);
  EXPECT_NEAR(A[2], 0.5, 1e-15);
  EXPECT_NEAR(A[3], 0.5, 1e-15);
  EXPECT_NEAR(tet_min_altitude(o, x, y, z), 1.0 / std::sqrt(3.0), 1e-15);
  // Edges 0-1, 1-2, 2-0, 0-3, 1-3, 2-3: right angles at the edges through the origin.
  const auto t = tet_dihedral_angles(o, x, y, z);
  const double other = std::acos(1.0 / std::sqrt(3.0)) * kDeg;  // 54.7356
  const std::array<double, 6> expected{90, other, 90, 90, other, other};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(t[i], expected[i], 1e-9) << i;
  // longest edge sqrt(2), smallest altitude 1/sqrt(3): sqrt(6) * sqrt(2/3) = 2
  EXPECT_NEAR(tet_aspect_ratio(o, x, y, z), 2.0, 1e-14);
}

TEST(TetGeometry, SliverAndDegenerate) {
  // Square with a tiny lift: the classic sliver (all edges fine, volume ~0).
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 1e-4), d(0, 1, 0);
  const auto t = tet_dihedral_angles(a, b, c, d);
  EXPECT_LT(*std::min_element(t.begin(), t.end()), 0.1);
  EXPECT_GT(*std::max_element(t.begin(), t.end()), 179.9);
  EXPECT_GT(tet_aspect_ratio(a, b, c, d), 1e3);
  // Exactly flat.
  const Vec3 e(0.5, 0.5, 0);
  EXPECT_EQ(tet_signed_volume(a, b, e, d), 0.0);
  EXPECT_EQ(tet_min_altitude(a, b, e, d), 0.0);
  EXPECT_TRUE(std::isinf(tet_aspect_ratio(a, b, e, d)));
}

TEST(TetGeometry, ScaledJacobianAndCurvedVolume) {
  Tet10Mesh m = single(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(0.5, 0.5, 1));
  EXPECT_NEAR(tet10_min_scaled_jacobian(m, 0), 1.0, 1e-14);
  EXPECT_NEAR(tet10_volume(m, 0), tet_signed_volume(m.nodes[0], m.nodes[1], m.nodes[2], m.nodes[3]),
              1e-14);
  // A mid-edge node moved a little along its edge keeps the element valid, but a node moved
  // past the quarter point folds it (det J at the corner = 1 - 4 s for a shift of s * edge).
  const Vec3 edge = m.nodes[1] - m.nodes[0];
  m.nodes[4] = m.nodes[0] + 0.35 * edge;
  EXPECT_GT(tet10_min_scaled_jacobian(m, 0), 0.0);
  EXPECT_NEAR(tet10_min_scaled_jacobian(m, 0), 1.0 - 4 * 0.15, 1e-12);
  m.nodes[4] = m.nodes[0] + 0.2 * edge;
  EXPECT_LT(tet10_min_scaled_jacobian(m, 0), 0.0);
}

// A degree-2 map applied to the nodes of straight TET10 is represented exactly; its Jacobian
// determinant is cubic, so tet10_volume must give the exact mapped volume.
TEST(TetGeometry, CurvedVolumeIsExactForQuadraticMaps) {
  Tet10Mesh m = generate_box(Vec3(1.0, 2.0, 0.5), 0.25);
  const double c = 0.3, s = 0.2;
  for (Vec3& x : m.nodes) x = Vec3(x[0] + s * x[1] * x[1], x[1], x[2] * (1.0 + c * x[0]));
  // det = 1 + c x over the box: V (1 + c lx / 2)
  double v = 0.0;
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    v += tet10_volume(m, e);
    EXPECT_GT(tet10_min_scaled_jacobian(m, e), 0.0);
  }
  EXPECT_NEAR(v, 1.0 * 2.0 * 0.5 * (1.0 + c * 0.5), 1e-13);
}

TEST(TetGeometry, MeshQualityFindsInvertedElements) {
  Tet10Mesh m = generate_box(Vec3(1, 1, 1), 0.5);
  MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.elements, 48);
  EXPECT_EQ(q.nodes, 125);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_EQ(q.first_bad_element, -1);
  EXPECT_NEAR(q.total_volume, 1.0, 1e-14);
  EXPECT_NEAR(q.min_volume, 1.0 / 48, 1e-15);
  EXPECT_NEAR(q.max_volume, 1.0 / 48, 1e-15);
  EXPECT_NEAR(q.min_edge, 0.5, 1e-15);
  EXPECT_NEAR(q.max_edge, 0.5 * std::sqrt(3.0), 1e-15);
  EXPECT_NE(format_mesh_quality(q).find("no inverted"), std::string::npos);
  for (int e : {7, 30}) {
    Tet10& t = m.elements[e];
    std::swap(t[1], t[2]);
    std::swap(t[4], t[6]);
    std::swap(t[8], t[9]);
  }
  q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 2);
  EXPECT_EQ(q.first_bad_element, 7);
  EXPECT_LT(q.min_volume, 0.0);
  EXPECT_NE(format_mesh_quality(q).find("first: 7"), std::string::npos);
  // A folded quadratic element with a positive corner tet is also reported.
  Tet10Mesh f = generate_box(Vec3(1, 1, 1), 0.5);
  f.nodes[f.elements[3][4]] = f.nodes[f.elements[3][0]];
  q = mesh_quality(f);
  EXPECT_GE(q.bad_elements, 1);
  EXPECT_LT(q.min_scaled_jacobian, 0.0);
}
