// SPDX-License-Identifier: GPL-3.0-or-later
// `mpirun -np N femdem run SCENE` (docs/ARCHITECTURE.md, "Distributed runs"): a run on 2 and 3
// ranks writes what one process writes, to the bit (summary.json but for the machine's
// timings, history.csv byte for byte, every frame of results.h5, the XDMF files); a run
// started on 2 ranks resumes on 1 and one started in one process resumes on 3, each equal to
// the run made straight through; and what ranks cannot do yet is refused alike.
//
// The scenes: one body cut among the ranks: an elastic bar vibrating along its length on
// rollers with a fixed end (as scenes/bar_vibration.toml); a von Mises bar with nodal F-bar
// (three ghost layers) moving at 11 m/s with one end held, yielded by the wave from the held
// end (rho c v = 150 MPa against a yield stress of 30 MPa); a coarse Taylor bar on its anvil;
// a Drucker-Prager block pressed in a die with friction by a force-driven punch. Bodies in
// contact across ranks: the Hertz pair (scenes/hertz_two_spheres.toml, coarse: each sphere
// whole on 2 ranks, both cut on 3); eight spheres colliding obliquely with friction,
// deformation damping, impact damping and rolling resistance on a rough floor (whole bodies on
// 2 and 3 ranks); the 64-sphere compaction (scenes/compaction_64_spheres.toml) in small.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/femdem_on_ranks.hpp"
#include "support/run_outputs.hpp"
#include "support/sanitizers.hpp"
#include "support/square_die.hpp"
#include "support/vibrating_bar_scene.hpp"

namespace femdem::test {
namespace {

namespace fs = std::filesystem;

const std::string kElasticBar = vibrating_bar_scene("distributed: elastic bar vibration", R"(
end_time = 6.0
output_interval = 0.5
history_interval = 0.1
checkpoint_interval = 1.0
)") + R"(
[[constraints]]
body = "bar"
region = { plane_point = [0.0, 0.0, 0.0], plane_normal = [1.0, 0.0, 0.0] }
fix = ["x"]
)";

const char* const kPlasticBar = R"(title = "distributed: yielding bar, nodal F-bar"
[simulation]
end_time = 2e-4
output_interval = 2e-5
history_interval = 5e-6
gravity = [0.0, 0.0, -9.81]
stable_step = "assembled"

[[materials]]
name = "metal"
model = "von_mises"
density = 2700.0
youngs_modulus = 70e9
poisson_ratio = 0.3
yield_stress = 30e6
hardening_modulus = 300e6

[[bodies]]
name = "bar"
material = "metal"
fbar = "nodal"
mesh = { generator = "box", size = [0.06, 0.01, 0.01], element_size = 0.005 }
velocity = [10.0, 0.0, 5.0]

[[constraints]]
body = "bar"
region = { plane_point = [0.0, 0.0, 0.0], plane_normal = [1.0, 0.0, 0.0] }
fix = ["x", "y", "z"]
)";

// The Taylor bar (scenes/taylor_bar.toml) coarse: a copper rod at 227 m/s on a rigid wall.
const char* const kTaylorBar = R"(title = "distributed: coarse Taylor bar"
[simulation]
end_time = 16e-6
output_interval = 2e-6
history_interval = 4e-7
checkpoint_interval = 4e-6

[[materials]]
name = "copper"
model = "von_mises"
density = 8930.0
youngs_modulus = 117e9
poisson_ratio = 0.35
yield_stress = 400e6
hardening_modulus = 100e6

[[bodies]]
name = "rod"
material = "copper"
mesh = { generator = "cylinder", radius = 3.2e-3, length = 32.4e-3, element_size = 1.6e-3 }
velocity = [0.0, 0.0, -227.0]

[[walls]]
name = "anvil"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
)";

// A Drucker-Prager block pressed in a die with friction by a force-driven punch: the walls'
// forces (reduced over the ranks), friction springs carried across the ranks' near lists,
// the punch's own motion from those forces.
const std::string kDiePress = R"(title = "distributed: block pressed in a die"
[simulation]
end_time = 1.2e-4
output_interval = 2e-5
history_interval = 2e-6
gravity = [0.0, 0.0, -9.81]

[[materials]]
name = "powder"
model = "drucker_prager"
density = 2500.0
youngs_modulus = 3e9
poisson_ratio = 0.25
cohesion = 2e6
friction_angle = 30.0
dilatancy_angle = 5.0

[[bodies]]
name = "block"
material = "powder"
mesh = { generator = "box", size = [8e-3, 8e-3, 10e-3], element_size = 2e-3 }
position = [-4e-3, -4e-3, 0.0]

[[walls]]
name = "bottom"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
friction = 0.2

[[walls]]
name = "punch"
point = [0.0, 0.0, 10.05e-3]
normal = [0.0, 0.0, -1.0]
force_history = [[0.0, 0.0], [6e-5, 2e4], [1.2e-4, 2e4]]
mass = 0.05
velocity = [0.0, 0.0, -5.0]

)" + std::string(kSquareDieSideWalls) +
                              R"()";

// The coarse Taylor bar with selective mass scaling to a step above its stable one: elements
// are scaled at the start and again as the foot is crushed (the added mass summed over the
// ranks, ghost masses from their owners).
const std::string kTaylorBarScaled = [] {
  std::string t = kTaylorBar;
  const std::string at = "[simulation]\n";
  t.insert(
      t.find(at) + at.size(),
      "mass_scaling_time_step = 6e-8\nmass_scaling_limit = 1.0\nstable_step = \"assembled\"\n");
  return t;
}();

// A steel sphere of radius 1 cm, as a [[bodies]] table.
std::string sphere(const std::string& name, const std::string& position,
                   const std::string& velocity, const std::string& element_size = "5e-3") {
  return "\n[[bodies]]\nname = \"" + name +
         "\"\nmaterial = \"steel\"\nmesh = { generator = \"sphere\", radius = 0.01, "
         "element_size = " +
         element_size + " }\nposition = " + position + "\nvelocity = " + velocity + "\n";
}

const char* const kElasticSteel = R"(
[[materials]]
name = "steel"
model = "elastic"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3
)";

// scenes/hertz_two_spheres.toml coarse: two steel spheres head-on at 0.5 m/s each.
const std::string kHertzPair = std::string(R"(title = "distributed: Hertz pair"
[simulation]
end_time = 100e-6
output_interval = 10e-6
history_interval = 1e-6
checkpoint_interval = 25e-6
)") + kElasticSteel + sphere("upper", "[0.0, 0.0, 0.010001]", "[0.0, 0.0, -0.5]", "4e-3") +
                               sphere("lower", "[0.0, 0.0, -0.010001]", "[0.0, 0.0, 0.5]", "4e-3");

// Spheres meeting obliquely with friction, over a rough floor, under gravity and
// deformation damping: sticking and sliding pairs between ranks, their friction springs carried
// across rebuilds and checkpoints.
const std::string kSpheres = [] {
  std::string t = R"(title = "distributed: spheres in contact"
[simulation]
end_time = 1.2e-4
output_interval = 2.5e-5
history_interval = 2.5e-6
checkpoint_interval = 2.5e-5
gravity = [0.0, 0.0, -9.81]
deformation_damping = { ratio = 0.05, frequency = 5000.0 }

[[materials]]
name = "steel"
model = "von_mises"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3
yield_stress = 300e6
hardening_modulus = 1e9

[contact]
friction = 0.3

[[walls]]
name = "floor"
point = [0.0, 0.0, -0.0102]
normal = [0.0, 0.0, 1.0]
friction = 0.4
)";
  // two layers of four, the second moving onto the first (eight whole bodies on 2 and 3 ranks)
  const char* const bodies[8][3] = {{"a", "[0.0, 0.0, 0.0]", "[3.0, 0.0, -1.0]"},
                                    {"b", "[0.0201, 0.003, 0.0]", "[-3.0, 0.0, 0.0]"},
                                    {"c", "[0.001, 0.0, 0.0201]", "[0.0, 1.0, -3.0]"},
                                    {"d", "[0.0212, 0.003, 0.0201]", "[-2.0, 0.0, -2.0]"},
                                    {"e", "[0.0, 0.0204, 0.0]", "[3.0, -2.0, -1.0]"},
                                    {"f", "[0.0201, 0.0234, 0.0]", "[-3.0, -2.0, 0.0]"},
                                    {"g", "[0.001, 0.0204, 0.0201]", "[0.0, -1.0, -3.0]"},
                                    {"h", "[0.0212, 0.0234, 0.0201]", "[-2.0, -2.0, -2.0]"}};
  for (const auto& b : bodies) t += sphere(b[0], b[1], b[2]);
  return t;
}();

// The same with impact damping and rolling resistance on every patch (between bodies of two
// ranks: each rank loads its own body with the other's rigid motion; on the floor).
const std::string kSpheresDamped = [] {
  std::string t = kSpheres;
  const std::string at = "friction = 0.3\n";
  t.insert(t.find(at) + at.size(), "impact_damping = 0.3\nrolling_resistance = 0.05\n");
  return t;
}();

// scenes/compaction_64_spheres.toml in small: the 64 spheres at one cell per radius, 20 us of
// a lid driven at 10 m/s ([compaction]'s columns sum the powder's volume over the ranks).
const std::string kCompaction64 = [] {
  std::string t = read_text(fs::path(FEMDEM_SOURCE_DIR) / "scenes/compaction_64_spheres.toml");
  auto replace = [&](const std::string& from, const std::string& to) {
    t.replace(t.find(from), from.size(), to);
  };
  replace("end_time = 2.76e-3", "end_time = 2e-5\ncheckpoint_interval = 5e-6");
  replace("output_interval = 5.52e-5", "output_interval = 5e-6");
  replace("cells_per_radius = 2", "cells_per_radius = 1");
  // (the lid at 10 m/s from the start: the spheres are pressed together within the test's time)
  replace("velocity_history = [[0.0, 0.0, 0.0, 0.0], [2e-4, 0.0, 0.0, -1.0]]",
          "velocity_history = [[0.0, 0.0, 0.0, -10.0], [1.0, 0.0, 0.0, -10.0]]");
  return t;
}();

// Four spheres in a square whose spread turns from x to y (the left and right ones close in,
// the lower and upper ones part; they would meet at 170 us): the bisection of their centroids
// cuts along x at the start and along y after about 40 us, so with rebalance_threshold = 0 the
// ranks re-deal them at the frame of 50 us, and the run goes on as one process's. (Bodies in
// contact re-dealt: the sphere scene on 3 ranks, at the default threshold.)
const std::string kSpheresRedealt = std::string(R"(title = "distributed: re-dealt spheres"
[simulation]
end_time = 1.5e-4
output_interval = 2.5e-5
history_interval = 2.5e-6
checkpoint_interval = 5e-5
rebalance_threshold = 0.0

[contact]
friction = 0.3
)") + kElasticSteel + sphere("left_low", "[0.0, 0.0, 0.0]", "[3.0, -3.0, 0.0]") +
                                    sphere("right_low", "[0.021, 0.0, 0.0]", "[-3.0, -3.0, 0.0]") +
                                    sphere("left_high", "[0.0, 0.0205, 0.0]", "[3.0, 3.0, 0.0]") +
                                    sphere("right_high", "[0.021, 0.0205, 0.0]",
                                           "[-3.0, 3.0, 0.0]");

struct SceneCase {
  const char* text;
  const char* half_time;  // where the resume tests stop the first run
  const char* end_time;
};

SceneCase scene_case(const std::string& name) {
  if (name == "elastic_bar") return {kElasticBar.c_str(), "3.0", "6.0"};
  if (name == "plastic_bar") return {kPlasticBar, "1e-4", "2e-4"};
  if (name == "taylor_bar") return {kTaylorBar, "8e-6", "16e-6"};
  if (name == "taylor_bar_mass_scaling") return {kTaylorBarScaled.c_str(), "8e-6", "16e-6"};
  if (name == "hertz_pair") return {kHertzPair.c_str(), "40e-6", "100e-6"};
  if (name == "spheres_damped") return {kSpheresDamped.c_str(), "6e-5", "1.2e-4"};
  if (name == "compaction_64") return {kCompaction64.c_str(), "1e-5", "2e-5"};
  if (name == "spheres_redealt") return {kSpheresRedealt.c_str(), "7.5e-5", "1.5e-4"};
  return {kDiePress.c_str(), "6e-5", "1.2e-4"};
}

fs::path tmp_dir() {
  return fs::path(FEMDEM_TEST_TMP) / "distributed_run";
}

fs::path write_scene(const std::string& name, const std::string& text) {
  fs::create_directories(tmp_dir());
  const fs::path p = tmp_dir() / (name + ".toml");
  std::ofstream(p) << text;
  return p;
}

CommandResult femdem(int ranks, const std::string& args) {
  return femdem_on_ranks(ranks, args);
}

CommandResult run(int ranks, const fs::path& scene, const fs::path& out,
                  const std::string& options = "") {
  fs::remove_all(out);
  return femdem(ranks, "run '" + scene.string() + "' --quiet --threads 1 --out '" + out.string() +
                           "' " + options);
}

// A body cut among ranks has its per-step motion (the restitution monitors) summed per rank and
// the ranks' sums added: its coefficients of restitution agree to round-off only (the one
// exception to the same bits, docs/ARCHITECTURE.md).
constexpr double kCutBodyRestitution = 1e-12;

class DistributedRun : public ::testing::TestWithParam<std::string> {
 protected:
  const char* scene_text() const { return scene_case(GetParam()).text; }
};

TEST_P(DistributedRun, TwoAndThreeRanksWriteWhatOneProcessWrites) {
  if (kUnderSanitizers && (GetParam() == "hertz_pair" || GetParam() == "taylor_bar"))
    GTEST_SKIP() << kSkippedUnderSanitizers
                 << "contact across ranks runs there in the sphere scenes and the compaction, "
                    "walls across ranks in die_press and taylor_bar_mass_scaling";
  const fs::path scene = write_scene(GetParam(), scene_text());
  const fs::path one = tmp_dir() / (GetParam() + "_1");
  const CommandResult c1 = run(1, scene, one);
  ASSERT_EQ(c1.code, 0) << c1.output;
  // (under the sanitizers, 3 ranks only, which cut the bodies more and run the same code, but
  // for the spheres re-dealt on 2)
  const std::vector<int> rank_counts = kUnderSanitizers && GetParam() != "spheres_redealt"
                                           ? std::vector<int>{3}
                                           : std::vector<int>{2, 3};
  for (int ranks : rank_counts) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const fs::path out = tmp_dir() / (GetParam() + "_" + std::to_string(ranks));
    const CommandResult c = run(ranks, scene, out);
    ASSERT_EQ(c.code, 0) << c.output;
    expect_same_run(one, out, kCutBodyRestitution);
    const std::string log = read_text(out / "run.log");
    EXPECT_NE(log.find("in each of " + std::to_string(ranks) + " ranks"), std::string::npos);
    // bodies in contact across ranks: some pairs had a sub-tet of another rank's body
    const std::string received = "contact nodes of other ranks' bodies received a step: ";
    // (the spheres re-dealt: on 2 ranks, once their spread has turned)
    // (and the sphere scene on 3 ranks at the default threshold: bodies in contact re-dealt)
    if ((GetParam() == "spheres_redealt" && ranks == 2) ||
        (GetParam() == "spheres_damped" && ranks == 3)) {
      EXPECT_NE(log.find("rebalanced at t = "), std::string::npos) << log;
    }
    if (const auto at = log.find(received); at != std::string::npos) {
      if (GetParam() != "spheres_redealt") {  // (its pairs meet on one rank once re-dealt)
        EXPECT_GT(std::stod(log.substr(at + received.size())), 0.0) << log;
      }
      // each pair evaluated by one rank: the pairs taken on all ranks are the pairs listed
      // (counted once), and a pair listed on two ranks went from one to the other as an outcome
      long long evaluated = -1, listed = -2;
      double sent = -1.0;
      const auto e = log.find("contact pairs evaluated: ");
      ASSERT_NE(e, std::string::npos) << log;
      ASSERT_EQ(std::sscanf(log.c_str() + e,
                            "contact pairs evaluated: %lld on all ranks for %lld listed (each by "
                            "one rank); %lf",
                            &evaluated, &listed, &sent),
                3)
          << log;
      EXPECT_EQ(evaluated, listed) << log;
      EXPECT_GT(listed, 0) << log;
      if (GetParam() != "spheres_redealt") {
        EXPECT_GT(sent, 0.0) << log;
      }
    } else {
      EXPECT_TRUE(GetParam().find("bar") != std::string::npos || GetParam() == "die_press") << log;
    }
  }
}

// (a fixture of its own: contact across ranks is resumed in the sphere scenes; the Hertz pair
// and the compaction would add nothing to that but time)
class DistributedRunResume : public DistributedRun {};

TEST_P(DistributedRunResume, ResumesOnAnotherNumberOfRanks) {
  if (kUnderSanitizers && GetParam() != "spheres_redealt")
    GTEST_SKIP() << kSkippedUnderSanitizers
                 << "the re-dealt spheres resume 2 -> 1 and 1 -> 3 there (checkpoints of runs on "
                    "ranks, contact across ranks, rebalancing); the bars and walls run on ranks "
                    "in DistributedRun.*";
  const fs::path scene = write_scene(GetParam() + "_resume", scene_text());
  const SceneCase sc = scene_case(GetParam());
  const std::string half = sc.half_time;
  const fs::path straight = tmp_dir() / (GetParam() + "_straight");
  ASSERT_EQ(run(1, scene, straight).code, 0);
  // started on 2 ranks, finished in one process; started in one, finished on 3
  for (const auto& [first, second] : {std::pair{2, 1}, std::pair{1, 3}}) {
    SCOPED_TRACE(std::to_string(first) + " then " + std::to_string(second) + " ranks");
    const fs::path out = tmp_dir() / (GetParam() + "_resumed_" + std::to_string(first) + "_" +
                                      std::to_string(second));
    const CommandResult a = run(first, scene, out, "--set simulation.end_time=" + half);
    ASSERT_EQ(a.code, 0) << a.output;
    const CommandResult b = femdem(
        second, "resume '" + out.string() + "' --quiet --set simulation.end_time=" + sc.end_time);
    ASSERT_EQ(b.code, 0) << b.output;
    // (the resumed run's summary has the end time it was extended to, as the straight run's)
    expect_same_run(straight, out, kCutBodyRestitution);
  }
}

INSTANTIATE_TEST_SUITE_P(Bars, DistributedRun, ::testing::Values("elastic_bar", "plastic_bar"));
INSTANTIATE_TEST_SUITE_P(Walls, DistributedRun,
                         ::testing::Values("taylor_bar", "die_press", "taylor_bar_mass_scaling"));
INSTANTIATE_TEST_SUITE_P(Contact, DistributedRun,
                         ::testing::Values("hertz_pair", "spheres_damped", "compaction_64",
                                           "spheres_redealt"));
INSTANTIATE_TEST_SUITE_P(Bars, DistributedRunResume,
                         ::testing::Values("elastic_bar", "plastic_bar"));
INSTANTIATE_TEST_SUITE_P(Walls, DistributedRunResume,
                         ::testing::Values("taylor_bar", "die_press", "taylor_bar_mass_scaling"));
INSTANTIATE_TEST_SUITE_P(Contact, DistributedRunResume,
                         ::testing::Values("spheres_damped", "spheres_redealt"));

const char* const kMetal = R"([[materials]]
name = "metal"
model = "elastic"
density = 2700.0
youngs_modulus = 70e9
poisson_ratio = 0.3
)";

// Exit code 2 and the message once (rank 0 reports what every rank finds).
void expect_refused_once(const CommandResult& c, const std::string& message) {
  EXPECT_EQ(c.code, 2) << c.output;
  const auto at = c.output.find(message);
  ASSERT_NE(at, std::string::npos) << c.output;
  EXPECT_EQ(c.output.find(message, at + 1), std::string::npos) << c.output;
}

TEST(DistributedRunRefusal, WhatRanksCannotDoYetExitsTwoFromEveryRankWithOneMessage) {
  const fs::path scene = write_scene("two_bodies", R"(title = "two bodies"
[simulation]
end_time = 1e-5

[contact]
impact_damping = 0.5

)" + std::string(kMetal) + R"(
[[bodies]]
name = "a"
material = "metal"
mesh = { generator = "box", size = [0.01, 0.01, 0.01], element_size = 0.005 }

[[bodies]]
name = "b"
material = "metal"
mesh = { generator = "box", size = [0.01, 0.01, 0.01], element_size = 0.005 }
position = [0.0, 0.0, 0.02]
)");
  const fs::path out = tmp_dir() / "two_bodies";
  // (two bodies on 3 ranks: each is cut, its patches summed per rank)
  const CommandResult c = run(3, scene, out);
  // one message, from rank 0, naming what is missing
  expect_refused_once(c, "impact_damping or rolling_resistance on a body cut among ranks");
  EXPECT_FALSE(fs::exists(out / "results.h5"));
  // a scene too small for the ranks: two elements on 3 ranks
  const fs::path tiny = write_scene("two_elements", (std::string(R"(title = "two elements"
[simulation]
end_time = 1e-6

)" + std::string(kMetal) + R"(
[[bodies]]
name = "a"
material = "metal"
mesh = { file = ")") + FEMDEM_SOURCE_DIR + "/tests/data/two_tet10_v41.msh\" }\n")
                                                        .c_str());
  const CommandResult small = run(3, tiny, tmp_dir() / "two_elements");
  expect_refused_once(small, "cannot be split among 3 ranks");
  // a layout of ranks and threads that cannot be: refused once, every rank exits 2
  const CommandResult threads = femdem(2, "run '" + scene.string() + "' --threads -2");
  expect_refused_once(threads, "--threads");
  // commands other than run and resume run as one process
  const CommandResult check = femdem(2, "check '" + scene.string() + "'");
  EXPECT_EQ(check.code, 2) << check.output;
  EXPECT_NE(check.output.find("only run and resume take several ranks"), std::string::npos)
      << check.output;
}

// A rank that cannot read its scene while rank 0 can (as on a cluster whose ranks do not share
// the folder; here mpirun gives each rank its own command line): every rank exits 2 at once,
// rank 1 saying why, once, and nothing is written. (Before the start agreement rank 0 waited for
// rank 1 in its first collective call forever.)
TEST(DistributedRunRefusal, ARankThatCannotReadItsSceneStopsEveryRank) {
  const fs::path scene = write_scene("readable_bar", kElasticBar);
  const fs::path missing = tmp_dir() / "no_such_scene.toml";
  const fs::path out = tmp_dir() / "one_rank_fails";
  fs::remove_all(out);
  const std::string rank =
      std::string(" -np 1 -x OMP_NUM_THREADS=1 -x ASAN_OPTIONS=detect_leaks=0 '") + FEMDEM_EXE +
      "' run ";
  const std::string tail = " --quiet --threads 1 --out '" + out.string() + "'";
  const auto start = std::chrono::steady_clock::now();
  const CommandResult c = run_command(
      "timeout 120 '" + std::string(FEMDEM_MPIEXEC) + "' --oversubscribe --allow-run-as-root" +
      rank + "'" + scene.string() + "'" + tail + " :" + rank + "'" + missing.string() + "'" + tail);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(c.code, 2) << c.output;  // (124: timeout's, the ranks hung)
  EXPECT_LT(seconds, 60.0) << c.output;
  const std::string said = "error (rank 1 of 2): ";
  const auto at = c.output.find(said);
  ASSERT_NE(at, std::string::npos) << c.output;
  EXPECT_NE(c.output.find("no_such_scene.toml", at), std::string::npos) << c.output;
  EXPECT_EQ(c.output.find(said, at + 1), std::string::npos) << c.output;  // (once)
  EXPECT_EQ(c.output.find("error: "), std::string::npos) << c.output;     // (rank 0 quiet)
  EXPECT_FALSE(fs::exists(out / "results.h5"));
}

// `femdem sweep --launcher 'mpirun -np 2'`: every run of the sweep on 2 ranks, each the run one
// process makes in a plain sweep.
TEST(DistributedRunSweep, EachRunOnRanksIsTheOneProcessRun) {
  const fs::path scene = write_scene("sweep_bar", kElasticBar);
  const fs::path plain = tmp_dir() / "sweep_plain", ranked = tmp_dir() / "sweep_ranks";
  const std::string vary =
      "sweep '" + scene.string() +
      "' --quiet --no-plot --jobs 1 --vary 'bodies.bar.velocity=[1e-4,0,0],[2e-4,0,0]' "
      "--set simulation.end_time=2.0 --out '";
  fs::remove_all(plain);
  fs::remove_all(ranked);
  const CommandResult a = femdem(1, vary + plain.string() + "'");
  ASSERT_EQ(a.code, 0) << a.output;
  const CommandResult b = femdem(1, vary + ranked.string() + "' --launcher '" + FEMDEM_MPIEXEC +
                                        " -np 2 --oversubscribe --allow-run-as-root -x "
                                        "OMP_NUM_THREADS=1 -x ASAN_OPTIONS=detect_leaks=0'");
  ASSERT_EQ(b.code, 0) << b.output;
  int runs = 0;
  for (const auto& entry : fs::directory_iterator(plain)) {
    if (!fs::exists(entry.path() / "history.csv")) continue;
    const fs::path other = ranked / entry.path().filename();
    expect_same_run(entry.path(), other);
    EXPECT_NE(read_text(other / "run.log").find("in each of 2 ranks"), std::string::npos) << other;
    ++runs;
  }
  EXPECT_EQ(runs, 2);
}

}  // namespace
}  // namespace femdem::test
