// SPDX-License-Identifier: GPL-3.0-or-later
// `femdem sweep` (FEMDEM_EXE): value lists, sweep.csv against each run's summary.json, the
// physics following a varied value, validation before any run, resume, jobs, divergence.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "support/run_command.hpp"
#include "tools/femdem/sweep/sweep.hpp"

namespace {

namespace fs = std::filesystem;
using Result = femdem::test::CommandResult;
using femdem::split_value_list;

fs::path tmp_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "sweep" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Result femdem_in(const fs::path& cwd, const std::string& args) {
  return femdem::test::run_command("cd '" + cwd.string() + "' && '" + FEMDEM_EXE + "' " + args);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A CSV file (RFC 4180 quoting) as a header and rows of column -> text.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

Csv read_csv(const fs::path& p) {
  const std::string text = read_text(p);
  std::vector<std::vector<std::string>> lines(1);
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      lines.back().push_back(field);
      field.clear();
    } else if (c == '\n') {
      lines.back().push_back(field);
      field.clear();
      lines.emplace_back();
    } else {
      field += c;
    }
  }
  if (lines.back().empty()) lines.pop_back();
  Csv csv;
  if (lines.empty()) return csv;
  csv.header = lines[0];
  for (std::size_t r = 1; r < lines.size(); ++r) {
    EXPECT_EQ(lines[r].size(), csv.header.size()) << "row " << r << " of " << p;
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < csv.header.size() && c < lines[r].size(); ++c)
      row[csv.header[c]] = lines[r][c];
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

std::string bar_scene() {
  return std::string(FEMDEM_SOURCE_DIR) + "/scenes/bar_vibration.toml";
}
// A few dozen steps of the bar.
const std::string kShortBar =
    " --set simulation.end_time=0.2 --set simulation.output_interval=0.1 --no-plot";

// A free elastic cube, nothing touching it: its kinetic energy stays 1/2 m v^2.
const char* kFreeCube = R"(title = "sweep test: free cube"
[simulation]
end_time = 2e-5
output_interval = 1e-5

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
velocity = [1.0, 0.0, 0.0]
)";

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

double num(const std::string& s) {
  EXPECT_FALSE(s.empty());
  return std::stod(s);
}

// --- value lists ------------------------------------------------------------------------------

TEST(SweepValues, ArraysAreNotSplitAtTheirCommas) {
  using V = std::vector<std::string>;
  EXPECT_EQ(split_value_list("[0,0,-5],[0,0,-10]", "k"), (V{"[0,0,-5]", "[0,0,-10]"}));
  EXPECT_EQ(split_value_list("1e-3, 2e-3 ,5", "k"), (V{"1e-3", "2e-3", "5"}));
  EXPECT_EQ(split_value_list("\"a,b\",c", "k"), (V{"\"a,b\"", "c"}));
  EXPECT_EQ(split_value_list("{ generator = \"sphere\", radius = 1 },[[0,1],[2,3]]", "k"),
            (V{"{ generator = \"sphere\", radius = 1 }", "[[0,1],[2,3]]"}));
}

TEST(SweepValues, Ranges) {
  using V = std::vector<std::string>;
  EXPECT_EQ(split_value_list("10:50:20", "k"), (V{"10", "30", "50"}));
  EXPECT_EQ(split_value_list("0.1:0.3:0.1", "k"), (V{"0.1", "0.2", "0.3"}));
  EXPECT_EQ(split_value_list("5:1:-2", "k"), (V{"5", "3", "1"}));
  EXPECT_EQ(split_value_list("linspace(0,1,3)", "k"), (V{"0.0", "0.5", "1.0"}));
  EXPECT_EQ(split_value_list("logspace(1e-3,1e-1,3),7", "k"), (V{"0.001", "0.01", "0.1", "7"}));
  EXPECT_EQ(split_value_list("a:b", "k"), (V{"a:b"}));  // not numbers: a plain value
}

TEST(SweepValues, Errors) {
  EXPECT_THROW(split_value_list("1,,2", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("[1,2", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("1,1", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("1:5:-1", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("1:5", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("linspace(0,1)", "k"), femdem::InputError);
  EXPECT_THROW(split_value_list("logspace(0,1,3)", "k"), femdem::InputError);
}

// --- the program ------------------------------------------------------------------------------

// 2 x 2: four rows, the right varied values, every number equal to the run's own summary.json.
TEST(Sweep, TwoByTwoMatchesEachRunsSummary) {
  const fs::path d = tmp_dir("two_by_two");
  const Result r =
      femdem_in(d, "sweep '" + bar_scene() +
                       "' --vary materials.bar.youngs_modulus=100,400"
                       " --vary 'bodies.bar.velocity=[1e-4,0,0],[2e-4,0,0]' --out s --jobs 2" +
                       kShortBar);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "[4/4]")) << r.output;
  const Csv csv = read_csv(d / "s" / "sweep.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  ASSERT_GE(csv.header.size(), 3u);
  EXPECT_EQ(csv.header[0], "materials.bar.youngs_modulus");
  EXPECT_EQ(csv.header[1], "bodies.bar.velocity");
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"100", "[1e-4,0,0]"}, {"100", "[2e-4,0,0]"}, {"400", "[1e-4,0,0]"}, {"400", "[2e-4,0,0]"}};
  std::set<std::string> dirs;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& row = csv.rows[i];
    EXPECT_EQ(row.at("materials.bar.youngs_modulus"), expected[i].first);
    EXPECT_EQ(row.at("bodies.bar.velocity"), expected[i].second);
    EXPECT_EQ(row.at("status"), "completed");
    EXPECT_EQ(row.at("exit_code"), "0");
    dirs.insert(row.at("run"));
    const nlohmann::json s = read_json(d / "s" / row.at("run") / "summary.json");
    EXPECT_EQ(std::stoll(row.at("steps")), s["steps"].get<long long>());
    EXPECT_EQ(num(row.at("wall_time_s")), s["wall_time_s"].get<double>());
    EXPECT_EQ(num(row.at("time_step")), s["time_step"].get<double>());
    for (const char* e : {"kinetic", "internal", "external_work", "balance_error"})
      EXPECT_EQ(num(row.at(std::string("energy.") + e)), s["energy"][e].get<double>()) << e;
    const auto& b = s["bodies"]["bar"];
    EXPECT_EQ(num(row.at("bodies.bar.kinetic_energy")), b["kinetic_energy"].get<double>());
    EXPECT_EQ(num(row.at("bodies.bar.com.x")), b["com"][0].get<double>());
    EXPECT_EQ(num(row.at("bodies.bar.bbox_max.x")), b["bbox_max"][0].get<double>());
    EXPECT_EQ(num(row.at("bodies.bar.max_equivalent_plastic_strain")),
              b["max_equivalent_plastic_strain"].get<double>());
    EXPECT_EQ(row.at("bodies.bar.coefficient_of_restitution.com"), "");  // null: no contact
    EXPECT_EQ(num(row.at("extra.stable_time_step")), s["extra"]["stable_time_step"].get<double>());
    // the run really used the varied values
    const std::string log = read_text(d / "s" / row.at("run") / "run.log");
    EXPECT_TRUE(contains(log, "youngs_modulus = " + expected[i].first)) << log;
  }
  EXPECT_EQ(dirs.size(), 4u);
  EXPECT_TRUE(fs::exists(d / "s" / "youngs_modulus=100__velocity=1e-4,0,0" / "summary.json"));
  // the stiffer bar has the smaller stable step
  EXPECT_LT(num(csv.rows[2].at("extra.stable_time_step")),
            num(csv.rows[0].at("extra.stable_time_step")));
}

// Kinetic energy of a free body: x4 for twice the speed, x2 for twice the density.
TEST(Sweep, VariedValuesChangeThePhysics) {
  const fs::path d = tmp_dir("physics");
  std::ofstream(d / "cube.toml") << kFreeCube;
  const Result r = femdem_in(d,
                             "sweep cube.toml --vary 'bodies.cube.velocity=[1,0,0],[2,0,0]'"
                             " --vary materials.steel.density=4000:8000:4000 --no-plot --quiet");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, "");  // --quiet
  const Csv csv = read_csv(d / "out" / "cube_sweep" / "sweep.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  auto ke = [&](std::size_t i) { return num(csv.rows[i].at("bodies.cube.kinetic_energy")); };
  // rows: (v1, 4000), (v1, 8000), (v2, 4000), (v2, 8000)
  EXPECT_EQ(csv.rows[1].at("materials.steel.density"), "8000");
  EXPECT_NEAR(ke(0), 0.5 * 4000 * 1e-3 * 1.0, 1e-9 * ke(0));
  EXPECT_NEAR(ke(2) / ke(0), 4.0, 1e-9);
  EXPECT_NEAR(ke(1) / ke(0), 2.0, 1e-9);
  EXPECT_NEAR(ke(3) / ke(0), 8.0, 1e-9);
  EXPECT_NEAR(num(csv.rows[3].at("energy.kinetic")), ke(3), 1e-12 * ke(3));
}

// A string-valued axis (which material a body is made of) crossed with a numeric one: plain and
// quoted strings both work, the CSV keeps the values as given, the folders are named after them.
TEST(Sweep, StringValuesSelectTheBodysMaterial) {
  const fs::path d = tmp_dir("strings");
  std::ofstream(d / "cube.toml") << kFreeCube << R"(
[[materials]]
name = "light"
model = "von_mises"
density = 2000
youngs_modulus = 40e9
poisson_ratio = 0.17
yield_stress = 60e6
)";
  const Result r = femdem_in(d,
                             "sweep cube.toml --vary 'bodies.cube.material=steel,\"light\"'"
                             " --vary 'bodies.cube.velocity=[1,0,0],[2,0,0]' --no-plot --quiet");
  ASSERT_EQ(r.code, 0) << r.output;
  const Csv csv = read_csv(d / "out" / "cube_sweep" / "sweep.csv");
  ASSERT_EQ(csv.rows.size(), 4u);
  EXPECT_EQ(csv.header[0], "bodies.cube.material");
  EXPECT_EQ(csv.rows[0].at("bodies.cube.material"), "steel");
  EXPECT_EQ(csv.rows[3].at("bodies.cube.material"), "\"light\"");
  EXPECT_EQ(csv.rows[0].at("run"), "material=steel__velocity=1,0,0");
  EXPECT_EQ(csv.rows[3].at("run"), "material=light__velocity=2,0,0");
  // the mass follows the material: 8000 and 2000 kg/m^3 times 1e-3 m^3
  EXPECT_NEAR(num(csv.rows[0].at("bodies.cube.mass")), 8.0, 1e-9);
  EXPECT_NEAR(num(csv.rows[2].at("bodies.cube.mass")), 2.0, 1e-9);
  EXPECT_NEAR(num(csv.rows[3].at("bodies.cube.kinetic_energy")), 0.5 * 2.0 * 4.0, 1e-9);
  const std::string log = read_text(d / "out" / "cube_sweep" / csv.rows[2].at("run") / "run.log");
  EXPECT_TRUE(contains(log, "material = \"light\"")) << log;
  // a material that does not exist is named before anything runs
  const Result bad = femdem_in(d,
                               "sweep cube.toml --vary bodies.cube.material=steel,concrete"
                               " --out bad --no-plot");
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_TRUE(contains(bad.output, "concrete")) << bad.output;
  EXPECT_FALSE(fs::exists(d / "bad"));
}

TEST(Sweep, BadKeyOrValueRunsNothing) {
  const fs::path d = tmp_dir("bad");
  struct Case {
    std::string vary, must_name;
  };
  const std::vector<Case> cases = {
      {"'bodies.bar.velocty=[1,0,0],[2,0,0]'", "bodies.bar.velocty"},
      {"'bodies.rod.velocity=[1,0,0]'", "bodies.rod.velocity"},
      {"materials.bar.youngs_modulus=100,-5", "-5"},
      {"materials.bar.youngs_modulus=100,fast", "fast"},
      {"'bodies.bar.velocity=[1,0,0],[1,0]'", "[1,0]"},
      {"materials.bar.youngs_modulus=1:5:-1", "materials.bar.youngs_modulus"},
      {"materials.bar.youngs_modulus", "--vary"},
  };
  for (const auto& c : cases) {
    const Result r = femdem_in(d, "sweep '" + bar_scene() + "' --vary " + c.vary +
                                      " --vary materials.bar.density=1,2 --out s" + kShortBar);
    EXPECT_EQ(r.code, 2) << c.vary << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, c.must_name)) << c.vary << "\n" << r.output;
    EXPECT_FALSE(fs::exists(d / "s")) << c.vary;
  }
  // a key both set and varied, and a key varied twice
  Result r = femdem_in(d, "sweep '" + bar_scene() +
                              "' --vary simulation.end_time=0.1,0.2 --set simulation.end_time=1"
                              " --out s --no-plot");
  EXPECT_EQ(r.code, 2) << r.output;
  r = femdem_in(d, "sweep '" + bar_scene() +
                       "' --vary simulation.end_time=0.1 --vary simulation.end_time=0.2 --out s"
                       " --no-plot");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_FALSE(fs::exists(d / "s"));
}

TEST(Sweep, ResumeSkipsCompletedRuns) {
  const fs::path d = tmp_dir("resume");
  const std::string base =
      "sweep '" + bar_scene() + "' --out s --jobs 2" + kShortBar + " --vary materials.bar.density=";
  Result r = femdem_in(d, base + "1,2");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string csv1 = read_text(d / "s" / "sweep.csv");
  std::map<std::string, fs::file_time_type> stamps;
  for (const auto& row : read_csv(d / "s" / "sweep.csv").rows)
    stamps[row.at("run")] = fs::last_write_time(d / "s" / row.at("run") / "summary.json");
  ASSERT_EQ(stamps.size(), 2u);

  // the same sweep again: nothing reruns, the CSV is the same
  r = femdem_in(d, base + "1,2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "2 already completed")) << r.output;
  EXPECT_FALSE(contains(r.output, "[1/2]")) << r.output;
  EXPECT_EQ(read_text(d / "s" / "sweep.csv"), csv1);
  for (const auto& [run, t] : stamps)
    EXPECT_EQ(fs::last_write_time(d / "s" / run / "summary.json"), t) << run;

  // one more value: only it runs; a run whose scene changed (--set) reruns
  r = femdem_in(d, base + "1,2,3");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "2 already completed")) << r.output;
  EXPECT_TRUE(contains(r.output, "running 1")) << r.output;
  EXPECT_EQ(read_csv(d / "s" / "sweep.csv").rows.size(), 3u);
  r = femdem_in(d, base + "1 --set contact.friction=0.1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(contains(r.output, "already completed")) << r.output;
  EXPECT_TRUE(contains(r.output, "running 1")) << r.output;
}

TEST(Sweep, ResumesInterruptedRunsFromTheirCheckpoints) {
  const fs::path d = tmp_dir("resume_interrupted");
  const std::string args = "sweep '" + bar_scene() + "' --out s --jobs 1 --no-plot" + kShortBar +
                           " --vary materials.bar.density=1,2";
  Result r = femdem_in(d, args);
  ASSERT_EQ(r.code, 0) << r.output;
  const Csv before = read_csv(d / "s" / "sweep.csv");
  ASSERT_EQ(before.rows.size(), 2u);
  // the first run as a kill leaves it: its checkpoint, no summary
  const fs::path run = d / "s" / before.rows[0].at("run");
  ASSERT_TRUE(fs::exists(run / "checkpoint.h5"));
  fs::remove(run / "summary.json");
  r = femdem_in(d, args);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "1 already completed")) << r.output;
  EXPECT_TRUE(contains(r.output, "1 of them resumed from their checkpoints")) << r.output;
  EXPECT_TRUE(contains(read_text(run / "run.log"), "# resumed")) << "rerun, not resumed";
  const Csv after = read_csv(d / "s" / "sweep.csv");
  ASSERT_EQ(after.header, before.header);
  const std::set<std::string> timing = {"wall_time_s", "extra.setup_time_s", "extra.loop_time_s",
                                        "extra.element_updates_per_s"};
  for (std::size_t i = 0; i < before.rows.size(); ++i)
    for (const auto& col : before.header) {
      if (timing.count(col)) continue;
      EXPECT_EQ(before.rows[i].at(col), after.rows[i].at(col)) << col << " row " << i;
    }
}

TEST(Sweep, JobsDoNotChangeTheNumbers) {
  const fs::path d = tmp_dir("jobs");
  const std::string args = "sweep '" + bar_scene() + "'" + kShortBar +
                           " --vary materials.bar.poisson_ratio=0,0.2,0.3"
                           " --vary 'bodies.bar.velocity=[1e-4,0,0],[0,1e-4,0]'";
  Result r1 = femdem_in(d, args + " --jobs 1 --out j1");
  ASSERT_EQ(r1.code, 0) << r1.output;
  Result r2 = femdem_in(d, args + " --jobs 2 --out j2");
  ASSERT_EQ(r2.code, 0) << r2.output;
  const Csv a = read_csv(d / "j1" / "sweep.csv"), b = read_csv(d / "j2" / "sweep.csv");
  ASSERT_EQ(a.header, b.header);
  ASSERT_EQ(a.rows.size(), 6u);
  ASSERT_EQ(b.rows.size(), 6u);
  const std::set<std::string> timing = {"wall_time_s", "extra.setup_time_s", "extra.loop_time_s",
                                        "extra.element_updates_per_s"};
  for (std::size_t i = 0; i < a.rows.size(); ++i)
    for (const auto& col : a.header) {
      if (timing.count(col)) continue;
      EXPECT_EQ(a.rows[i].at(col), b.rows[i].at(col)) << col << " row " << i;
    }
}

// A run that diverges: exit code 3, its row says so, the other runs are in the CSV.
TEST(Sweep, DivergedRunGivesExitCode3) {
  const fs::path d = tmp_dir("diverged");
  const Result r =
      femdem_in(d, "sweep '" + bar_scene() +
                       "' --set simulation.end_time=0.5 --set simulation.output_interval=0.25"
                       " --vary simulation.time_step=5e-3,0.05 --out s --no-plot");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_TRUE(contains(r.output, "DIVERGED")) << r.output;
  const Csv csv = read_csv(d / "s" / "sweep.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0].at("status"), "completed");
  EXPECT_EQ(csv.rows[1].at("status"), "unstable");
  EXPECT_EQ(csv.rows[1].at("exit_code"), "3");
  EXPECT_NE(csv.rows[1].at("steps"), "");  // an unstable run still has its summary
}

// The plots, when python3 and matplotlib are there.
TEST(Sweep, Plots) {
  if (femdem::test::run_command("/usr/bin/python3 -c 'import matplotlib'").code != 0 &&
      femdem::test::run_command("python3 -c 'import matplotlib'").code != 0)
    GTEST_SKIP() << "no python3/matplotlib";
  const fs::path d = tmp_dir("plots");
  const Result r = femdem_in(d, "sweep '" + bar_scene() +
                                    "' --set simulation.end_time=0.2"
                                    " --vary materials.bar.youngs_modulus=100,200"
                                    " --vary materials.bar.density=1,2 --out s");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(d / "s" / "wall_time.png")) << r.output;
  EXPECT_TRUE(fs::exists(d / "s" / "energy_balance_error.png")) << r.output;
  EXPECT_TRUE(fs::exists(d / "s" / "kinetic_energy.png")) << r.output;
}

}  // namespace
