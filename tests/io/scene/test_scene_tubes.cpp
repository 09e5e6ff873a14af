// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, [[tubes]]: a tube becomes `sides` bounded, thin walls named <name>_k around its
// axis with the tube's motion; the resolved scene keeps the tube (not its walls) and reads back
// the same; bad values name file, line and key.
#include <gtest/gtest.h>

#include <cmath>
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

// the base scene ends at line 19; a [[tubes]] block appended starts at line 20
const std::string kTube = "[[tubes]]\nname = \"tube\"\ncentre = [0, 0, 0]\nradius = 0.01\n";

// clang-format off
const std::vector<BadCase> kBadCases = {
  {"tube_without_centre", 0, "", "[[tubes]]\nname = \"tube\"\nradius = 0.01\nheight = 0.05", "tubes.tube.centre", 20, "required value is missing"},
  {"tube_without_height", 0, "", kTube, "tubes.tube.height", 20, "required value is missing"},
  {"tube_zero_radius", 0, "", "[[tubes]]\nname = \"tube\"\ncentre = [0, 0, 0]\nradius = 0\nheight = 0.05", "tubes.tube.radius", 23, "must be positive, got 0"},
  {"tube_two_sides", 0, "", kTube + "height = 0.05\nsides = 2", "tubes.tube.sides", 25, "must be an integer in [3, 1024], got 2"},
  {"tube_zero_axis", 0, "", kTube + "height = 0.05\naxis = [0, 0, 0]", "tubes.tube.axis", 25, "zero vector"},
  {"tube_negative_thickness", 0, "", kTube + "height = 0.05\nthickness = -1e-3", "tubes.tube.thickness", 25, "must be positive"},
  {"tube_negative_friction", 0, "", kTube + "height = 0.05\nfriction = -0.1", "tubes.tube.friction", 25, "must not be negative"},
  {"tube_velocity_and_history", 0, "", kTube + "height = 0.05\nvelocity = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 1]]", "tubes.tube.velocity_history", 26, "not both"},
  {"tube_history_not_from_zero", 0, "", kTube + "height = 0.05\nvelocity_history = [[1e-3, 0, 0, 1]]", "tubes.tube.velocity_history", 25, "first row must be at t = 0"},
  {"tube_unknown_key", 0, "", kTube + "height = 0.05\nthicknes = 1e-3", "tubes.tube.thicknes", 25, "did you mean 'thickness'?"},
  {"tube_named_as_a_wall", 0, "", "[[tubes]]\nname = \"floor\"\ncentre = [0, 0, 0]\nradius = 0.01\nheight = 0.05", "tubes.floor.name", 21, "duplicate name"},
  {"tube_wall_named_as_a_wall", 15, "name = \"tube_3\"", kTube + "height = 0.05", "tubes.tube.name", 21, "makes walls named tube_1 ... tube_24, but 'tube_3' is already the name of a body or wall"},
};
// clang-format on

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  expect_bad_scene(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(SceneReader, TubeBecomesBoundedThinWallsThatMoveTogether) {
  const std::string text = scene_text(0, "",
                                      "[[tubes]]\n"
                                      "name = \"tube\"\n"
                                      "centre = [0.1, 0.2, 0.3]\n"
                                      "radius = 0.01\n"
                                      "sides = 4\n"
                                      "height = 0.05\n"
                                      "thickness = 2e-3\n"
                                      "friction = 0.2\n"
                                      "velocity_history = [[0, 0, 0, 0], [1e-3, 0, 0, 0.25]]\n");
  const std::string path = write_file(tmp_dir() / "tube.toml", text);
  const femdem::SceneFile s = load_scene(path);
  ASSERT_EQ(s.model.walls.size(), 5u);  // the floor and four sides
  const Vec3 centre(0.1, 0.2, 0.3);
  // side k faces the axis from the direction at 90 (k - 1) degrees from x, about z
  const Vec3 out[4] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
  for (int k = 0; k < 4; ++k) {
    const femdem::WallSpec& w = s.model.walls[1 + k];
    EXPECT_EQ(w.name, "tube_" + std::to_string(k + 1));
    EXPECT_LT((w.normal + out[k]).norm(), 1e-15);
    EXPECT_NEAR((w.point - centre).dot(out[k]), 0.01, 1e-15);  // the inscribed radius
    EXPECT_TRUE(w.bounded);
    EXPECT_LT((w.bound_axis - Vec3(0, 0, 1)).norm(), 1e-15);
    EXPECT_DOUBLE_EQ(w.bound_min, 0.3);   // from the tube's lower end ...
    EXPECT_DOUBLE_EQ(w.bound_max, 0.35);  // ... to its upper end, along the axis
    EXPECT_EQ(w.thickness, 2e-3);
    EXPECT_EQ(w.friction, 0.2);
    ASSERT_EQ(w.velocity_history.size(), 2u);
    EXPECT_EQ(w.velocity_history[1].velocity, Vec3(0, 0, 0.25));
  }
  EXPECT_EQ(s.model.walls[0].thickness, HUGE_VAL);  // a plain wall is a half-space
  // the resolved scene keeps the tube (with its defaults) and not its walls, and reads back
  EXPECT_NE(s.resolved_toml.find("[[tubes]]"), std::string::npos) << s.resolved_toml;
  EXPECT_EQ(s.resolved_toml.find("tube_1"), std::string::npos) << s.resolved_toml;
  const femdem::SceneFile again =
      load_scene(write_file(tmp_dir() / "tube_resolved.toml", s.resolved_toml));
  EXPECT_EQ(again.resolved_toml, s.resolved_toml);
  ASSERT_EQ(again.model.walls.size(), 5u);
  // --set reaches a tube like any entry; the default thickness is a fiftieth of the radius
  const femdem::SceneFile o = load_scene(
      path, {"tubes.tube.radius=0.02", "tubes.tube.sides=6", "tubes.tube.thickness=4e-4"});
  ASSERT_EQ(o.model.walls.size(), 7u);
  EXPECT_NEAR((o.model.walls[1].point - centre).norm(), 0.02, 1e-15);
  const femdem::SceneFile d = load_scene(
      write_file(tmp_dir() / "tube_default.toml", scene_text(0, "", kTube + "height = 0.05\n")));
  ASSERT_EQ(d.model.walls.size(), 25u);
  EXPECT_DOUBLE_EQ(d.model.walls[1].thickness, 0.02 * 0.01);
  EXPECT_TRUE(d.model.walls[1].velocity_history.empty());
}

}  // namespace
