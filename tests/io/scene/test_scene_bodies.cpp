// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, [[bodies]] and their meshes: bad bodies and mesh sources name file, line and
// key (CAD and gmsh files included), relative mesh paths, rotation and position, gmsh physical
// volumes as bodies and physical surfaces and points as the node sets of constraints.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/scene_cases.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::InputError;
using femdem::load_scene;
using femdem::Vec3;
using femdem::test::BadCase;
using femdem::test::BadScene;
using femdem::test::expect_bad_scene;
using femdem::test::kBase;
using femdem::test::scene_text;
using femdem::test::tmp_dir;
using femdem::test::write_file;

// clang-format off
const std::vector<BadCase> kBadCases = {
  {"bad_fbar", 13, "mesh = { generator = \"box\", size = [0.02, 0.02, 0.02], element_size = 0.01 }\nfbar = \"sometimes\"", "", "bodies.ball.fbar", 14, "volume_average"},
  {"unknown_material_in_body", 12, R"(material = "stel")", "", "bodies.ball.material", 12, "did you mean 'steel'?"},
  {"missing_body_material", 12, "# no material", "", "bodies.ball.material", 10, "required"},
  {"missing_mesh", 13, "fixed = false", "", "bodies.ball.mesh", 10, "required"},
  {"mesh_not_a_table", 13, R"(mesh = "ball.msh")", "", "bodies.ball.mesh", 13, "expected a table"},
  {"body_name_with_dot", 11, R"(name = "my.ball")", "", "bodies.my.ball.name", 11, "names may contain only"},
  {"body_unknown_key", 13, kBase[12] + "\nvelocty = [0, 0, 1]", "", "bodies.ball.velocty", 14, "did you mean 'velocity'?"},
  {"body_velocity_two_components", 13, kBase[12] + "\nvelocity = [0, 1]", "", "bodies.ball.velocity", 14, "3 numbers"},
  {"body_velocity_string_element", 13, kBase[12] + "\nvelocity = [0, \"a\", 1]", "", "bodies.ball.velocity", 14, "element 2"},
  {"body_fixed_not_bool", 13, kBase[12] + "\nfixed = \"yes\"", "", "bodies.ball.fixed", 14, "true or false"},
  {"sphere_negative_radius", 13, R"(mesh = { generator = "sphere", radius = -1.0, element_size = 0.01 })", "", "bodies.ball.mesh.radius", 13, "must be positive"},
  {"cylinder_missing_length", 13, R"(mesh = { generator = "cylinder", radius = 0.01, element_size = 0.01 })", "", "bodies.ball.mesh.length", 13, "required"},
  {"box_size_two_components", 13, R"(mesh = { generator = "box", size = [1, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "3 numbers"},
  {"box_size_zero", 13, R"(mesh = { generator = "box", size = [1, 0, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "positive"},
  {"element_size_zero", 13, R"(mesh = { generator = "box", size = [1, 1, 1], element_size = 0 })", "", "bodies.ball.mesh.element_size", 13, "must be positive"},
  {"element_size_too_small", 13, R"(mesh = { generator = "box", size = [1, 1, 1], element_size = 1e-5 })", "", "bodies.ball.mesh.element_size", 13, "elements"},
  {"unknown_generator", 13, R"(mesh = { generator = "spere", radius = 1, element_size = 0.5 })", "", "bodies.ball.mesh.generator", 13, "did you mean 'sphere'?"},
  {"generator_wrong_key", 13, R"(mesh = { generator = "sphere", size = [1, 1, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "unknown key"},
  {"generator_and_file", 13, R"(mesh = { generator = "sphere", file = "a.msh", radius = 1.0, element_size = 0.5 })", "", "bodies.ball.mesh", 13, "not both"},
  {"mesh_without_source", 13, R"(mesh = { element_size = 0.5 })", "", "bodies.ball.mesh", 13, "needs 'generator'"},
  {"missing_mesh_file", 13, R"(mesh = { file = "no_such_mesh.msh" })", "", "bodies.ball.mesh.file", 13, "does not exist"},
  {"unsupported_mesh_type", 13, R"(mesh = { file = "mesh.xyz" })", "", "bodies.ball.mesh.file", 13, "unsupported mesh file type"},
  {"msh_with_element_size", 13, R"(mesh = { file = "mesh.msh", element_size = 0.1 })", "", "bodies.ball.mesh.element_size", 13, "unknown key"},
};
// clang-format on

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  expect_bad_scene(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

// CAD meshing itself is tested in test_cad_mesh.cpp; here only that its errors carry the
// scene's file, line and key.
TEST(SceneReader, CadMeshErrorsNameTheScenesKey) {
  write_file(tmp_dir() / "cad" / "part.stl", "solid part\nendsolid part\n");
  const std::string path =
      write_file(tmp_dir() / "cad" / "scene.toml",
                 scene_text(13, R"(mesh = { file = "part.stl", element_size = 0.01 })"));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies.ball.mesh.file");
    EXPECT_EQ(e.line, 13);
    EXPECT_NE(std::string(e.what()).find("cannot mesh the surface"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("part.stl"), std::string::npos) << e.what();
  }
}

// Two TET4 elements sharing a face (gmsh 2.2 ASCII); the second one listed with the given
// corner order.
std::string two_tet4_msh(const std::string& second) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
         "5 1 1 1\n$EndNodes\n$Elements\n2\n1 4 2 0 1 1 2 3 4\n2 4 2 0 1 " +
         second + "\n$EndElements\n";
}

TEST(SceneReader, InvertedMeshElementIsReportedWithTheScenesKey) {
  write_file(tmp_dir() / "inverted" / "bad.msh", two_tet4_msh("3 2 4 5"));
  const std::string path = write_file(tmp_dir() / "inverted" / "scene.toml",
                                      scene_text(13, R"(mesh = { file = "bad.msh" })"));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    SCOPED_TRACE(e.describe());
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.key, "bodies.ball.mesh.file");
    EXPECT_EQ(e.line, 13);
  }
}

TEST(SceneReader, RelativeMeshPathIsResolvedAgainstTheScenesFolder) {
  write_file(tmp_dir() / "relative" / "meshes" / "two.msh", two_tet4_msh("2 3 4 5"));
  const std::string path = write_file(tmp_dir() / "relative" / "scene.toml",
                                      scene_text(13, R"(mesh = { file = "meshes/two.msh" })"));
  // From another working directory, so only the scene's folder can make the path work.
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());
  femdem::SceneFile s;
  EXPECT_NO_THROW(s = load_scene(path));
  fs::current_path(cwd);
  ASSERT_EQ(s.model.bodies.size(), 1u);
  EXPECT_EQ(s.model.bodies[0].mesh.elements.size(), 2u);
  EXPECT_EQ(s.model.bodies[0].mesh.nodes.size(), 5u + 9u);  // TET4 promoted: 9 edges
}
TEST(SceneReader, RotationThenPositionPlaceTheGeneratedMesh) {
  const Vec3 size(0.02, 0.04, 0.06), pos(1, 2, 3);
  const double h = 0.02;
  const femdem::Tet10Mesh ref = femdem::generate_box(size, h);
  struct Case {
    std::string rotation;
    // the expected image of a reference point before the translation
    Vec3 (*turn)(const Vec3&);
  };
  const std::vector<Case> cases = {
      {"[0, 0, 90]", [](const Vec3& p) { return Vec3(-p.y(), p.x(), p.z()); }},
      {"[90, 0, 0]", [](const Vec3& p) { return Vec3(p.x(), -p.z(), p.y()); }},
      {"[0, 90, 0]", [](const Vec3& p) { return Vec3(p.z(), p.y(), -p.x()); }},
      // about x first, then about z: (x, y, z) -> (x, -z, y) -> (z, x, y)
      {"[90, 0, 90]", [](const Vec3& p) { return Vec3(p.z(), p.x(), p.y()); }},
  };
  int i = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.rotation);
    const std::string mesh_line =
        R"(mesh = { generator = "box", size = [0.02, 0.04, 0.06], element_size = 0.02 })";
    const std::string path =
        write_file(tmp_dir() / ("rotation" + std::to_string(i++) + ".toml"),
                   scene_text(13, mesh_line + "\nposition = [1, 2, 3]\nrotation = " + c.rotation));
    const femdem::SceneFile s = load_scene(path);
    const auto& mesh = s.model.bodies[0].mesh;
    ASSERT_EQ(mesh.nodes.size(), ref.nodes.size());
    ASSERT_EQ(mesh.elements, ref.elements);
    double worst = 0.0;
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
      worst = std::max(worst, (mesh.nodes[n] - (c.turn(ref.nodes[n]) + pos)).norm());
    EXPECT_LT(worst, 1e-12);
  }
}

// Two bodies from the one gmsh file with two physical volumes (tests/data/gmsh/two_blocks.geo),
// each selected by `physical`; a constraint on the physical surface "left_bottom".
std::string two_blocks_scene(const std::string& left_mesh, const std::string& region) {
  const std::string file = std::string(FEMDEM_SOURCE_DIR) + "/tests/data/gmsh/two_blocks_bin41.msh";
  return "[simulation]\nend_time = 1e-3\n"
         "[[materials]]\nname = \"steel\"\nmodel = \"elastic\"\ndensity = 7800\n"
         "youngs_modulus = 200e9\npoisson_ratio = 0.3\n"
         "[[bodies]]\nname = \"a\"\nmaterial = \"steel\"\nmesh = { file = \"" +
         file + "\"" + left_mesh +
         " }\n"
         "[[bodies]]\nname = \"b\"\nmaterial = \"steel\"\nmesh = { file = \"" +
         file +
         "\", physical = \"right\" }\n"
         "[[constraints]]\nbody = \"a\"\nregion = " +
         region + "\nfix = [\"x\", \"y\", \"z\"]\n";
}

TEST(SceneReader, GmshPhysicalVolumesAreBodiesAndSurfacesNodeSets) {
  const femdem::SceneFile s = load_scene(
      write_file(tmp_dir() / "physical.toml",
                 two_blocks_scene(", physical = \"left\"", R"({ physical = "left_bottom" })")));
  ASSERT_EQ(s.model.bodies.size(), 2u);
  for (const auto& [body, x0] : {std::pair{0, 0.0}, std::pair{1, 2.0}}) {
    const femdem::Tet10Mesh& m = s.model.bodies[static_cast<std::size_t>(body)].mesh;
    EXPECT_FALSE(m.elements.empty());
    for (const Vec3& p : m.nodes) {
      EXPECT_GE(p.x(), x0 - 1e-9);
      EXPECT_LE(p.x(), x0 + 1 + 1e-9);
    }
  }
  ASSERT_EQ(s.model.constraints.size(), 1u);
  const femdem::RegionSpec& r = s.model.constraints[0].region;
  EXPECT_EQ(r.kind, femdem::RegionSpec::Kind::Nodes);
  EXPECT_EQ(r.node_set, "left_bottom");
  // exactly the left body's nodes on z = 0
  const femdem::Tet10Mesh& a = s.model.bodies[0].mesh;
  std::vector<std::int32_t> on_bottom;
  for (std::size_t n = 0; n < a.nodes.size(); ++n)
    if (std::abs(a.nodes[n].z()) < 1e-12) on_bottom.push_back(static_cast<std::int32_t>(n));
  EXPECT_EQ(r.nodes, on_bottom);
}

TEST(SceneReader, GmshFileWithSeveralVolumesNeedsOneChosen) {
  const auto message = [](const std::string& name, const std::string& left,
                          const std::string& region, const std::string& key) {
    try {
      load_scene(write_file(tmp_dir() / (name + ".toml"), two_blocks_scene(left, region)));
      ADD_FAILURE() << name << ": no InputError";
      return std::string();
    } catch (const InputError& e) {
      EXPECT_EQ(e.key, key) << e.what();
      EXPECT_GT(e.line, 0) << e.what();
      return std::string(e.what());
    }
  };
  EXPECT_NE(message("no_volume", "", R"("all")", "bodies.a.mesh.file")
                .find("holds 2 physical volumes (left, right): choose"),
            std::string::npos);
  EXPECT_NE(message("typo_volume", ", physical = \"lft\"", R"("all")", "bodies.a.mesh.physical")
                .find("did you mean 'left'?"),
            std::string::npos);
  const std::string sets =
      message("typo_set", ", physical = \"left\"", R"({ physical = "right_top" })",
              "constraints[0].region.physical");
  EXPECT_NE(sets.find("body 'a' has no node set 'right_top'"), std::string::npos) << sets;
  EXPECT_NE(sets.find("its node sets: left_top_corner, left_bottom"), std::string::npos) << sets;
}

// SceneReadLimits: a mesh past the reading's cap is an input error on its element_size, before
// it is made (kBase's box: 0.02 m at 0.01 m is 2 x 2 x 2 cells of 6 tetrahedra = 48 elements).
TEST(SceneReader, MeshElementCapRefusesBeforeMeshing) {
  const std::string path = write_file(tmp_dir() / "capped.toml", scene_text(0, ""));
  EXPECT_NO_THROW(load_scene(path, {}, {.max_mesh_elements = 48}));
  try {
    load_scene(path, {}, {.max_mesh_elements = 47});
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies.ball.mesh.element_size");
    EXPECT_NE(std::string(e.what()).find("up to 48 elements, more than this reading allows (47)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
