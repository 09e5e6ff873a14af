// SPDX-License-Identifier: GPL-3.0-or-later
// Inputs that used to hang, crash or lie (issue 20): a schedule of absurd size is refused by
// `check` and `run` alike with its bound, quickly; --threads is bounded like the scene key; a
// fixed step far above the stable one stops on the energy balance (exit 3, at its default 25 %)
// instead of ending "completed" with a 99.6 % error.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_command.hpp"
#include "support/steel_ball_scene.hpp"

namespace femdem::test {
namespace {

namespace fs = std::filesystem;

std::string scene() {
  return std::string(FEMDEM_SOURCE_DIR) + "/scenes/sphere_drop.toml";
}

fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "hostile" / name;
  fs::remove_all(d);
  return d;
}

struct Timed {
  CommandResult result;
  double seconds = 0.0;
};

Timed femdem(const std::string& args) {
  const auto t0 = std::chrono::steady_clock::now();
  Timed t{run_command("timeout 60 '" + std::string(FEMDEM_EXE) + "' " + args), 0.0};
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

TEST(HostileInput, AnAbsurdScheduleIsRefusedWithItsBoundByCheckAndRun) {
  const struct {
    std::string set, message;
  } cases[] = {
      {"simulation.output_interval=1e-30",
       "simulation.output_interval: output_interval = 1e-30 s gives 8e+25 frames over end_time = "
       "8e-05 s, more than the 1e+05 a run may write"},
      {"simulation.history_interval=1e-30",
       "simulation.history_interval: history_interval = 1e-30 s gives 8e+25 rows over end_time = "
       "8e-05 s, more than the 1e+08 a run may write"},
      {"simulation.end_time=1e300", "simulation.end_time: must be at most 1e+06 s, got 1e+300"},
  };
  for (const auto& c : cases)
    for (const std::string command : {"check", "run"}) {
      SCOPED_TRACE(command + " --set " + c.set);
      const fs::path out = out_dir("schedule");
      const Timed t =
          femdem(command + " '" + scene() + "' --set " + c.set +
                 (command == "run" ? " --quiet --out '" + out.string() + "'" : std::string()));
      EXPECT_EQ(t.result.code, 2) << t.result.output;
      EXPECT_NE(t.result.output.find(c.message), std::string::npos) << t.result.output;
      EXPECT_LT(t.seconds, 5.0);
      EXPECT_FALSE(fs::exists(out));
    }
}

TEST(HostileInput, ThreadsAreBoundedOnTheCommandLineAsInTheScene) {
  for (const std::string value : {"100000", "abc", "-1"}) {
    SCOPED_TRACE(value);
    const fs::path out = out_dir("threads");
    const Timed t = femdem("run '" + scene() + "' --quiet --threads " + value + " --out '" +
                           out.string() + "'");
    EXPECT_EQ(t.result.code, 2) << t.result.output;
    EXPECT_NE(t.result.output.find("--threads: Value " + value + " not in range 0 to 4096"),
              std::string::npos)
        << t.result.output;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(HostileInput, AStepFarAboveTheStableOneStopsOnTheEnergyBalance) {
  // one step of 0.5 ms where 42 ns is stable: the positions stay finite, the energy does not
  const fs::path out = out_dir("lie");
  const Timed t = femdem("run '" + scene() + "' --quiet --out '" + out.string() +
                         "' --set simulation.time_step=5e-4 --set simulation.end_time=5e-4");
  EXPECT_EQ(t.result.code, 3) << t.result.output;
  EXPECT_NE(t.result.output.find("the energy balance error reached"), std::string::npos)
      << t.result.output;
  EXPECT_NE(t.result.output.find("more than simulation.energy_balance_limit = 25 %"),
            std::string::npos)
      << t.result.output;
  std::ifstream in(out / "summary.json");
  ASSERT_TRUE(in);
  EXPECT_EQ(nlohmann::json::parse(in)["status"], "unstable");
}

// the shared ball and a second one 1.4 mm above it
const std::string kTwoSpheres = steel_ball_scene("two spheres", "end_time = 1e-5\n", R"(
[[bodies]]
name = "b"
material = "steel"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2e-3 }
position = [0.0, 0.0, 13.5e-3]
)");

// Bodies overlapping at the start are named by `check` and `run` (exit 2, nothing written)
// rather than run into "element inverted, lower time_step_safety".
TEST(HostileInput, BodiesOverlappingAtTheStartAreNamedWithTheFix) {
  const fs::path scene = fs::path(FEMDEM_TEST_TMP) / "hostile" / "two_spheres.toml";
  fs::create_directories(scene.parent_path());
  std::ofstream(scene) << kTwoSpheres;
  const struct {
    std::string set, message;
  } cases[] = {
      {"bodies.b.position=[0,0,11e-3]",
       "contact.initial_overlap: bodies 'ball' and 'b' overlap at the start"},
      {"bodies.ball.position=[0,0,3.5e-3]",
       "contact.initial_overlap: body 'ball' reaches 0.0005 m behind wall 'floor' at the start"},
  };
  for (const auto& c : cases)
    for (const std::string command : {"check", "run"}) {
      SCOPED_TRACE(command + " --set " + c.set);
      const fs::path out = out_dir("overlap");
      const Timed t =
          femdem(command + " '" + scene.string() + "' --set " + c.set +
                 (command == "run" ? " --quiet --out '" + out.string() + "'" : std::string()));
      EXPECT_EQ(t.result.code, 2) << t.result.output;
      EXPECT_NE(t.result.output.find(c.message), std::string::npos) << t.result.output;
      EXPECT_NE(t.result.output.find("or allow that much with contact.initial_overlap"),
                std::string::npos);
      EXPECT_EQ(t.result.output.find("Scene OK."), std::string::npos);
      EXPECT_FALSE(fs::exists(out));
    }
  // apart, and a stated allowance, pass
  EXPECT_EQ(femdem("check '" + scene.string() + "'").result.code, 0);
  EXPECT_EQ(femdem("check '" + scene.string() +
                   "' --set bodies.b.position=[0,0,11.9e-3] --set contact.initial_overlap=0.5")
                .result.code,
            0);
}

TEST(HostileInput, WeakMessagesSayWhatIsWrong) {
  // a string left open: named as such, with the file, line and column
  const fs::path bad = fs::path(FEMDEM_TEST_TMP) / "hostile" / "open_string.toml";
  fs::create_directories(bad.parent_path());
  std::ofstream(bad) << "[simulation]\nend_time = 1\ntitle = \"abc\n";
  Timed t = femdem("check '" + bad.string() + "'");
  EXPECT_EQ(t.result.code, 2);
  EXPECT_NE(t.result.output.find("open_string.toml:3:13: TOML syntax error: unterminated string"),
            std::string::npos)
      << t.result.output;
  // a number option given a word: no 309-digit range
  t = femdem("mesh part.stl --size abc");
  EXPECT_EQ(t.result.code, 2);
  EXPECT_NE(t.result.output.find("--size: must be a positive number, got 'abc'"), std::string::npos)
      << t.result.output;
  EXPECT_EQ(t.result.output.find("179769313486231570814527423731704356798070567525844996598917"),
            std::string::npos);
}

}  // namespace
}  // namespace femdem::test
