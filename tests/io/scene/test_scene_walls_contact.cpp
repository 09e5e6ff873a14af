// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, [[walls]], [[constraints]] (with their regions) and [contact]: bad values name
// file, line and key; explicit values and wall velocity histories are read and echoed.
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
using femdem::test::scene_text;
using femdem::test::tmp_dir;
using femdem::test::write_file;

// clang-format off
const std::vector<BadCase> kBadCases = {
  {"contact_pair_unknown_body", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"bal\"]\nfriction = 0.2", "contact.pairs[0].bodies", 21, "did you mean 'ball'?"},
  {"impact_damping_one", 0, "", "[contact]\nimpact_damping = 1.0", "contact.impact_damping", 21, "[0, 1)"},
  {"contact_pair_same_body", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"ball\"]\nfriction = 0.2", "contact.pairs[0].bodies", 21, "same body twice"},
  {"contact_pair_names_a_wall", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"floor\"]\nfriction = -0.2", "contact.pairs[0].bodies", 21, "unknown body 'floor'"},
  {"duplicate_body_and_wall_name", 15, R"(name = "ball")", "", "walls.ball.name", 15, "duplicate name"},
  {"zero_wall_normal", 16, "normal = [0, 0, 0]", "", "walls.floor.normal", 16, "zero vector"},
  {"negative_wall_friction", 16, "normal = [0, 0, 1]\nfriction = -0.1", "", "walls.floor.friction", 17, "must not be negative"},
  {"wall_rolling_resistance_above_one", 16, "normal = [0, 0, 1]\nrolling_resistance = 1.5", "", "walls.floor.rolling_resistance", 17, "coefficient in [0, 1]"},
  {"wall_bumps_not_a_table", 16, "normal = [0, 0, 1]\nbumps = 3e-3", "", "walls.floor.bumps", 17, "expected a table { diameter = D"},
  {"wall_bumps_without_diameter", 16, "normal = [0, 0, 1]\nbumps = { spacing = 3e-3 }", "", "walls.floor.bumps.diameter", 17, "required value is missing"},
  {"wall_bumps_negative_spacing", 16, "normal = [0, 0, 1]\nbumps = { diameter = 3e-3, spacing = -1e-3 }", "", "walls.floor.bumps.spacing", 17, "must be positive"},
  {"wall_bumps_unknown_key", 16, "normal = [0, 0, 1]\nbumps = { diameter = 3e-3, arrangement = \"square\" }", "", "walls.floor.bumps.arrangement", 17, "unknown key 'arrangement'"},
  {"wall_rolling_resistance_negative", 16, "normal = [0, 0, 1]\nrolling_resistance = -0.1", "", "walls.floor.rolling_resistance", 17, "got -0.1"},
  {"zero_wall_penalty", 16, "normal = [0, 0, 1]\npenalty_factor = 0", "", "walls.floor.penalty_factor", 17, "must be positive"},
  {"wall_history_and_velocity", 16, "normal = [0, 0, 1]\nvelocity = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0]]", "", "walls.floor.velocity_history", 18, "not both"},
  {"wall_history_time_not_increasing", 16, "normal = [0, 0, 1]\nvelocity_history = [\n  [0, 0, 0, 0],\n  [1e-3, 0, 0, 1],\n  [1e-3, 0, 0, 2],\n]", "", "walls.floor.velocity_history", 20, "increase strictly: row 3 has t = 0.001 after t = 0.001"},
  {"wall_history_time_decreasing", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], [2e-3, 0, 0, 1], [1e-3, 0, 0, 2]]", "", "walls.floor.velocity_history", 17, "increase strictly"},
  {"wall_history_not_from_zero", 16, "normal = [0, 0, 1]\nvelocity_history = [[1e-3, 0, 0, 0], [2e-3, 0, 0, 1]]", "", "walls.floor.velocity_history", 17, "first row must be at t = 0"},
  {"wall_history_short_row", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], [1e-3, 0, 1]]", "", "walls.floor.velocity_history", 17, "row 2 must be [t, vx, vy, vz] (4 numbers), got 3"},
  {"wall_history_long_row", 16, "normal = [0, 0, 1]\nvelocity_history = [\n  [0, 0, 0, 0],\n  [1e-3, 0, 0, 1, 5],\n]", "", "walls.floor.velocity_history", 19, "got 5"},
  {"wall_history_row_not_array", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], 1e-3]", "", "walls.floor.velocity_history", 17, "row 2 must be"},
  {"wall_history_string_element", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, \"a\", 0]]", "", "walls.floor.velocity_history", 17, "element 3 is a string"},
  {"wall_history_empty", 16, "normal = [0, 0, 1]\nvelocity_history = []", "", "walls.floor.velocity_history", 17, "non-empty"},
  {"wall_history_not_array", 16, "normal = [0, 0, 1]\nvelocity_history = 1.0", "", "walls.floor.velocity_history", 17, "non-empty array"},
  {"wall_history_misspelt", 16, "normal = [0, 0, 1]\nvelocity_histroy = [[0, 0, 0, 0]]", "", "walls.floor.velocity_histroy", 17, "did you mean 'velocity_history'?"},
  {"unknown_body_in_constraint", 18, R"(body = "bal")", "", "constraints[0].body", 18, "did you mean 'ball'?"},
  {"unknown_fix_component", 19, R"(fix = ["x", "w"])", "", "constraints[0].fix", 19, "unknown component 'w'"},
  {"fix_not_array", 19, R"(fix = "x")", "", "constraints[0].fix", 19, "expected an array"},
  {"fix_and_velocity_empty", 19, "fix = []", "", "constraints[0]", 19, "does nothing"},
  {"no_fix_no_velocity", 19, "# nothing", "", "constraints[0]", 17, "does nothing"},
  {"fix_and_velocity_both", 19, "fix = [\"z\"]\nvelocity = [0, 0, 1]", "", "constraints[0].velocity", 20, "not both"},
  {"region_bad_string", 19, "fix = [\"z\"]\nregion = \"everything\"", "", "constraints[0].region", 20, "unknown region"},
  {"region_box_and_plane", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 0], plane_normal = [0, 0, 1] }", "", "constraints[0].region", 20, "mixes"},
  {"region_box_min_above_max", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 1], box_max = [1, 1, 0] }", "", "constraints[0].region.box_max", 20, "below box_min in z"},
  {"region_box_missing_max", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 0] }", "", "constraints[0].region.box_max", 20, "required"},
  {"region_zero_plane_normal", 19, "fix = [\"z\"]\nregion = { plane_point = [0, 0, 0], plane_normal = [0, 0, 0] }", "", "constraints[0].region.plane_normal", 20, "zero vector"},
  {"region_unknown_key", 19, "fix = [\"z\"]\nregion = { plane_point = [0, 0, 0], plane_normal = [0, 0, 1], tolerence = 1e-9 }", "", "constraints[0].region.tolerence", 20, "did you mean 'tolerance'?"},
  {"contact_negative_penalty", 0, "", "[contact]\npenalty_factor = -1\n", "contact.penalty_factor", 21, "must be positive"},
  {"contact_penalty_not_a_number", 0, "", "[contact]\npenalty_factor = true\n", "contact.penalty_factor", 21, "expected a positive number or \"auto\", got a boolean"},
  {"wall_penalty_unknown_word", 16, "normal = [0, 0, 1]\npenalty_factor = \"automatic\"", "", "walls.floor.penalty_factor", 17, "expected a positive number or \"auto\", got \"automatic\""},
  {"contact_unknown_key", 0, "", "[contact]\nfricton = 0.2\n", "contact.fricton", 21, "did you mean 'friction'?"},
  {"contact_unknown_law", 0, "", "[contact]\nlaw = \"penalty_potentail\"\n", "contact.law", 21, "unknown law 'penalty_potentail' (did you mean 'penalty_potential'?); laws: penalty_potential"},
  {"contact_unknown_wall_law", 0, "", "[contact]\nwall_law = \"hertz\"\n", "contact.wall_law", 21, "unknown law 'hertz'"},
  {"contact_law_not_text", 0, "", "[contact]\nlaw = 3\n", "contact.law", 21, "string"},
};
// clang-format on

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  expect_bad_scene(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(SceneReader, ExplicitValuesAreRead) {
  const std::string extra = R"(
[contact]
penalty_factor = 50
friction = 0.3
)";
  std::string text = scene_text(19,
                                "region = { box_min = [-1, -1, -1], box_max = [1, 1, 0.001] }\n"
                                "velocity = [0, 0, -0.5]",
                                extra);
  // a plane region on a second constraint, and wall values
  text +=
      "[[constraints]]\nbody = \"ball\"\nregion = { plane_point = [0, 0, 0], "
      "plane_normal = [0, 2, 0], tolerance = 1e-6 }\nfix = [\"y\"]\n";
  text +=
      "[[walls]]\nname = \"roof\"\npoint = [0, 0, 1]\nnormal = [0, 0, -3]\nfriction = 0.2\n"
      "penalty_factor = 10\nvelocity = [0, 0, -1]\n";
  // a wall on the automatic stiffness while [contact] sets a factor
  // ... and studded with bumps, their spacing the diameter unless given
  text +=
      "[[walls]]\nname = \"side\"\nnormal = [1, 0, 0]\npenalty_factor = \"auto\"\n"
      "bumps = { diameter = 2e-3 }\n";
  const femdem::SceneFile s = load_scene(write_file(tmp_dir() / "explicit.toml", text));
  const auto& m = s.model;
  EXPECT_EQ(m.title, "base");
  ASSERT_EQ(m.constraints.size(), 2u);
  EXPECT_EQ(m.constraints[0].region.kind, femdem::RegionSpec::Kind::Box);
  EXPECT_EQ(m.constraints[0].region.box_max, Vec3(1, 1, 0.001));
  ASSERT_TRUE(m.constraints[0].velocity.has_value());
  EXPECT_EQ(*m.constraints[0].velocity, Vec3(0, 0, -0.5));
  EXPECT_EQ(m.constraints[1].region.kind, femdem::RegionSpec::Kind::Plane);
  EXPECT_EQ(m.constraints[1].region.plane_normal, Vec3(0, 1, 0));
  EXPECT_DOUBLE_EQ(m.constraints[1].region.tolerance, 1e-6);
  ASSERT_EQ(m.walls.size(), 3u);
  EXPECT_LT(m.walls[2].penalty_factor, 0.0);  // "auto", kept apart from "absent"
  EXPECT_NE(s.resolved_toml.find("penalty_factor = \"auto\""), std::string::npos);
  EXPECT_DOUBLE_EQ(m.walls[2].bump_diameter, 2e-3);
  EXPECT_DOUBLE_EQ(m.walls[2].bump_spacing, 2e-3);
  EXPECT_EQ(m.walls[1].bump_diameter, 0.0);  // a flat wall
  EXPECT_NE(s.resolved_toml.find("bumps = { diameter = 0.002, spacing = 0.002 }"),
            std::string::npos);
  EXPECT_EQ(m.walls[1].normal, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(m.walls[1].penalty_factor, 10.0);
  EXPECT_DOUBLE_EQ(m.walls[1].friction, 0.2);
  EXPECT_EQ(m.walls[1].velocity, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(m.contact.penalty_factor, 50.0);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.3);
  // the laws: the defaults, named in the resolved scene
  EXPECT_EQ(m.contact.law, "penalty_potential");
  EXPECT_EQ(m.contact.wall_law, "penalty");
  EXPECT_NE(s.resolved_toml.find("law = \"penalty_potential\""), std::string::npos);
  EXPECT_NE(s.resolved_toml.find("wall_law = \"penalty\""), std::string::npos);
}

TEST(SceneReader, WallVelocityHistoryIsReadAndEchoed) {
  const std::string text = scene_text(16,
                                      "normal = [0, 0, 1]\n"
                                      "velocity_history = [[0, 0, 0, 0], [1e-3, 0, 0, 0.5],\n"
                                      "                    [2.5e-3, 1, 0, -0.25]]");
  const std::string path = write_file(tmp_dir() / "velocity_history.toml", text);
  const femdem::SceneFile s = load_scene(path);
  ASSERT_EQ(s.model.walls.size(), 1u);
  const auto& h = s.model.walls[0].velocity_history;
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0].time, 0.0);
  EXPECT_EQ(h[0].velocity, Vec3::Zero());
  EXPECT_EQ(h[1].time, 1e-3);
  EXPECT_EQ(h[1].velocity, Vec3(0, 0, 0.5));
  EXPECT_EQ(h[2].time, 2.5e-3);
  EXPECT_EQ(h[2].velocity, Vec3(1, 0, -0.25));
  // The resolved scene holds the history (and no constant velocity) and reads back the same.
  EXPECT_NE(s.resolved_toml.find("velocity_history = [[0"), std::string::npos) << s.resolved_toml;
  const std::size_t walls = s.resolved_toml.find("[[walls]]");
  ASSERT_NE(walls, std::string::npos);
  EXPECT_EQ(s.resolved_toml.find("velocity = ", walls), std::string::npos) << s.resolved_toml;
  const femdem::SceneFile again =
      load_scene(write_file(tmp_dir() / "velocity_history_resolved.toml", s.resolved_toml));
  EXPECT_EQ(again.resolved_toml, s.resolved_toml);
  ASSERT_EQ(again.model.walls[0].velocity_history.size(), 3u);
  EXPECT_EQ(again.model.walls[0].velocity_history[2].velocity, Vec3(1, 0, -0.25));
  // --set replaces it like any value (and one row is enough: a constant velocity)
  const femdem::SceneFile o = load_scene(path, {"walls.floor.velocity_history=[[0, 0, 0, -2]]"});
  ASSERT_EQ(o.model.walls[0].velocity_history.size(), 1u);
  EXPECT_EQ(o.model.walls[0].velocity_history[0].velocity, Vec3(0, 0, -2));
  try {
    load_scene(path, {"walls.floor.velocity=[0, 0, 1]"});
    FAIL() << "velocity and velocity_history together were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "walls.floor.velocity_history");
    EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what();
  }
}

}  // namespace
