// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "support/mesh_checks.hpp"

using namespace femdem;

namespace {

using test::check_conforming;

constexpr double kPi = 3.14159265358979323846;

void expect_same(const Tet10Mesh& a, const Tet10Mesh& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) ASSERT_EQ(a.nodes[i], b.nodes[i]);
  for (std::size_t i = 0; i < a.elements.size(); ++i) ASSERT_EQ(a.elements[i], b.elements[i]);
}

void expect_input_error(auto&& f, const std::string& text) {
  try {
    f();
    FAIL() << "no InputError, expected: " << text;
  } catch (const InputError& e) {
    EXPECT_TRUE(e.file.empty());
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(MeshGenerators, BoxIsExactConformingAndGood) {
  const Vec3 size(1.0, 0.6, 0.37);
  const Tet10Mesh m = generate_box(size, 0.1);
  // Cells: round(10), round(6), round(3.7) = 4.
  EXPECT_EQ(m.elements.size(), 6u * 10 * 6 * 4);
  EXPECT_EQ(m.nodes.size(), 21u * 13 * 9);
  EXPECT_EQ(box_element_count(size, 0.1), static_cast<std::int64_t>(m.elements.size()));
  const test::Faces topo = check_conforming(m);
  EXPECT_EQ(topo.boundary.size(), 2u * 2 * (10 * 6 + 10 * 4 + 6 * 4));
  EXPECT_NEAR(test::mesh_volume(m), size.prod(), 1e-14);
  Vec3 lo = m.nodes[0], hi = m.nodes[0];
  for (const Vec3& x : m.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  EXPECT_EQ(lo, Vec3::Zero());
  EXPECT_EQ(hi, size);
  // Boundary faces lie in the six planes.
  for (const auto& f : topo.boundary) {
    bool on_plane = false;
    for (int a = 0; a < 3; ++a)
      for (double v : {0.0, size[a]}) {
        bool all = true;
        for (int n : f) all = all && m.nodes[n][a] == v;
        on_plane = on_plane || all;
      }
    EXPECT_TRUE(on_plane);
  }
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 35.0);  // cells are 0.1 x 0.1 x 0.0925
  EXPECT_LT(q.max_dihedral_deg, 95.0);
  EXPECT_LT(q.max_aspect_ratio, 2.5);
  EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-12);
  // Cubic cells: the Kuhn tetrahedra, 45..90 degrees, aspect ratio 2.
  const MeshQuality c = mesh_quality(generate_box(Vec3(1, 1, 1), 0.25));
  EXPECT_NEAR(c.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(c.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_NEAR(c.max_aspect_ratio, 2.0, 1e-9);
}

TEST(MeshGenerators, CoarsestMeshes) {
  // h larger than the body: one cell (box) or one cell per radius.
  const Tet10Mesh b = generate_box(Vec3(1, 2, 3), 10.0);
  EXPECT_EQ(b.elements.size(), 6u);
  check_conforming(b);
  EXPECT_NEAR(test::mesh_volume(b), 6.0, 1e-14);
  const Tet10Mesh c = generate_cylinder(1.0, 0.1, 5.0);
  EXPECT_EQ(c.elements.size(), 6u * 4);
  check_conforming(c);
  const Tet10Mesh s = generate_sphere(1.0, 5.0);
  EXPECT_EQ(s.elements.size(), 6u * 8);
  check_conforming(s);
  EXPECT_NEAR(test::mesh_volume(s), 4.0 / 3.0 * kPi, 0.1);
}

TEST(MeshGenerators, CylinderBoundaryOnSurfaceAndConforming) {
  const double R = 0.4, L = 1.3, h = 0.1;
  const Tet10Mesh m = generate_cylinder(R, L, h);
  EXPECT_EQ(m.elements.size(), 6u * 8 * 8 * 13);
  EXPECT_EQ(cylinder_element_count(R, L, h), static_cast<std::int64_t>(m.elements.size()));
  const test::Faces topo = check_conforming(m);
  std::size_t side = 0;
  for (const auto& f : topo.boundary) {
    bool bottom = true, top = true, mantle = true;
    for (int n : f) {
      const Vec3& x = m.nodes[n];
      bottom = bottom && x[2] == 0.0;
      top = top && x[2] == L;
      mantle = mantle && std::abs(std::hypot(x[0], x[1]) - R) <= 1e-12 * R;
    }
    EXPECT_TRUE(bottom || top || mantle) << "boundary face off the cylinder";
    side += mantle;
  }
  EXPECT_EQ(side, 2u * (4 * 8) * 13);  // perimeter cells x layers x 2 triangles
  // Every node within the cylinder.
  for (const Vec3& x : m.nodes) {
    EXPECT_LE(std::hypot(x[0], x[1]), R * (1 + 1e-14));
    EXPECT_GE(x[2], 0.0);
    EXPECT_LE(x[2], L);
  }
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 30.0);
  EXPECT_LT(q.max_dihedral_deg, 125.0);
  EXPECT_LT(q.max_aspect_ratio, 2.6);
  EXPECT_GT(q.min_scaled_jacobian, 0.9);
}

TEST(MeshGenerators, SphereBoundaryOnSurfaceAndConforming) {
  const double R = 2.5, h = 0.5;
  const Tet10Mesh m = generate_sphere(R, h);
  EXPECT_EQ(m.elements.size(), 6u * 10 * 10 * 10);
  EXPECT_EQ(sphere_element_count(R, h), static_cast<std::int64_t>(m.elements.size()));
  const test::Faces topo = check_conforming(m);
  EXPECT_EQ(topo.boundary.size(), 6u * 10 * 10 * 2);
  for (const auto& f : topo.boundary)
    for (int n : f) EXPECT_NEAR(m.nodes[n].norm(), R, 1e-12 * R) << "node " << n;
  for (const Vec3& x : m.nodes) EXPECT_LE(x.norm(), R * (1 + 1e-14));
  // Symmetric about the centre.
  Vec3 sum = Vec3::Zero();
  for (const Vec3& x : m.nodes) sum += x;
  EXPECT_LT(sum.norm() / m.nodes.size(), 1e-14 * R);
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 28.0);
  EXPECT_LT(q.max_dihedral_deg, 120.0);
  EXPECT_LT(q.max_aspect_ratio, 2.8);
  EXPECT_GT(q.min_scaled_jacobian, 0.75);
}

// Volume error e(h) and e(h/2): quadratic geometry with mid-edge nodes on the true surface.
// Measured: sphere R = 1: 2.3e-5 (h = 0.25), 1.5e-6 (0.125); cylinder R = 1, L = 3: 3.1e-6,
// 1.9e-7 -- rate 4. Straight (chordal) boundary edges would give rate 2 and errors ~1e-2.
TEST(MeshGenerators, VolumeConvergesAtQuadraticGeometryRate) {
  const double vs = 4.0 / 3.0 * kPi;
  const double es1 = std::abs(test::mesh_volume(generate_sphere(1.0, 0.25)) / vs - 1.0);
  const double es2 = std::abs(test::mesh_volume(generate_sphere(1.0, 0.125)) / vs - 1.0);
  EXPECT_LT(es1, 5e-5);
  EXPECT_LT(es2, 3e-6);
  EXPECT_GT(es1 / es2, 8.0) << "rate " << std::log2(es1 / es2);
  const double vc = kPi * 3.0;
  const double ec1 = std::abs(test::mesh_volume(generate_cylinder(1.0, 3.0, 0.25)) / vc - 1.0);
  const double ec2 = std::abs(test::mesh_volume(generate_cylinder(1.0, 3.0, 0.125)) / vc - 1.0);
  EXPECT_LT(ec1, 1e-5);
  EXPECT_LT(ec2, 5e-7);
  EXPECT_GT(ec1 / ec2, 8.0) << "rate " << std::log2(ec1 / ec2);
}

TEST(MeshGenerators, Deterministic) {
  expect_same(generate_sphere(1.0, 0.3), generate_sphere(1.0, 0.3));
  expect_same(generate_cylinder(1.0, 2.0, 0.3), generate_cylinder(1.0, 2.0, 0.3));
  expect_same(generate_box(Vec3(1, 2, 3), 0.3), generate_box(Vec3(1, 2, 3), 0.3));
}

TEST(MeshGenerators, BadArgumentsThrowInputError) {
  expect_input_error([] { generate_box(Vec3(1, 0, 1), 0.1); }, "size");
  expect_input_error([] { generate_box(Vec3(1, 1, 1), -0.1); }, "element_size");
  expect_input_error([] { generate_box(Vec3(1, NAN, 1), 0.1); }, "size");
  expect_input_error([] { generate_cylinder(0.0, 1.0, 0.1); }, "radius");
  expect_input_error([] { generate_cylinder(1.0, -1.0, 0.1); }, "length");
  expect_input_error([] { generate_cylinder(1.0, 1.0, INFINITY); }, "element_size");
  expect_input_error([] { generate_sphere(-1.0, 0.1); }, "radius");
  expect_input_error([] { generate_sphere(1.0, 0.0); }, "element_size");
  // 6 * 1000^3 elements.
  expect_input_error([] { generate_box(Vec3(1, 1, 1), 1e-3); }, "6e+09 elements");
  expect_input_error([] { generate_sphere(1.0, 1e-3); }, "elements");
  expect_input_error([] { generate_cylinder(1.0, 1e9, 1.0); }, "elements");
  EXPECT_THROW(sphere_element_count(1.0, 1e-6), InputError);
}
