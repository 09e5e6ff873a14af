// SPDX-License-Identifier: GPL-3.0-or-later
// Compaction through the femdem program: the [compaction] columns of history.csv and the
// summary, checked against answers computed here from the geometry and the material alone
// (uniaxial strain in a filled rigid die, uniaxial stress of a cube standing free in it), the
// force balance of the powder, unloading and ejection, and bad [compaction] input.
//
// The powder is one elastic (or von Mises) 4 mm cube, 48 TET10, E = 1 GPa, nu = 0.3, pushed by
// a punch that reaches 0.1 m/s in 0.1 ms: a thousand times slower than the wave speed
// (1.16 km/s), so the response is quasi-static within about 1 %.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "engine/errors.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/history_csv.hpp"
#include "support/run_command.hpp"
#include "support/scene_run.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kE = 1e9, kNu = 0.3, kSide = 4e-3;

struct Options {
  double die_radius = 2e-3;  // inscribed: 2 mm is a square die the cube fills exactly
  double die_friction = 0.0;
  std::string die_extra;  // more keys of the die table
  std::string material = "model = \"elastic\"";
  std::string punch_motion = "velocity_history = [[0, 0, 0, 0], [1e-4, 0, 0, -0.1]]";
  std::string bottom_motion;
  double end_time = 0.5e-3;
  std::string compaction_extra;
  double height = 4e-3;  // of the cube (a tablet when below 4 mm)
  // of every wall. The columns are checked against the continuum answer, so the walls are
  // stiff: with the automatic stiffness the node springs of the two walls would take 17 % of
  // the 2-element cube's shortening (test_compaction.cpp checks that compliance).
  double penalty_factor = 100;
  double element_size = 2e-3;
  int threads = 1;
  double history_interval = 5e-6;
};

// a number as TOML reads it back exactly (std::to_string would print 2.5e-7 as 0.000000)
std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}

std::string scene_text(const Options& o) {
  const double c = 0.5 * kSide;
  const std::string pf =
      o.penalty_factor > 0 ? "penalty_factor = " + num(o.penalty_factor) + "\n" : std::string();
  std::string s = R"(title = "compaction test"
[simulation]
end_time = )" + num(o.end_time) +
                  R"(
output_interval = )" +
                  num(o.end_time / 2) +
                  R"(
history_interval = )" +
                  num(o.history_interval) + R"(
[[materials]]
name = "m"
)" + o.material + R"(
density = 1000
youngs_modulus = 1e9
poisson_ratio = 0.3
[[bodies]]
name = "cube"
material = "m"
mesh = { generator = "box", size = [4e-3, 4e-3, )" +
                  num(o.height) + R"(], element_size = )" + num(o.element_size) + R"( }
[[walls]]
name = "bottom"
point = [)" + num(c) +
                  ", " + num(c) +
                  R"(, 0]
normal = [0, 0, 1]
)" + pf + o.bottom_motion +
                  R"(
[[walls]]
name = "punch"
point = [0, 0, )" +
                  num(o.height) + R"(]
normal = [0, 0, -1]
)" + pf + o.punch_motion +
                  R"(
[compaction]
punch = "punch"
bottom = "bottom"
die = { radius = )" +
                  num(o.die_radius) + ", sides = 4, friction = " + num(o.die_friction) +
                  o.die_extra +
                  (o.penalty_factor > 0 ? ", penalty_factor = " + num(o.penalty_factor)
                                        : std::string()) +
                  " }\n" + o.compaction_extra + "\n";
  return s;
}

struct RunResult {
  std::map<std::string, std::vector<double>> h;
  nlohmann::json summary;
};

RunResult run_scene(const std::string& name, const Options& o) {
  auto r = femdem::test::run_scene_text("compaction/" + name, scene_text(o),
                                        "--threads " + std::to_string(o.threads));
  EXPECT_EQ(r.command.code, 0) << r.command.output;
  return {std::move(r.history), std::move(r.summary)};
}

double last(const std::vector<double>& v) {
  return v.back();
}

// The mean of the last n rows: the wall forces ring around their quasi-static trend (+-2 % row to
// row on the 2-element cube), so a balance read from one row depends on where in the ringing the
// run ends (measured at the last row: +0.47 % at safety 0.5, +2.55 % at 0.8; over 10 rows +0.17 %).
double last_mean(const std::vector<double>& v, std::size_t n) {
  double s = 0.0;
  for (std::size_t i = v.size() - n; i < v.size(); ++i) s += v[i];
  return s / static_cast<double>(n);
}

}  // namespace

// A filled frictionless die: uniaxial strain. With Hencky elasticity the Kirchhoff stresses are
// exactly tau_a = (lambda + 2G) e and tau_r = lambda e for the axial log strain e = ln(h/h0),
// J = h / h0, so the Cauchy punch pressure is (lambda + 2G) |e| / J, the die-wall pressure is
// nu / (1 - nu) of it, the solid volume is A h (D = 1, V/V0 = h/h0), and the bottom carries
// the punch force. The walls' penalty (factor 1000 here) lets each face sink in by about
// p h_e / (1000 E) (h_e the element depth), 0.14 % of the strain; with the default 100 it would
// be 1.4 %, which is why D comes out a little above 1.
TEST(CompactionRuns, FilledFrictionlessDieIsUniaxialStrain) {
  Options o;
  o.penalty_factor = 1000;
  const RunResult r = run_scene("filled", o);
  const auto& h = r.h;
  ASSERT_TRUE(h.count("compaction.punch_pressure")) << "no compaction columns";
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), G = kE / (2 * (1 + kNu));
  const double height = last(h.at("compaction.height")), h0 = h.at("compaction.height").front();
  EXPECT_DOUBLE_EQ(h0, kSide);
  // the column height is the walls' gap, from their own position columns
  EXPECT_NEAR(height, last(h.at("punch.position_z")) - last(h.at("bottom.position_z")), 1e-15);
  const double e = std::log(height / h0), J = height / h0;
  ASSERT_LT(e, -0.01);  // compressed by more than 1 %
  const double P = last(h.at("compaction.punch_pressure"));
  const double P_theory = -(lambda + 2 * G) * e / J;
  const double area = kSide * kSide;
  const double punch_force = last(h.at("punch.force_z"));  // the cube pushes the punch up
  std::printf(
      "P %.5g MPa, theory %.5g MPa (%+.2f %%); radial %.5g MPa, nu/(1-nu) P %.5g MPa; "
      "D %.6f; V/V0 %.6f, h/h0 %.6f\n",
      P / 1e6, P_theory / 1e6, 100 * (P / P_theory - 1),
      last(h.at("compaction.radial_pressure")) / 1e6, kNu / (1 - kNu) * P / 1e6,
      last(h.at("compaction.relative_density")), last(h.at("compaction.volume_ratio")), J);
  EXPECT_NEAR(P / P_theory, 1.0, 0.01);
  EXPECT_NEAR(P, punch_force / area, 1e-9 * P);  // the die of radius 2 mm is 4 x 4 mm
  EXPECT_NEAR(last(h.at("compaction.radial_pressure")) / (kNu / (1 - kNu) * P), 1.0, 0.02);
  EXPECT_NEAR(last(h.at("compaction.relative_density")), 1.0, 1e-4);
  EXPECT_NEAR(h.at("compaction.relative_density").front(), 1.0, 1e-12);
  EXPECT_NEAR(last(h.at("compaction.volume_ratio")), J, 1e-4);
  EXPECT_NEAR(last(h.at("compaction.column_strain")), 1.0 - J, 1e-12);
  EXPECT_NEAR(last(h.at("compaction.bottom_force")) / last(h.at("compaction.punch_force")), 1.0,
              0.02);
  EXPECT_NEAR(last(h.at("compaction.die_axial_force")), 0.0, 1e-9 * punch_force);
  EXPECT_NEAR(last(h.at("compaction.punch_displacement")), h0 - height, 1e-15);
  // summary: the peak is the last row; Heckel needs D < 1, which a solid never reaches, so its
  // fit is empty (null), while Kawakita's column strain is defined
  const auto& c = r.summary.at("compaction");
  EXPECT_NEAR(c.at("max_punch_pressure").get<double>(), P, 1e-6 * P);
  EXPECT_NEAR(c.at("final_volume_change").get<double>(),
              last(h.at("compaction.volume_ratio")) - 1.0, 1e-12);
  EXPECT_TRUE(c.at("heckel").at("K").is_null());
  EXPECT_EQ(c.at("heckel").at("points").get<double>(), 0);
  EXPECT_GT(c.at("kawakita").at("points").get<double>(), 10);
}

// A cube standing free in a wider die (inscribed radius 3 mm, never touched): uniaxial stress.
// Hencky: tau_a = E e, lateral log strains -nu e, J = exp((1 - 2 nu) e), so the solid volume is
// a^3 (h/a)^(1 - 2 nu), D = that over (36 mm^2 x h), and the force is E e a^2 exp(-e).
TEST(CompactionRuns, FreeCubeGivesTheRelativeDensityOfItsVolume) {
  Options o;
  o.die_radius = 3e-3;
  const RunResult r = run_scene("free", o);
  const auto& h = r.h;
  const double area = 36e-6;
  for (std::size_t i = h.at("time").size() / 2; i < h.at("time").size(); i += 10) {
    const double height = h.at("compaction.height")[i];
    const double e = std::log(height / kSide);
    const double V = std::pow(kSide, 3) * std::pow(height / kSide, 1 - 2 * kNu);
    EXPECT_NEAR(h.at("compaction.solid_volume")[i] / V, 1.0, 2e-4) << "row " << i;
    EXPECT_NEAR(h.at("compaction.relative_density")[i] / (V / (area * height)), 1.0, 2e-4);
    const double F = -kE * e * kSide * kSide * std::exp(-e);
    EXPECT_NEAR(h.at("compaction.punch_force")[i] / F, 1.0, 0.03) << "row " << i;
    EXPECT_NEAR(h.at("compaction.punch_pressure")[i] / (F / area), 1.0, 0.03);
    EXPECT_EQ(h.at("compaction.die_normal_force")[i], 0.0);
  }
  EXPECT_NEAR(h.at("compaction.relative_density").front(), 64.0 / 144.0, 1e-12);
}

// With die-wall friction the powder hangs on the die: quasi-statically the punch force is the
// bottom's plus the friction the die walls take (along the axis).
TEST(CompactionRuns, PunchForceIsBottomPlusDieFriction) {
  Options o;
  o.die_friction = 0.3;
  const RunResult r = run_scene("friction", o);
  const auto& h = r.h;
  const double Fp = last_mean(h.at("compaction.punch_force"), 10),
               Fb = last_mean(h.at("compaction.bottom_force"), 10),
               Fd = last_mean(h.at("compaction.die_axial_force"), 10);
  std::printf(
      "last 10 rows: punch %.4g N, bottom %.4g N, die friction %.4g N: bottom + die %+.2f %% of "
      "punch\n",
      Fp, Fb, Fd, 100 * ((Fb + Fd) / Fp - 1));
  EXPECT_GT(Fd, 0.05 * Fp);  // friction matters here
  EXPECT_NEAR((Fb + Fd) / Fp, 1.0, 0.02);
  EXPECT_LT(Fb, Fp);
}

// Load a 2 mm tablet (plastically), unload by reversing the punch, then eject: the bottom
// rises and pushes the compact out through the die mouth (the die walls end 2.5 mm above the
// bottom). The walls follow their histories; the compact rides on the bottom, comes out, and
// the die then carries nothing. While the bottom starts the compact slowly, its force is the
// die-wall friction (the later 2 m/s push is far from quasi-static: the tablet chatters on the
// bottom).
TEST(CompactionRuns, UnloadingAndEjection) {
  Options o;
  o.height = 2e-3;
  o.material = "model = \"von_mises\"\nyield_stress = 5e6\nhardening_modulus = 1e8";
  o.die_friction = 0.2;
  o.die_extra = ", height = 2.5e-3";
  // down at 0.1 m/s until 0.6 ms (about 2.5 % strain), back up, then away at 3 m/s
  o.punch_motion =
      "velocity_history = [[0, 0, 0, 0], [1e-4, 0, 0, -0.1], [6e-4, 0, 0, -0.1], "
      "[7e-4, 0, 0, 0.1], [1e-3, 0, 0, 0.1], [1.2e-3, 0, 0, 3]]";
  // the bottom starts the tablet slowly (0.1 m/s from 1.3 to 1.6 ms), then pushes it out at 2 m/s
  const std::vector<std::array<double, 2>> bottom_v = {
      {0, 0}, {1.2e-3, 0}, {1.3e-3, 0.1}, {1.6e-3, 0.1}, {1.8e-3, 2.0}};
  std::ostringstream bm;
  bm << "velocity_history = [";
  for (const auto& [tv, v] : bottom_v) bm << "[" << tv << ", 0, 0, " << v << "], ";
  bm << "]";
  o.bottom_motion = bm.str();
  o.end_time = 3.1e-3;
  const RunResult r = run_scene("eject", o);
  const auto& h = r.h;
  const auto& t = h.at("time");
  // the walls follow the integrals of their histories
  auto bottom_z = [&](double s) {  // the trapezoid rule is exact for a piece-wise linear v
    double z = 0.0;
    for (std::size_t k = 0; k + 1 < bottom_v.size(); ++k) {
      const double t0 = bottom_v[k][0], t1 = std::min(s, bottom_v[k + 1][0]);
      if (t1 <= t0) break;
      const double v0 = bottom_v[k][1], dv = bottom_v[k + 1][1] - v0,
                   span = bottom_v[k + 1][0] - t0;
      z += v0 * (t1 - t0) + 0.5 * dv / span * (t1 - t0) * (t1 - t0);
    }
    if (s > bottom_v.back()[0]) z += bottom_v.back()[1] * (s - bottom_v.back()[0]);
    return z;
  };
  double eject = 0.0, fric = 0.0;
  std::size_t unloaded = 0, sliding = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(h.at("bottom.position_z")[i], bottom_z(t[i]), 1e-12) << "t = " << t[i];
    // sliding slowly (quasi-statically), the whole tablet inside the die
    if (t[i] > 1.35e-3 && t[i] < 1.6e-3) {
      eject += h.at("compaction.bottom_force")[i];
      fric -= h.at("compaction.die_axial_force")[i];
      ++sliding;
    }
    if (t[i] > 0.95e-3 && t[i] < 1.2e-3) unloaded = i;
  }
  ASSERT_GT(sliding, 10u);
  eject /= static_cast<double>(sliding);
  fric /= static_cast<double>(sliding);
  const double peak = r.summary.at("compaction").at("max_punch_force").get<double>();
  std::printf(
      "peak punch force %.4g N; after unloading: punch %.3g N, die normal %.4g N "
      "(residual); mean ejection force %.4g N, mean die friction %.4g N\n",
      peak, h.at("compaction.punch_force")[unloaded], h.at("compaction.die_normal_force")[unloaded],
      eject, fric);
  EXPECT_EQ(h.at("compaction.punch_force")[unloaded], 0.0);       // the punch has left
  EXPECT_GT(h.at("compaction.die_normal_force")[unloaded], 0.0);  // residual radial stress
  EXPECT_GT(eject, 0.0);
  EXPECT_NEAR(fric / eject, 1.0, 0.03);
  // out: above the mouth, nothing on the die, not left behind by the bottom
  const double z_end = last(h.at("cube.com_z"));
  EXPECT_GT(z_end - 1e-3, 2.5e-3);
  EXPECT_EQ(last(h.at("compaction.die_normal_force")), 0.0);
  EXPECT_GT(z_end - h.at("cube.com_z").front(), bottom_z(last(t)) - 2e-5);
}

// Bad [compaction] input stops `femdem check` with exit code 2, naming file, line and key.
TEST(CompactionRuns, BadKeysExitWithTwoNamingFileLineAndKey) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "compaction" / "bad";
  fs::create_directories(dir);
  struct Case {
    std::string name, extra, expected;
    Options o;
  };
  std::vector<Case> cases;
  auto add = [&](std::string name, std::string expected, auto edit) {
    Case c;
    c.name = std::move(name);
    c.expected = std::move(expected);
    edit(c.o);
    cases.push_back(std::move(c));
  };
  add("unknown_key",
      "scene.toml:32:1: compaction.powdr: unknown key 'powdr' (did you mean 'powder'?)",
      [](Options& o) { o.compaction_extra = "powdr = [\"cube\"]"; });
  add("die_key", "compaction.die.sids: unknown key 'sids' (did you mean 'sides'?)",
      [](Options& o) { o.die_extra = ", sids = 8"; });
  add("height", "compaction.die.height: must be positive, got -1",
      [](Options& o) { o.die_extra = ", height = -1"; });
  add("powder", "scene.toml:32:11: compaction.powder: unknown body 'cub' (did you mean 'cube'?)",
      [](Options& o) { o.compaction_extra = "powder = [\"cub\"]"; });
  add("fit", "compaction.fit_max_pressure: must be 0 (the largest pressure) or above",
      [](Options& o) { o.compaction_extra = "fit_min_pressure = 5e6\nfit_max_pressure = 1e6"; });
  add("mass", "walls.punch.mass: only a force-driven wall has a mass",
      [](Options& o) { o.punch_motion = "mass = 1.0"; });
  add("force_history", "walls.punch.force_history: row 2 must be [t, F] (2 numbers)",
      [](Options& o) { o.punch_motion = "force_history = [[0, 0], [1e-3]]\nmass = 1"; });
  add("force_mass", "walls.punch.mass: required value is missing",
      [](Options& o) { o.punch_motion = "force_history = [[0, 0], [1e-3, 10]]"; });
  add("both", "walls.punch.force_history: give either 'velocity_history'",
      [](Options& o) { o.punch_motion += "\nforce_history = [[0, 0]]\nmass = 1"; });
  for (const Case& c : cases) {
    const fs::path d = dir / c.name;
    fs::create_directories(d);
    std::ofstream(d / "scene.toml") << scene_text(c.o);
    const auto r = femdem::test::run_command("cd '" + d.string() + "' && '" + FEMDEM_EXE +
                                             "' check scene.toml");
    EXPECT_EQ(r.code, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.name << ": " << r.output;
  }
  // the punch and the bottom must face each other
  Options o;
  o.punch_motion = "";
  std::string text = scene_text(o);
  text.replace(text.find("normal = [0, 0, -1]"), 19, "normal = [1, 0, 0]");
  std::ofstream(dir / "facing.toml") << text;
  try {
    femdem::load_scene((dir / "facing.toml").string());
    ADD_FAILURE() << "accepted a punch that does not face the bottom";
  } catch (const femdem::InputError& e) {
    EXPECT_EQ(e.key, "compaction.punch") << e.describe();
    EXPECT_GT(e.line, 0);
  }
}

// The compaction columns are sums over elements and walls: with a mesh big enough for the
// parallel loops (750 elements), 1 and 2 threads must write the same history.csv, bit for bit.
TEST(CompactionRuns, OneAndTwoThreadsGiveIdenticalColumns) {
  Options o;
  o.element_size = 0.8e-3;
  o.end_time = 5e-6;
  o.history_interval = 2.5e-7;
  o.die_friction = 0.3;
  o.punch_motion = "velocity = [0, 0, -0.1]";  // from the start: contact within the short run
  std::string text[2];
  for (int threads : {1, 2}) {
    o.threads = threads;
    const std::string name = "threads" + std::to_string(threads);
    run_scene(name, o);
    std::ifstream in(fs::path(FEMDEM_TEST_TMP) / "compaction" / name / "out" / "history.csv");
    std::ostringstream ss;
    ss << in.rdbuf();
    text[threads - 1] = ss.str();
  }
  ASSERT_GT(text[0].size(), 1000u);
  EXPECT_TRUE(text[0] == text[1]) << "history.csv differs between 1 and 2 threads";
}
