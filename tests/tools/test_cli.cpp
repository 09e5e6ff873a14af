// SPDX-License-Identifier: GPL-3.0-or-later
// The femdem program (FEMDEM_EXE): --version, --help, exit codes, `check` on good and bad scenes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;

using Result = femdem::test::CommandResult;

// Runs `femdem ARGS` in folder `cwd` (default: the test folder) through the shell.
Result run_femdem(const std::string& args, const fs::path& cwd = {}) {
  std::string cmd;
  if (!cwd.empty()) cmd = "cd '" + cwd.string() + "' && ";
  return femdem::test::run_command(cmd + "'" + FEMDEM_EXE + "' " + args);
}

fs::path tmp_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "cli" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

const char* kGoodScene = R"(title = "CLI test: a steel cube on a floor"
[simulation]
end_time = 1e-4
gravity = [0, 0, -9.81]

[[materials]]
name = "steel"
model = "elastic"
density = 8000
youngs_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "cube"
material = "steel"
mesh = { generator = "box", size = [0.1, 0.1, 0.1], element_size = 0.05 }
position = [0, 0, 0.01]

[[walls]]
name = "floor"
normal = [0, 0, 1]
)";

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(Cli, Version) {
  const Result r = run_femdem("--version");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "femdem ")) << r.output;
  EXPECT_TRUE(contains(r.output, "git")) << r.output;
}

TEST(Cli, Help) {
  const Result r = run_femdem("--help");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "run")) << r.output;
  EXPECT_TRUE(contains(r.output, "check")) << r.output;
  const Result sub = run_femdem("run --help");
  EXPECT_EQ(sub.code, 0) << sub.output;
  EXPECT_TRUE(contains(sub.output, "--out")) << sub.output;
  EXPECT_TRUE(contains(sub.output, "--set")) << sub.output;
  EXPECT_TRUE(contains(sub.output, "--threads")) << sub.output;
  EXPECT_TRUE(contains(sub.output, "--quiet")) << sub.output;
}

TEST(Cli, BadUsageExitsWithTwo) {
  EXPECT_EQ(run_femdem("--bogus").code, 2);
  EXPECT_EQ(run_femdem("").code, 2);                       // no subcommand
  EXPECT_EQ(run_femdem("frobnicate scene.toml").code, 2);  // unknown subcommand
  EXPECT_EQ(run_femdem("check").code, 2);                  // no scene
  EXPECT_EQ(run_femdem("run").code, 2);
  const fs::path dir = tmp_dir("usage");
  const std::string scene = write_file(dir / "cube.toml", kGoodScene);
  EXPECT_EQ(run_femdem("check '" + scene + "' --bogus").code, 2);
  EXPECT_EQ(run_femdem("run '" + scene + "' --threads -1").code, 2);
  EXPECT_EQ(run_femdem("run '" + scene + "' --threads many").code, 2);
}

TEST(Cli, CheckGoodSceneSummarisesAndWritesNothing) {
  const fs::path dir = tmp_dir("good");
  write_file(dir / "cube.toml", kGoodScene);
  const Result r = run_femdem("check cube.toml", dir);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "CLI test: a steel cube on a floor")) << r.output;
  EXPECT_TRUE(contains(r.output, "mass 8 kg")) << r.output;  // 8000 kg/m^3 * 1e-3 m^3
  EXPECT_TRUE(contains(r.output, "cube")) << r.output;
  EXPECT_TRUE(contains(r.output, "floor")) << r.output;
  EXPECT_TRUE(contains(r.output, "wave speed")) << r.output;
  // nothing but the scene in the folder
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(Cli, CheckWithOverrides) {
  const fs::path dir = tmp_dir("overrides");
  const std::string scene = write_file(dir / "cube.toml", kGoodScene);
  const Result ok = run_femdem("check '" + scene + "' --set materials.steel.density=4000 --set " +
                               "'bodies.cube.velocity=[0, 0, -1]'");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(contains(ok.output, "mass 4 kg")) << ok.output;
  EXPECT_TRUE(contains(ok.output, "velocity [0, 0, -1] m/s")) << ok.output;
  const Result bad = run_femdem("check '" + scene + "' --set bodies.cub.velocity=[0,0,1]");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_TRUE(contains(bad.output, "--set bodies.cub.velocity=[0,0,1]")) << bad.output;
  EXPECT_TRUE(contains(bad.output, "did you mean 'cube'?")) << bad.output;
}

TEST(Cli, BadScenesExitWithTwoNamingFileLineAndKey) {
  const fs::path dir = tmp_dir("bad");
  struct Case {
    std::string name, text, expected;
  };
  const std::string good = kGoodScene;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const Case cases[] = {
      {"negative_density", replace("density = 8000", "density = -8000"),
       "negative_density.toml:9:11: materials.steel.density: must be positive"},
      {"typo", replace("end_time = 1e-4", "end_tim = 1e-4"),
       "typo.toml:3:1: simulation.end_tim: unknown key 'end_tim' (did you mean 'end_time'?)"},
      {"syntax", replace("end_time = 1e-4", "end_time = = 1e-4"), "syntax.toml:3:"},
      {"model_key_missing", replace("\"elastic\"", "\"drucker_prager\""),
       "model_key_missing.toml:6:1: materials.steel.cohesion: required value is missing"},
      {"missing_mesh_file",
       replace("generator = \"box\", size = [0.1, 0.1, 0.1], element_size = 0.05",
               "file = \"missing.msh\""),
       "missing_mesh_file.toml:16:17: bodies.cube.mesh.file:"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    write_file(dir / (c.name + ".toml"), c.text);
    for (const char* cmd : {"check", "run"}) {
      const Result r = run_femdem(std::string(cmd) + " " + c.name + ".toml", dir);
      EXPECT_EQ(r.code, 2) << r.output;
      EXPECT_TRUE(contains(r.output, "error: " + c.expected)) << r.output;
    }
  }
  // run stops before writing anything
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, MissingSceneFileExitsWithTwo) {
  const fs::path dir = tmp_dir("missing");
  for (const char* cmd : {"check", "run"}) {
    const Result r = run_femdem(std::string(cmd) + " no_such_scene.toml", dir);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_TRUE(contains(r.output, "no_such_scene.toml")) << r.output;
  }
}

}  // namespace

// Every shipped scene reads, meshes and builds (`femdem check` exits 0): a scene that drifted
// from the reader's rules would otherwise only show when a user runs it.
TEST(Cli, EveryShippedSceneChecks) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(FEMDEM_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".toml") continue;
    ++scenes;
    const Result r = run_femdem("check '" + entry.path().string() + "'");
    EXPECT_EQ(r.code, 0) << entry.path() << "\n" << r.output;
  }
  EXPECT_GE(scenes, 9);
}

TEST(Cli, CheckTimesTheFirstStepsAndEstimatesTheRun) {
  const fs::path dir = tmp_dir("timed_sample");
  write_file(dir / "cube.toml", kGoodScene);
  const Result r = run_femdem("check cube.toml", dir);
  ASSERT_EQ(r.code, 0) << r.output;
  // "about 49 steps to the end time" then "timed sample: N steps in T s on 1 thread (R steps/s):
  // about D for the run at that rate"
  const std::size_t at = r.output.find("timed sample: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const long sampled = std::stol(r.output.substr(at + 14));
  EXPECT_GE(sampled, 3) << r.output;
  EXPECT_TRUE(contains(r.output.substr(at), "steps/s): about ")) << r.output;
  EXPECT_TRUE(contains(r.output.substr(at), " for the run at that rate")) << r.output;
  int entries = 0;  // still writes nothing
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(Cli, PipedProgressPrintsALineEveryTenthOfTheRun) {
  const fs::path dir = tmp_dir("piped_progress");
  write_file(dir / "cube.toml", kGoodScene);
  // 1e-3 s at the cube's step of about 2 us: some 500 steps, a tenth every 50, far more often
  // than the minute that would also print a line
  const Result r =
      run_femdem("run cube.toml --out out --set simulation.end_time=1e-3 --no-plot", dir);
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<double> percents;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("t = ", 0) != 0) continue;
    const std::size_t open = line.find('(');
    ASSERT_NE(open, std::string::npos) << line;
    percents.push_back(std::stod(line.substr(open + 1)));
  }
  ASSERT_GE(percents.size(), 9u) << r.output;
  ASSERT_LE(percents.size(), 10u) << r.output;
  for (std::size_t i = 0; i < percents.size(); ++i)  // one line per tenth, in order
    EXPECT_NEAR(percents[i], 10.0 * static_cast<double>(i + 1), 3.0) << r.output;
}
