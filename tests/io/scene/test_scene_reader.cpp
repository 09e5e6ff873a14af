// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, whole scenes: unknown sections and top-level keys, TOML syntax errors, a missing
// scene file, the column of a bad value, and the defaults filled into the model and the
// resolved scene. The sections have their own files (test_scene_simulation_materials.cpp,
// test_scene_bodies.cpp, test_scene_walls_contact.cpp, test_scene_overrides.cpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/scene_cases.hpp"

namespace {

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
  {"unknown_top_level_key", 1, R"(titel = "x")", "", "titel", 1, "did you mean 'title'?"},
  {"misplaced_key", 2, "[contact]", "", "simulation", 1, "[simulation] is missing"},
  {"unknown_section", 2, "[simulaton]", "", "simulaton", 2, "did you mean 'simulation'?"},
  {"toml_syntax_error", 3, "end_time = ", "", "", 3, "TOML syntax error"},
  {"unknown_output_field", 0, "", "[output]\nfields = [\"log_strian\"]", "output.fields", 21, "did you mean 'log_strain'?"},
  {"duplicate_output_field", 0, "", "[output]\nfields = [\"log_strain\", \"log_strain\"]", "output.fields", 21, "listed twice"},
  {"unknown_output_key", 0, "", "[output]\nfeilds = []", "output.feilds", 21, "did you mean 'fields'?"},
};
// clang-format on

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  expect_bad_scene(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(SceneReader, MissingSimulationTableAndNoBodies) {
  std::string no_sim;
  for (std::size_t i = 3; i < kBase.size(); ++i) no_sim += kBase[i] + "\n";
  try {
    load_scene(write_file(tmp_dir() / "no_simulation.toml", no_sim));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "simulation");
    EXPECT_NE(std::string(e.what()).find("[simulation] is missing"), std::string::npos);
  }
  std::string no_bodies;
  for (std::size_t i = 0; i < 9; ++i) no_bodies += kBase[i] + "\n";
  try {
    load_scene(write_file(tmp_dir() / "no_bodies.toml", no_bodies));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies");
    EXPECT_NE(std::string(e.what()).find("no bodies"), std::string::npos);
  }
}

TEST(SceneReader, ColumnPointsAtTheValue) {
  const std::string path =
      write_file(tmp_dir() / "column.toml", scene_text(7, "density =   -5", ""));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line, 7);
    EXPECT_EQ(e.column, 13);
  }
}

TEST(SceneReader, MissingSceneFile) {
  const std::string path = (tmp_dir() / "does_not_exist.toml").string();
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, 0);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}
TEST(SceneReader, DefaultsAreFilledIn) {
  const std::string text = R"(
[simulation]
end_time = 2e-3
[[materials]]
name = "rubber"
model = "elastic"
density = 1100
youngs_modulus = 5e6
poisson_ratio = 0.45
[[bodies]]
name = "ball"
material = "rubber"
mesh = { generator = "sphere", radius = 0.05, element_size = 0.025 }
[[walls]]
[[constraints]]
body = "ball"
fix = ["x", "y"]
)";
  const std::string path = write_file(tmp_dir() / "defaults.toml", text);
  const femdem::SceneFile s = load_scene(path);
  EXPECT_EQ(s.path, path);
  EXPECT_EQ(s.stem, "defaults");
  const auto& m = s.model;
  EXPECT_EQ(m.title, "defaults");
  EXPECT_DOUBLE_EQ(m.simulation.end_time, 2e-3);
  EXPECT_DOUBLE_EQ(m.simulation.time_step_safety, 0.0);  // the estimate's default:
  EXPECT_DOUBLE_EQ(m.simulation.safety(), 0.8);          // 0.8 of the assembled estimate
  EXPECT_DOUBLE_EQ(m.simulation.time_step, 0.0);
  EXPECT_DOUBLE_EQ(m.simulation.output_interval, 2e-3 / 50);
  EXPECT_DOUBLE_EQ(m.simulation.history_interval, 2e-3 / 50 / 20);
  EXPECT_EQ(m.simulation.gravity, Vec3::Zero());
  EXPECT_EQ(m.simulation.threads, 0);
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_TRUE(m.materials[0].is<femdem::ElasticParams>());
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_EQ(m.bodies[0].material, 0);
  EXPECT_EQ(m.bodies[0].velocity, Vec3::Zero());
  EXPECT_EQ(m.bodies[0].angular_velocity, Vec3::Zero());
  EXPECT_FALSE(m.bodies[0].fixed);
  EXPECT_FALSE(m.bodies[0].mesh.elements.empty());
  ASSERT_EQ(m.walls.size(), 1u);
  EXPECT_EQ(m.walls[0].name, "wall1");
  EXPECT_EQ(m.walls[0].point, Vec3::Zero());
  EXPECT_EQ(m.walls[0].normal, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(m.walls[0].friction, 0.0);
  EXPECT_DOUBLE_EQ(m.walls[0].penalty_factor, 0.0);
  ASSERT_EQ(m.constraints.size(), 1u);
  EXPECT_EQ(m.constraints[0].body, 0);
  EXPECT_EQ(m.constraints[0].region.kind, femdem::RegionSpec::Kind::All);
  EXPECT_TRUE(m.constraints[0].fix[0] && m.constraints[0].fix[1] && !m.constraints[0].fix[2]);
  EXPECT_FALSE(m.constraints[0].velocity.has_value());
  EXPECT_DOUBLE_EQ(m.contact.penalty_factor, 0.0);  // the automatic stiffness
  EXPECT_NE(s.resolved_toml.find("penalty_factor = \"auto\""), std::string::npos);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.0);

  // The resolved scene holds every default and is itself a valid scene giving the same model.
  for (const char* key : {"output_interval", "history_interval", "time_step_safety", "threads",
                          "penalty_factor", "angular_velocity", "wall1", "region"})
    EXPECT_NE(s.resolved_toml.find(key), std::string::npos) << key;
  const std::string again_path = write_file(tmp_dir() / "defaults_resolved.toml", s.resolved_toml);
  const femdem::SceneFile again = load_scene(again_path);
  EXPECT_EQ(again.resolved_toml, s.resolved_toml);
  EXPECT_EQ(again.model.bodies[0].mesh.nodes, m.bodies[0].mesh.nodes);
}

}  // namespace

// The resolved scene holds the [output] section (run.log shows it, and the digest that ties a
// checkpoint to its scene sees it: a resume must not change what the frames hold).
namespace {
TEST(SceneReader, ResolvedSceneHoldsTheOutputFields) {
  const std::string base = femdem::test::scene_text(0, "");
  const femdem::SceneFile plain = load_scene(write_file(tmp_dir() / "output_plain.toml", base));
  const femdem::SceneFile fields = load_scene(
      write_file(tmp_dir() / "output_fields.toml", base + "[output]\nfields = [\"log_strain\"]\n"));
  EXPECT_NE(fields.resolved_toml.find("[output]"), std::string::npos) << fields.resolved_toml;
  EXPECT_NE(fields.resolved_toml.find("log_strain"), std::string::npos) << fields.resolved_toml;
  EXPECT_NE(fields.resolved_toml, plain.resolved_toml);
  // and reads back the same
  const femdem::SceneFile again =
      load_scene(write_file(tmp_dir() / "output_again.toml", fields.resolved_toml));
  EXPECT_EQ(again.resolved_toml, fields.resolved_toml);
}
}  // namespace
