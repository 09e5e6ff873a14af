// SPDX-License-Identifier: GPL-3.0-or-later
// The output folder's rules (tools/femdem/run/output_folder.hpp): an empty --out is refused, a
// folder holding an earlier run's outputs is not overwritten without --force, and a folder in
// use by a running femdem is refused to a second run or resume, which leave the first one's
// outputs whole. Each refusal exits 2 with its message.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"
#include "support/steel_ball_scene.hpp"

extern char** environ;

namespace femdem::test {
namespace {

namespace fs = std::filesystem;

const std::string kScene =
    steel_ball_scene("output folder", "end_time = 2e-5\noutput_interval = 2e-6\n");

fs::path dir() {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "output_folder";
  fs::create_directories(d);
  return d;
}

// Each test writes its own scene file: ctest runs these tests side by side, and a file rewritten
// (truncated) by one test while another's femdem reads it would be read empty.
fs::path scene(const std::string& test) {
  const fs::path p = dir() / (test + ".toml");
  std::ofstream(p) << kScene;
  return p;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult femdem(const std::string& args, const fs::path& cwd = {}) {
  const std::string cd = cwd.empty() ? "" : "cd '" + cwd.string() + "' && ";
  return run_command(cd + "'" + FEMDEM_EXE + "' " + args);
}

std::string run_args(const fs::path& scene, const fs::path& out, const std::string& more = "") {
  return "run '" + scene.string() + "' --quiet --threads 1 --out '" + out.string() + "' " + more;
}

TEST(OutputFolder, AnEmptyOutIsRefusedAndNothingIsWritten) {
  const fs::path cwd = dir() / "empty_out";
  fs::remove_all(cwd);
  fs::create_directories(cwd);
  const CommandResult r = femdem("run '" + scene("empty_out").string() + "' --quiet --out ''", cwd);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--out: the output folder's name is empty"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::is_empty(cwd)) << "out/ was written";
}

TEST(OutputFolder, AnEarlierRunIsNotOverwrittenWithoutForce) {
  const fs::path out = dir() / "earlier", ball = scene("earlier");
  fs::remove_all(out);
  ASSERT_EQ(femdem(run_args(ball, out)).code, 0);
  const std::string summary = read_text(out / "summary.json");
  CommandResult r = femdem(run_args(ball, out, "--set simulation.end_time=1e-5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("holds the outputs of a run that completed: --force replaces them, "
                          "`femdem resume " +
                          out.string() + "` continues that run"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_text(out / "summary.json"), summary) << "the refused run changed the folder";
  // a killed run (no summary) is named as such
  fs::remove(out / "summary.json");
  r = femdem(run_args(ball, out));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("a run that was killed (a checkpoint, no summary)"), std::string::npos)
      << r.output;
  // --force replaces it
  r = femdem(run_args(ball, out, "--force --set simulation.end_time=1e-5"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "summary.json"))["end_time"].get<double>(), 1e-5);
}

TEST(OutputFolder, InUseByARunningFemdemIsRefusedAndTheFirstRunIsUnharmed) {
  const fs::path out = dir() / "in_use", ball = scene("in_use");
  fs::remove_all(out);
  const std::string s = ball.string(), o = out.string();
  std::vector<std::string> args = {
      FEMDEM_EXE, "run",       s,   "--quiet", "--out",
      o,          "--threads", "1", "--set",   "simulation.end_time=4e-4"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, FEMDEM_EXE, nullptr, nullptr, argv.data(), environ), 0);
  while (!fs::exists(out / "history.csv"))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const CommandResult second = femdem(run_args(ball, out, "--force"));
  const CommandResult resumed = femdem("resume '" + o + "' --quiet");
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(second.code, 2) << second.output;
  EXPECT_NE(second.output.find("is in use by another femdem (pid " + std::to_string(pid)),
            std::string::npos)
      << second.output;
  EXPECT_EQ(resumed.code, 2) << resumed.output;
  const nlohmann::json summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["end_time"].get<double>(), 4e-4);
  EXPECT_EQ(read_text(out / "run.log").find("# resumed"), std::string::npos);
}

}  // namespace
}  // namespace femdem::test
