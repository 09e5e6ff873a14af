// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, --set overrides: arrays of tables addressed by name, values read as TOML or as
// bare strings, and bad overrides named in the error.
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
using femdem::test::scene_text;
using femdem::test::tmp_dir;
using femdem::test::write_file;

TEST(SceneReader, OverridesAddressArraysOfTablesByName) {
  const std::string path = write_file(tmp_dir() / "overrides.toml", scene_text(0, ""));
  const femdem::SceneFile s =
      load_scene(path, {"bodies.ball.velocity=[0,0,-5.4]", "materials.steel.density=7000",
                        "simulation.end_time=2e-3", "simulation.threads=2", "contact.friction=0.25",
                        "walls.floor.normal = [0, 1, 0]", "title=Hello world",
                        "bodies.ball.angular_velocity=[0, 0, 10]"});
  const auto& m = s.model;
  EXPECT_EQ(m.bodies[0].velocity, Vec3(0, 0, -5.4));
  EXPECT_EQ(m.bodies[0].angular_velocity, Vec3(0, 0, 10));
  EXPECT_DOUBLE_EQ(m.materials[0].density, 7000.0);
  EXPECT_DOUBLE_EQ(m.simulation.end_time, 2e-3);
  EXPECT_DOUBLE_EQ(m.simulation.output_interval, 2e-3 / 50);  // default follows the override
  EXPECT_EQ(m.simulation.threads, 2);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.25);
  EXPECT_EQ(m.walls[0].normal, Vec3(0, 1, 0));
  EXPECT_EQ(m.title, "Hello world");  // not TOML: taken as a bare string
  EXPECT_NE(s.resolved_toml.find("-5.4"), std::string::npos);
}

TEST(SceneReader, BadOverridesNameTheOverride) {
  const std::string path = write_file(tmp_dir() / "bad_overrides.toml", scene_text(0, ""));
  struct Case {
    std::string set, key, contains;
  };
  const std::vector<Case> cases = {
      {"bodies.bal.velocity=[0,0,1]", "bodies.bal.velocity", "did you mean 'ball'?"},
      {"simulation.end_time=-1", "simulation.end_time", "must be positive"},
      {"simulation.end_tme=1", "simulation.end_tme", "did you mean 'end_time'?"},
      {"bodies.ball.velocity=[0,0]", "bodies.ball.velocity", "3 numbers"},
      {"materials.steel.yield_stress=350e6", "materials.steel.yield_stress", "unknown key"},
      {"simulation.end_time.x=1", "simulation.end_time.x", "not a table"},
      {"simulation", "simulation", "expected KEY=VALUE"},
      {"bodies.ball=1", "bodies.ball", "cannot replace a whole entry"},
      {"simulation..end_time=1", "simulation..end_time", "malformed key"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.set);
    try {
      load_scene(path, {c.set});
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key, c.key);
      EXPECT_EQ(e.line, 0);
      EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--set " + c.set), std::string::npos) << e.what();
    }
  }
}

}  // namespace
