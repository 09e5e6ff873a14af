// SPDX-License-Identifier: GPL-3.0-or-later
// Local refinement of the built-in mesh generators (refine_point / refine_size / refine_radius /
// refine_growth): conformity, surface fidelity, element sizes near and far, quality bounds,
// determinism, bad arguments, and the scene keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/mesh_checks.hpp"

using namespace femdem;

namespace {

using test::check_conforming;
using test::Faces;

constexpr double kPi = 3.14159265358979323846;

double mean_edge(const Tet10Mesh& m, std::size_t e) {
  const Tet10& t = m.elements[e];
  double s = 0.0;
  for (const auto& ed : kTet10Edges) s += (m.nodes[t[ed[0]]] - m.nodes[t[ed[1]]]).norm();
  return s / 6.0;
}

Vec3 centroid(const Tet10Mesh& m, std::size_t e) {
  const Tet10& t = m.elements[e];
  return 0.25 * (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]] + m.nodes[t[3]]);
}

// Largest ratio of the mean edge lengths of two face neighbours: the grading.
double worst_neighbour_size_ratio(const Tet10Mesh& m, const Faces& f) {
  double worst = 1.0;
  for (const auto& [a, b] : f.interior) {
    const double ha = mean_edge(m, a), hb = mean_edge(m, b);
    worst = std::max(worst, std::max(ha / hb, hb / ha));
  }
  return worst;
}

MeshRefinement refinement(Vec3 point, double size, double radius,
                          double growth = kDefaultRefineGrowth) {
  MeshRefinement r;
  r.point = point;
  r.size = size;
  r.radius = radius;
  r.growth = growth;
  return r;
}

void expect_input_error(auto&& f, const std::string& text) {
  try {
    f();
    FAIL() << "no InputError, expected: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

// The Hertz sphere of docs/VALIDATION.md section 3 (R 10 mm) refined at its south pole.
// Measured: 13704 elements, 19829 nodes; dihedral angles 20.5 .. 144.6 deg, worst aspect ratio
// 6.12, min scaled Jacobian 0.73 (uniform h = 2.5 mm alone: 3072 elements, 28 .. 120 deg).
TEST(MeshRefinement, HertzSphereIsConformingOnTheSurfaceAndModest) {
  const double R = 0.01, h = 2.5e-3, hf = 0.3e-3, rr = 1e-3;
  const MeshRefinement r = refinement(Vec3(0, 0, -R), hf, rr);
  const Tet10Mesh m = generate_sphere(R, h, r);
  EXPECT_GT(m.elements.size(), 5000u);
  EXPECT_LT(m.elements.size(), 20000u);
  const Faces f = check_conforming(m);
  if (HasFailure()) return;
  // Every node of every boundary face (corners and mid-edge nodes) on the true sphere.
  for (const auto& face : f.boundary)
    for (int n : face) ASSERT_NEAR(m.nodes[n].norm(), R, 1e-12 * R) << "node " << n;
  for (const Vec3& x : m.nodes) EXPECT_LE(x.norm(), R * (1 + 1e-14));
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 19.0);
  EXPECT_LT(q.max_dihedral_deg, 150.0);
  EXPECT_LT(q.max_aspect_ratio, 6.5);
  EXPECT_GT(q.min_scaled_jacobian, 0.7);
  EXPECT_NEAR(q.total_volume, 4.0 / 3.0 * kPi * R * R * R, 1e-4 * R * R * R);
  EXPECT_LT(worst_neighbour_size_ratio(m, f), 2.6);

  // Sizes, as mean corner-to-corner edge lengths: within refine_radius ~ refine_size.
  double near = 0.0;
  int n_near = 0;
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    if ((centroid(m, e) - r.point).norm() < rr) {
      near += mean_edge(m, e);
      ++n_near;
      EXPECT_LT(mean_edge(m, e), 1.2 * hf) << "element " << e;
    }
  ASSERT_GT(n_near, 100);
  EXPECT_NEAR(near / n_near, hf, 0.15 * hf);
  // Far away (the northern half) the mesh is the unrefined grid: same elements, same sizes.
  const Tet10Mesh u = generate_sphere(R, h);
  auto north = [](const Tet10Mesh& mm) {
    double s = 0.0;
    int n = 0;
    for (std::size_t e = 0; e < mm.elements.size(); ++e)
      if (centroid(mm, e).z() > 0.0) s += mean_edge(mm, e), ++n;
    return std::make_pair(n, s / n);
  };
  const auto [n_far, far] = north(m);
  const auto [n_uni, uni] = north(u);
  EXPECT_EQ(n_far, n_uni);
  EXPECT_NEAR(far, uni, 1e-12 * h);
  EXPECT_GT(far, 0.7 * h);
  EXPECT_LT(far, 1.1 * h);
}

// The thesis' elastic-plastic sphere (R 0.1 m, h 0.015 m) refined to 3 mm within 10 mm.
TEST(MeshRefinement, ThesisSphere) {
  const Tet10Mesh m = generate_sphere(0.1, 0.015, refinement(Vec3(0, 0, -0.1), 3e-3, 1e-2));
  EXPECT_LT(m.elements.size(), 50000u);
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 19.0);
  EXPECT_LT(q.max_dihedral_deg, 150.0);
  EXPECT_GT(q.min_scaled_jacobian, 0.7);
  EXPECT_LT(q.min_edge, 3e-3);
}

// Volume error of quadratic geometry, refined or not: e(h) / e(h/2) ~ 16.
TEST(MeshRefinement, VolumeConvergesToTheSphere) {
  const double vs = 4.0 / 3.0 * kPi;
  const double e1 = std::abs(
      test::mesh_volume(generate_sphere(1.0, 0.25, refinement(Vec3(0.3, 0.2, -0.9), 0.05, 0.1))) /
          vs -
      1.0);
  const double e2 = std::abs(
      test::mesh_volume(generate_sphere(1.0, 0.125, refinement(Vec3(0.3, 0.2, -0.9), 0.025, 0.1))) /
          vs -
      1.0);
  EXPECT_LT(e1, 5e-5);
  EXPECT_LT(e2, 3e-6);
  EXPECT_GT(e1 / e2, 8.0) << "rate " << std::log2(e1 / e2);
}

TEST(MeshRefinement, BoxStaysExactWithBoundedShapes) {
  const Vec3 size(1.0, 0.6, 0.5);
  const MeshRefinement r = refinement(Vec3(0.3, 0.6, 0.2), 0.02, 0.05);
  const Tet10Mesh m = generate_box(size, 0.1, r);
  const Faces f = check_conforming(m);
  if (HasFailure()) return;
  EXPECT_NEAR(test::mesh_volume(m), size.prod(), 1e-13);
  for (const auto& face : f.boundary) {
    bool on_plane = false;
    for (int a = 0; a < 3; ++a)
      for (double v : {0.0, size[a]}) {
        bool all = true;
        for (int n : face) all = all && m.nodes[n][a] == v;
        on_plane = on_plane || all;
      }
    EXPECT_TRUE(on_plane);
  }
  // Bisection of Kuhn tetrahedra: three similarity classes, 45 .. 120 degrees for cubic cells.
  const MeshQuality q = mesh_quality(generate_box(Vec3(1, 1, 1), 0.25, r));
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_NEAR(q.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, 120.0, 1e-9);
  EXPECT_LT(q.max_aspect_ratio, 2.4);
  double near = 0.0;
  int n_near = 0;
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    if ((centroid(m, e) - r.point).norm() < r.radius) near += mean_edge(m, e), ++n_near;
  ASSERT_GT(n_near, 10);
  EXPECT_NEAR(near / n_near, r.size, 0.15 * r.size);
}

TEST(MeshRefinement, CylinderOnTheSurfaceAndGood) {
  const double R = 0.5, L = 1.0;
  const MeshRefinement r = refinement(Vec3(0, 0, 0), 0.02, 0.05);  // centre of the bottom face
  const Tet10Mesh m = generate_cylinder(R, L, 0.125, r);
  const Faces f = check_conforming(m);
  if (HasFailure()) return;
  for (const auto& face : f.boundary) {
    bool bottom = true, top = true, mantle = true;
    for (int n : face) {
      const Vec3& x = m.nodes[n];
      bottom = bottom && x[2] == 0.0;
      top = top && x[2] == L;
      mantle = mantle && std::abs(std::hypot(x[0], x[1]) - R) <= 1e-12 * R;
    }
    EXPECT_TRUE(bottom || top || mantle);
  }
  EXPECT_NEAR(test::mesh_volume(m), kPi * R * R * L, 1e-4);
  const MeshQuality q = mesh_quality(m);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_dihedral_deg, 19.0);
  EXPECT_LT(q.max_dihedral_deg, 150.0);
  EXPECT_GT(q.min_scaled_jacobian, 0.75);
  // A point on the rim of the top face.
  const Tet10Mesh rim = generate_cylinder(R, L, 0.125, refinement(Vec3(R, 0, L), 0.02, 0.0));
  check_conforming(rim);
  EXPECT_EQ(mesh_quality(rim).bad_elements, 0);
}

TEST(MeshRefinement, DeterministicAndGradedByGrowth) {
  const MeshRefinement r = refinement(Vec3(0, 0, -1), 0.05, 0.1);
  const Tet10Mesh a = generate_sphere(1.0, 0.25, r), b = generate_sphere(1.0, 0.25, r);
  ASSERT_EQ(a.nodes, b.nodes);
  ASSERT_EQ(a.elements, b.elements);
  // A faster growth gives fewer elements.
  const Tet10Mesh c = generate_sphere(1.0, 0.25, refinement(Vec3(0, 0, -1), 0.05, 0.1, 1.0));
  EXPECT_LT(c.elements.size(), a.elements.size());
  // refine_size = element_size: nothing to refine, the same elements as the uniform grid.
  const Tet10Mesh d = generate_sphere(1.0, 0.25, refinement(Vec3(0, 0, 0), 0.25, 0.0));
  EXPECT_EQ(d.elements.size(), generate_sphere(1.0, 0.25).elements.size());
}

TEST(MeshRefinement, BadArgumentsThrowInputError) {
  const Vec3 p(0, 0, -1);
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 0.0, 0.1)); }, "refine_size");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 0.5, 0.1)); },
                     "refine_size (0.5) must not be larger than element_size");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 0.05, -0.1)); },
                     "refine_radius");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 0.05, 0.1, 0.0)); },
                     "refine_growth");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 0.05, 0.1, 3.0)); },
                     "refine_growth");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(Vec3(0, 0, NAN), 0.05, 0.1)); },
                     "refine_point");
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(Vec3(0, 0, -2), 0.05, 0.5)); },
                     "refine_point is 1 m from the body");
  expect_input_error(
      [&] { generate_box(Vec3(1, 1, 1), 0.25, refinement(Vec3(2, 0, 0), 0.05, 0.5)); },
      "refine_point");
  expect_input_error([&] { generate_cylinder(1, 1, 0.25, refinement(Vec3(0, 0, 1.5), 0.05, 0.4)); },
                     "refine_point");
  // The size grows linearly, so a tiny refine_size alone costs only ~log(h / refine_size)
  // layers of elements; a finer size than element_size / 1e6 is rejected (depth limit).
  EXPECT_LT(generate_sphere(1.0, 0.25, refinement(p, 1e-5, 0.0)).elements.size(), 60000u);
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 1e-7, 0.0)); },
                     "at least element_size / 1e6");
  // Far too many elements: fails at once (the estimate), before refining.
  expect_input_error([&] { generate_sphere(1.0, 0.25, refinement(p, 1e-5, 0.1)); },
                     "refine_size gives about");
}

// ---- The scene keys. ----

namespace fs = std::filesystem;

std::string write_scene(const std::string& name, const std::string& mesh) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "mesh_refinement";
  fs::create_directories(dir);
  const fs::path path = dir / (name + ".toml");
  std::ofstream(path) << "[simulation]\nend_time = 1e-3\n"
                         "[[materials]]\nname = \"steel\"\nmodel = \"elastic\"\ndensity = 7800\n"
                         "youngs_modulus = 200e9\npoisson_ratio = 0.3\n"
                         "[[bodies]]\nname = \"ball\"\nmaterial = \"steel\"\n"
                         "mesh = "
                      << mesh << "\n";
  return path.string();
}

TEST(MeshRefinement, SceneKeysAreRead) {
  const std::string path = write_scene(
      "good", R"({ generator = "sphere", radius = 0.01, element_size = 2.5e-3, )"
              R"(refine_point = [0, 0, -0.01], refine_size = 3e-4, refine_radius = 1e-3 })");
  const SceneFile s = load_scene(path);
  const Tet10Mesh expected =
      generate_sphere(0.01, 2.5e-3, refinement(Vec3(0, 0, -0.01), 3e-4, 1e-3));
  const Tet10Mesh& m = s.model.bodies.at(0).mesh;
  ASSERT_EQ(m.elements, expected.elements);
  ASSERT_EQ(m.nodes.size(), expected.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    ASSERT_LT((m.nodes[i] - expected.nodes[i]).norm(), 1e-15);
  // growth given explicitly; box and cylinder take the keys too.
  EXPECT_NO_THROW(load_scene(write_scene(
      "box", R"({ generator = "box", size = [1, 1, 1], element_size = 0.25, )"
             R"(refine_point = [0.5, 0.5, 0], refine_size = 0.1, refine_growth = 1.0 })")));
  EXPECT_NO_THROW(load_scene(write_scene(
      "cyl", R"({ generator = "cylinder", radius = 1, length = 1, element_size = 0.25, )"
             R"(refine_point = [0, 0, 0], refine_size = 0.1 })")));
}

struct BadKey {
  const char* name;
  const char* mesh;
  const char* key;
  const char* contains;
};

TEST(MeshRefinement, BadSceneKeysNameTheKey) {
  const std::string gen = R"(generator = "sphere", radius = 1.0, element_size = 0.25, )";
  const std::vector<BadKey> cases = {
      {"missing_point", "refine_size = 0.05", "refine_point", "required"},
      {"missing_size", "refine_point = [0, 0, -1]", "refine_size", "required"},
      {"radius_alone", "refine_radius = 0.1", "refine_point", "required"},
      {"size_zero", "refine_point = [0, 0, -1], refine_size = 0", "refine_size", "positive"},
      {"size_text", "refine_point = [0, 0, -1], refine_size = \"fine\"", "refine_size", "number"},
      {"size_above_h", "refine_point = [0, 0, -1], refine_size = 0.5", "refine_size",
       "not be larger than element_size"},
      {"point_two", "refine_point = [0, -1], refine_size = 0.05", "refine_point", "3 numbers"},
      {"radius_negative", "refine_point = [0, 0, -1], refine_size = 0.05, refine_radius = -1",
       "refine_radius", ">= 0"},
      {"growth_zero", "refine_point = [0, 0, -1], refine_size = 0.05, refine_growth = 0",
       "refine_growth", "positive"},
      {"growth_big", "refine_point = [0, 0, -1], refine_size = 0.05, refine_growth = 5",
       "refine_growth", "(0, 2]"},
      {"point_outside", "refine_point = [0, 0, -5], refine_size = 0.05, refine_radius = 1",
       "refine_point", "from the body"},
      {"too_many", "refine_point = [0, 0, -1], refine_size = 1e-3, refine_radius = 0.5",
       "refine_size", "elements"},
      {"too_deep", "refine_point = [0, 0, -1], refine_size = 1e-8", "refine_size",
       "at least element_size / 1e6"},
      {"typo", "refine_point = [0, 0, -1], refine_sise = 0.05", "refine_sise",
       "did you mean 'refine_size'?"},
  };
  for (const BadKey& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write_scene(std::string("bad_") + c.name, "{ " + gen + c.mesh + " }");
    try {
      load_scene(path);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key, std::string("bodies.ball.mesh.") + c.key) << e.describe();
      EXPECT_EQ(e.file, path);
      EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
    }
  }
  // A mesh file cannot be refined: the key is unknown there.
  const std::string path =
      write_scene("bad_file", R"({ file = "part.msh", refine_point = [0, 0, 0] })");
  try {
    load_scene(path);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies.ball.mesh.refine_point") << e.describe();
    EXPECT_NE(std::string(e.what()).find("unknown key"), std::string::npos) << e.what();
  }
}

}  // namespace
