// SPDX-License-Identifier: GPL-3.0-or-later
// `femdem resume`: a run killed (SIGKILL at a random moment, or SIGTERM) and resumed from its
// checkpoint gives the same bits as the run made without interruption: summary.json (all but
// the wall timings), history.csv byte for byte, every frame of results.h5; with 1 and 2
// threads. Extending a finished run equals the longer run made from the start. A missing,
// damaged or foreign checkpoint, a changed scene and a key that would alter the past exit 2
// and change nothing in the folder.
//
// The scenes use every stateful feature: the four plasticity models, wall and body friction,
// mass scaling, impact and deformation damping and rest detection (four spheres hitting a floor
// and each other); a force-driven punch in a die of walls with [compaction] (a cube and a
// sphere on it).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/checkpoint/checkpoint_file.hpp"
#include "support/run_command.hpp"
#include "support/run_outputs.hpp"
#include "support/sanitizers.hpp"
#include "support/square_die.hpp"
#include "support/steel_ball_scene.hpp"

extern char** environ;

namespace femdem::test {
namespace {

namespace fs = std::filesystem;

const char* const kEveryFeature = R"(title = "restart: every stateful feature"
[simulation]
end_time = 1.2e-3
output_interval = 1e-4
history_interval = 1e-5
gravity = [0.0, 0.0, -9.81]
mass_scaling_time_step = 2.5e-7
mass_scaling_limit = 1.0
deformation_damping = { ratio = 0.05, frequency = 5000.0 }
rest_kinetic_fraction = 1e-3
rest_hold_time = 1e-4
checkpoint_interval = 1e-4

[[materials]]
name = "metal"
model = "von_mises"
density = 2700.0
youngs_modulus = 70e9
poisson_ratio = 0.3
yield_stress = 30e6
hardening_modulus = 300e6

[[materials]]
name = "rock_dp"
model = "drucker_prager"
density = 2500.0
youngs_modulus = 30e9
poisson_ratio = 0.25
cohesion = 4e6
friction_angle = 30.0
dilatancy_angle = 10.0

[[materials]]
name = "rock_mc"
model = "mohr_coulomb"
density = 2500.0
youngs_modulus = 30e9
poisson_ratio = 0.25
cohesion = 4e6
friction_angle = 30.0
cohesion_hardening_modulus = -2e6
residual_cohesion = 1e6

[[materials]]
name = "rock_pdp"
model = "piecewise_drucker_prager"
density = 2500.0
youngs_modulus = 30e9
poisson_ratio = 0.25
pieces = [[0.42, 8e6], [0.30, 14e6], [0.14, 30e6]]

[[bodies]]
name = "a"
material = "metal"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2.5e-3 }
position = [-6e-3, 0.0, 4.2e-3]
velocity = [5.0, 0.0, -8.0]

[[bodies]]
name = "b"
material = "rock_dp"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2.5e-3 }
position = [6e-3, 0.0, 4.4e-3]
velocity = [-5.0, 0.0, -6.0]
angular_velocity = [0.0, 300.0, 0.0]

[[bodies]]
name = "c"
material = "rock_mc"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2.5e-3 }
position = [0.0, 9e-3, 4.3e-3]
velocity = [0.0, -2.0, -8.0]

[[bodies]]
name = "d"
material = "rock_pdp"
mesh = { generator = "sphere", radius = 4e-3, element_size = 2.5e-3 }
position = [0.0, -9e-3, 4.3e-3]
velocity = [0.0, 2.0, -8.0]

[[walls]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
friction = 0.4
damping = 0.05

[contact]
friction = 0.3
impact_damping = 0.1
)";

const std::string kDie = R"(title = "restart: force-driven punch in a die"
[simulation]
end_time = 3e-4
output_interval = 3e-5
history_interval = 3e-6
checkpoint_interval = 3e-5

[[materials]]
name = "aluminium"
model = "von_mises"
density = 2700.0
youngs_modulus = 70e9
poisson_ratio = 0.3
yield_stress = 100e6
hardening_modulus = 700e6

[[bodies]]
name = "cube"
material = "aluminium"
mesh = { generator = "box", size = [8e-3, 8e-3, 6e-3], element_size = 3e-3 }
position = [-4e-3, -4e-3, 0.0]

[[bodies]]
name = "ball"
material = "aluminium"
mesh = { generator = "sphere", radius = 2.5e-3, element_size = 2.5e-3 }
position = [0.0, 0.0, 8.6e-3]

[[walls]]
name = "bottom"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
friction = 0.2

[[walls]]
name = "punch"
point = [0.0, 0.0, 11.2e-3]
normal = [0.0, 0.0, -1.0]
force_history = [[0.0, 0.0], [1.5e-4, 4e4], [3e-4, 4e4]]
mass = 0.2
velocity = [0.0, 0.0, -2.0]

)" + std::string(kSquareDieSideWalls) +
                         R"(
[contact]
friction = 0.2

[compaction]
punch = "punch"
bottom = "bottom"
die_walls = ["left", "right", "front", "back"]
die_area = 6.4e-5
die_perimeter = 32e-3
)";

// A sphere that hits a floor with heavy impact damping and leaves it slowly: at rest by the
// kinetic-energy criterion soon after the impact, well before the end time.
const std::string kRest = steel_ball_scene("restart: stop at rest", R"(end_time = 1e-3
output_interval = 2e-5
history_interval = 2e-6
rest_kinetic_fraction = 0.05
rest_hold_time = 4e-5
checkpoint_interval = 2e-5
)",
                                           "\n[contact]\nimpact_damping = 0.6\n");

fs::path tmp_dir() {
  return fs::path(FEMDEM_TEST_TMP) / "resume";
}

fs::path write_scene(const std::string& name, const char* text) {
  fs::create_directories(tmp_dir());
  const fs::path p = tmp_dir() / (name + ".toml");
  std::ofstream(p) << text;
  return p;
}

std::string quoted(const fs::path& p) {
  std::string q = "'";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "'" + string
  q += p.string();
  q += '\'';
  return q;
}

CommandResult femdem(const std::string& args) {
  return run_command(std::string("'") + FEMDEM_EXE + "' " + args);
}

CommandResult run(const fs::path& scene, const fs::path& out, const std::string& options = "") {
  fs::remove_all(out);
  return femdem("run " + quoted(scene) + " --quiet --out " + quoted(out) + " " + options);
}

CommandResult resume(const fs::path& out, const std::string& options = "") {
  return femdem("resume " + quoted(out) + " --quiet " + options);
}

// Starts `femdem run`, waits until a checkpoint exists and then a random 0 to max_delay_ms more,
// and sends `sig`. Returns false if the run ended before it could be signalled.
bool signal_once(const fs::path& scene, const fs::path& out, int threads, int sig,
                 std::mt19937& rng, int max_delay_ms) {
  fs::remove_all(out);
  const std::string threads_text = std::to_string(threads);
  std::vector<std::string> args = {FEMDEM_EXE, "run",        scene.string(), "--quiet",
                                   "--out",    out.string(), "--threads",    threads_text};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, FEMDEM_EXE, nullptr, nullptr, argv.data(), environ) != 0) return false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out / "checkpoint.h5") && std::chrono::steady_clock::now() < give_up) {
    if (waitpid(pid, nullptr, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(rng() % (max_delay_ms + 1)));
  int status = 0;
  if (waitpid(pid, &status, WNOHANG) == pid) return false;  // finished first
  kill(pid, sig);
  waitpid(pid, &status, 0);
  return true;
}

// signal_once with a delay of up to a third of the uninterrupted run's wall time (read from
// `reference`'s summary), tried again with shorter delays if the run ends first.
bool run_and_signal(const fs::path& scene, const fs::path& out, int threads, int sig, unsigned seed,
                    const fs::path& reference) {
  std::ifstream in(reference / "summary.json");
  const double wall_s = in ? nlohmann::json::parse(in).value("wall_time_s", 1.0) : 1.0;
  std::mt19937 rng(seed);
  int max_delay_ms = static_cast<int>(1000.0 * wall_s / 3.0);
  for (int attempt = 0; attempt < 4; ++attempt, max_delay_ms /= 4)
    if (signal_once(scene, out, threads, sig, rng, max_delay_ms)) return true;
  return false;
}

struct Reference {
  fs::path scene, out;
};

// The uninterrupted run, one per test (ctest runs the tests as processes side by side: each
// writes its own scene file and folders).
Reference reference(const std::string& name, const char* text, const std::string& tag) {
  Reference r{write_scene(name + "_" + tag, text), tmp_dir() / (name + "_" + tag + "_straight")};
  const CommandResult c = run(r.scene, r.out, "--threads 1");
  EXPECT_EQ(c.code, 0) << c.output;
  return r;
}

class Resume : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

// Under the sanitizers, one case of each signal runs: SIGKILL on every_feature and SIGTERM on
// the die, with 2 threads (the other cases repeat their code: the same checkpoints, handler and
// resume).
bool skipped_under_sanitizers(const std::string& scene, int threads, int sig) {
  return kUnderSanitizers && (threads == 1 || (sig == SIGKILL) != (scene == "every_feature"));
}
constexpr const char* kOneCaseOfEachSignal =
    "SIGKILL on every_feature and SIGTERM on the die, with 2 threads, run the same code";

TEST_P(Resume, AfterSigkillAtARandomStepGivesTheUninterruptedRunsBits) {
  const auto [name, threads] = GetParam();
  if (skipped_under_sanitizers(name, threads, SIGKILL))
    GTEST_SKIP() << kSkippedUnderSanitizers << kOneCaseOfEachSignal;
  const std::string tag = "killed_" + std::to_string(threads);
  const Reference ref =
      reference(name, name == "every_feature" ? kEveryFeature : kDie.c_str(), tag);
  const fs::path out = tmp_dir() / (name + "_" + tag);
  ASSERT_TRUE(run_and_signal(ref.scene, out, threads, SIGKILL, 17u + threads, ref.out))
      << "the run ended before it could be killed";
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  // history.csv is flushed with every frame: the kill lost no row that a frame has
  const auto f = frames(out);
  ASSERT_FALSE(f.empty());
  ASSERT_GE(f[0].size(), 8u);
  double last_frame = 0.0;
  std::memcpy(&last_frame, f[0].data() + f[0].size() - 8, 8);
  const std::string h = read_text(out / "history.csv");
  const std::size_t last_line = h.rfind('\n', h.size() - 2) + 1;
  EXPECT_GE(std::stod(h.substr(last_line)), last_frame);
  const CommandResult r = resume(out, "--threads " + std::to_string(threads));
  ASSERT_EQ(r.code, 0) << r.output;
  expect_same_run(ref.out, out);
  EXPECT_NE(read_text(out / "run.log").find("resumed from checkpoint.h5"), std::string::npos);
}

TEST_P(Resume, AfterSigtermGivesTheUninterruptedRunsBits) {
  const auto [name, threads] = GetParam();
  if (skipped_under_sanitizers(name, threads, SIGTERM))
    GTEST_SKIP() << kSkippedUnderSanitizers << kOneCaseOfEachSignal;
  const std::string tag = "terminated_" + std::to_string(threads);
  const Reference ref =
      reference(name, name == "every_feature" ? kEveryFeature : kDie.c_str(), tag);
  const fs::path out = tmp_dir() / (name + "_" + tag);
  ASSERT_TRUE(run_and_signal(ref.scene, out, threads, SIGTERM, 5u + threads, ref.out));
  const nlohmann::json s = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(s["status"], "interrupted");
  ASSERT_TRUE(s.contains("checkpoint"));
  EXPECT_NE(s["checkpoint"]["resume"].get<std::string>().find("femdem resume"), std::string::npos);
  EXPECT_NE(read_text(out / "run.log").find("Continue with: femdem resume"), std::string::npos);
  const CommandResult r = resume(out, "--threads " + std::to_string(threads));
  ASSERT_EQ(r.code, 0) << r.output;
  expect_same_run(ref.out, out);
}

TEST(ResumeAfterSigint, GivesTheUninterruptedRunsBits) {  // Ctrl-C: the same as SIGTERM
  if (kUnderSanitizers)
    GTEST_SKIP() << kSkippedUnderSanitizers
                 << "SIGTERM's tests run the same handler, interruption and resume";
  const Reference ref = reference("every_feature", kEveryFeature, "interrupted");
  const fs::path out = tmp_dir() / "every_feature_interrupted";
  ASSERT_TRUE(run_and_signal(ref.scene, out, 1, SIGINT, 23u, ref.out));
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "summary.json"))["status"], "interrupted");
  ASSERT_EQ(resume(out, "--threads 1").code, 0);
  expect_same_run(ref.out, out);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Resume,
                         ::testing::Combine(::testing::Values("every_feature", "die"),
                                            ::testing::Values(1, 2)));

TEST(ResumeAtRest, AKilledRunThatComesToRestStopsWhereTheUninterruptedOneDoes) {
  const Reference ref = reference("rest", kRest.c_str(), "killed");
  const nlohmann::json s = nlohmann::json::parse(read_text(ref.out / "summary.json"));
  ASSERT_TRUE(s["extra"].contains("at_rest_time")) << "the scene must come to rest";
  EXPECT_LT(s["end_time"].get<double>(), 1e-3);
  const fs::path out = tmp_dir() / "rest_killed";
  ASSERT_TRUE(run_and_signal(ref.scene, out, 1, SIGKILL, 11u, ref.out));
  ASSERT_EQ(resume(out, "--threads 1").code, 0);
  expect_same_run(ref.out, out);
  // resumed as it is, a run at rest stays where it stopped
  const std::string history = read_text(out / "history.csv");
  ASSERT_EQ(resume(out).code, 0);
  EXPECT_EQ(read_text(out / "history.csv"), history);
}

TEST(ResumeAtRest, OtherRestCriteriaLookForRestAnew) {
  const Reference ref = reference("rest", kRest.c_str(), "rearmed");
  const nlohmann::json before = nlohmann::json::parse(read_text(ref.out / "summary.json"));
  const double rest_time = before["extra"]["at_rest_time"].get<double>();
  const CommandResult r = resume(ref.out, "--set simulation.rest_kinetic_fraction=0.001");
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json after = nlohmann::json::parse(read_text(ref.out / "summary.json"));
  EXPECT_GT(after["steps"].get<std::int64_t>(), before["steps"].get<std::int64_t>());
  EXPECT_GT(after["end_time"].get<double>(), rest_time);
  // the rows go on from the checkpoint: times strictly increasing, none twice
  std::istringstream rows(read_text(ref.out / "history.csv"));
  std::string line;
  std::getline(rows, line);
  double last = -1.0;
  int count = 0;
  while (std::getline(rows, line)) {
    const double t = std::stod(line.substr(0, line.find(',')));
    EXPECT_GT(t, last) << "row " << count;
    last = t, ++count;
  }
  EXPECT_GT(last, rest_time);
}

// How many checkpoints run.log says the run wrote.
int checkpoints_written(const fs::path& out) {
  const std::string log = read_text(out / "run.log");
  const auto at = log.find(" checkpoint");
  if (at == std::string::npos) return 0;
  const auto start = log.rfind('\n', at) + 1;
  return std::stoi(log.substr(start, at - start));
}

TEST(ResumeCheckpoints, AreWrittenByWallClockAndOnceBeforeTheLastSteps) {
  const fs::path scene = write_scene("wall_clock", kEveryFeature);
  const fs::path out = tmp_dir() / "wall_clock";
  const std::string shorter = "--threads 1 --set simulation.end_time=4e-4 ";
  ASSERT_EQ(run(scene, out,
                shorter + "--set simulation.checkpoint_interval=0 "
                          "--set simulation.checkpoint_wall_interval=0")
                .code,
            0);
  EXPECT_EQ(checkpoints_written(out), 1) << "only the one before the last steps";
  const double wall_s =
      nlohmann::json::parse(read_text(out / "summary.json"))["extra"]["loop_time_s"].get<double>();
  ASSERT_EQ(run(scene, out,
                shorter +
                    "--set simulation.checkpoint_interval=0 "
                    "--set simulation.checkpoint_wall_interval=" +
                    std::to_string(wall_s / 5))
                .code,
            0);
  // about five by the wall clock (the machine's speed varies between the two runs) and the last
  EXPECT_GE(checkpoints_written(out), 3);
  EXPECT_LE(checkpoints_written(out), 12);
}

TEST(ResumeExtend, AFinishedRunWithALaterEndTimeEqualsTheLongerRun) {
  const fs::path scene = write_scene("extend", kDie.c_str());
  const fs::path longer = tmp_dir() / "extend_longer", extended = tmp_dir() / "extend_extended";
  ASSERT_EQ(run(scene, longer, "--threads 1 --set simulation.end_time=3.6e-4").code, 0);
  ASSERT_EQ(run(scene, extended, "--threads 1").code, 0);
  const CommandResult r = resume(extended, "--set simulation.end_time=3.6e-4");
  ASSERT_EQ(r.code, 0) << r.output;
  expect_same_run(longer, extended);
}

// A failed resume leaves every file of the folder as it was.
std::map<std::string, std::string> folder_contents(const fs::path& dir) {
  std::map<std::string, std::string> c;
  for (const auto& e : fs::directory_iterator(dir)) c[e.path().filename()] = read_text(e.path());
  return c;
}

TEST(ResumeRefuses, BadCheckpointsAndChangesWithExit2AndTouchesNothing) {
  const fs::path scene = write_scene("refuse", kDie.c_str());
  const fs::path out = tmp_dir() / "refuse_run";
  ASSERT_TRUE(run_and_signal(scene, out, 1, SIGKILL, 3u, fs::path()));
  const fs::path other = tmp_dir() / "refuse_other";
  ASSERT_EQ(run(write_scene("refuse_other", kEveryFeature), other,
                "--threads 1 --set simulation.end_time=2e-4")
                .code,
            0);
  const auto before = folder_contents(out);
  const fs::path ck = out / "checkpoint.h5";
  const std::string good = read_text(ck);
  struct Case {
    std::string what, options, expected;
    std::function<void()> damage;
  };
  const std::vector<Case> cases = {
      {"key that alters the past",
       "--set contact.friction=0.5",
       "--set contact.friction: a resumed run may change only what does not alter the past",
       {}},
      {"material key",
       "--set materials.aluminium.yield_stress=1e8",
       "materials.aluminium.yield_stress: a resumed run may change only",
       {}},
      {"missing checkpoint", "", "no checkpoint", [&] { fs::remove(ck); }},
      {"truncated checkpoint", "", "truncated or damaged",
       [&] { std::ofstream(ck, std::ios::binary) << good.substr(0, good.size() / 2); }},
      {"not HDF5", "", "truncated or damaged", [&] { std::ofstream(ck) << "hello"; }},
      {"another run's checkpoint", "", "the checkpoint does not belong to this folder's run",
       [&] { fs::copy_file(other / "checkpoint.h5", ck, fs::copy_options::overwrite_existing); }},
      {"scene changed", "", "the scene has changed since the run started",
       [&] {
         const std::string text = kDie;
         const std::string from = "yield_stress = 100e6";
         const std::size_t at = text.find(from);
         ASSERT_NE(at, std::string::npos);
         std::ofstream(scene) << text.substr(0, at) << "yield_stress = 120e6"
                              << text.substr(at + from.size());
       }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::ofstream(ck, std::ios::binary) << good;
    std::ofstream(scene) << kDie;
    if (c.damage) c.damage();
    const auto damaged = folder_contents(out);
    const CommandResult r = resume(out, c.options);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_TRUE(folder_contents(out) == damaged) << "the failed resume changed the folder";
  }
  // the format version names itself
  std::ofstream(ck, std::ios::binary) << good;
  {
    const hid_t f = H5Fopen(ck.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t a = H5Aopen(f, "format", H5P_DEFAULT);
    const int other_format = 99;
    H5Awrite(a, H5T_NATIVE_INT, &other_format);
    H5Aclose(a);
    H5Fclose(f);
  }
  const CommandResult r = resume(out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(
      r.output.find("has format 99, this femdem reads format " + std::to_string(kCheckpointFormat)),
      std::string::npos)
      << r.output;
  (void)before;
}

}  // namespace
}  // namespace femdem::test
