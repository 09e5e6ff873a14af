// SPDX-License-Identifier: GPL-3.0-or-later
// Whole runs of the femdem program (FEMDEM_EXE) on the shipped scenes: the physics a user sees
// in history.csv and summary.json, determinism across thread counts, and what is left on disk
// when a run diverges, is interrupted or is killed.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/history_csv.hpp"
#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;

using Result = femdem::test::CommandResult;

Result run_femdem(const std::string& args) {
  return femdem::test::run_command(std::string("'") + FEMDEM_EXE + "' " + args);
}

fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "scenes" / name;
  fs::remove_all(d);
  return d;
}

std::string scene(const std::string& name) {
  return std::string(FEMDEM_SOURCE_DIR) + "/scenes/" + name;
}

// history.csv as columns
using femdem::test::read_history;

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

// VALIDATION.md section 1: the bar of seed 003 (E 100, rho 1, nu 0, L 10, fixed end, rollers),
// uniform initial velocity. The fixed end's wave makes the motion periodic with T = 4L/c = 4.0;
// the tip (and the centre of mass) follows it. Period within 1 %, energy within 0.5 % over the
// 10 periods of the scene.
TEST(Scenes, BarVibration) {
  const fs::path out = out_dir("bar");
  const Result r =
      run_femdem("run '" + scene("bar_vibration.toml") + "' --quiet --out '" + out.string() + "'");
  ASSERT_EQ(r.code, 0) << r.output;
  auto h = read_history(out / "history.csv");
  const auto& t = h["time"];
  const auto& x = h["bar.com_x"];
  ASSERT_GT(t.size(), 1000u);
  double mean = 0.0;
  for (double v : x) mean += v / x.size();
  std::vector<double> up;  // upward crossings of the mean
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < mean && x[i] >= mean)
      up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (mean - x[i - 1]) / (x[i] - x[i - 1]));
  ASSERT_GE(up.size(), 8u);
  const double period = (up.back() - up.front()) / (up.size() - 1);
  const double E0 = h["total_energy"][0];
  double drift = 0.0;
  for (double e : h["total_energy"]) drift = std::max(drift, std::fabs(e - E0) / E0);
  std::printf("bar scene: period %.5f (4.0), energy drift %.4f %%\n", period, 100 * drift);
  EXPECT_NEAR(period, 4.0, 0.04);
  EXPECT_LT(drift, 0.005);
  const auto s = read_json(out / "summary.json");
  EXPECT_EQ(s["status"], "completed");
  EXPECT_NEAR(s["end_time"].get<double>(), 40.0, 1e-12);
  EXPECT_NEAR(s["bodies"]["bar"]["mass"].get<double>(), 10.0, 1e-12);
}

// An elastic sphere dropped on a rigid wall comes back with its speed within 2 % (the energy
// left behind is in elastic vibrations). Coarse mesh to keep the test short.
TEST(Scenes, ElasticSphereRebounds) {
  const fs::path out = out_dir("drop");
  const Result r =
      run_femdem("run '" + scene("sphere_drop.toml") + "' --quiet --out '" + out.string() +
                 "' --set bodies.ball.mesh.element_size=2.5e-3 --set simulation.end_time=60e-6");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto s = read_json(out / "summary.json");
  const auto& e = s["bodies"]["ball"]["coefficient_of_restitution"];
  ASSERT_FALSE(e.is_null()) << "the ball must have touched the wall and left it";
  std::printf("sphere drop: restitution %.4f (com), %.4f (kinetic energy)\n",
              e["com"].get<double>(), e["kinetic_energy"].get<double>());
  EXPECT_NEAR(e["com"].get<double>(), 1.0, 0.02);
  EXPECT_LE(e["com"].get<double>(), 1.0 + 1e-3);  // no energy created
  EXPECT_LT(std::fabs(s["energy"]["balance_error"].get<double>()), 1e-3);
  EXPECT_GT(s["bodies"]["ball"]["vcom"][2].get<double>(), 0.9);  // moving up
  // summary.json's energies are the last history row's
  auto h = read_history(out / "history.csv");
  EXPECT_EQ(s["energy"]["balance_error"].get<double>(), h["energy_balance_error"].back());
  EXPECT_EQ(s["energy"]["external_work"].get<double>(), h["external_work"].back());
  EXPECT_EQ(s["energy"]["kinetic"].get<double>(), h["kinetic_energy"].back());
  EXPECT_EQ(s["energy"]["viscous_dissipation"].get<double>(), h["viscous_dissipation"].back());
}

// Oblique impact with Coulomb friction (scenes/oblique_impact.toml; VALIDATION.md section 3),
// against rigid-body impact theory with the measured normal restitution e. Sliding throughout
// (v_t / v_n = 5 > 7/2 mu (1 + e) = 2.1): the tangential impulse is mu (1 + e) m v_n, so
// v_t' = v_t - mu (1 + e) v_n and the spin is 5/2 (v_t - v_t') / R. Sticking (v_t = 0.5): the
// tangential impulse stays below mu (1 + e) m v_n, and the spin still equals the angular impulse
// over the inertia, 5/2 (v_t - v_t') / R. (Rolling is not exact: the sphere's tangential
// elasticity makes it leave spinning a little faster than v_t' / R, as Maw, Barber & Fawcett
// found.) Coarse mesh to keep the test short.
TEST(Scenes, ObliqueImpactFollowsRigidBodyTheory) {
  const double mu = 0.3, R = 0.01, vn = 1.0;
  for (const double vt : {5.0, 0.5}) {
    const fs::path out = out_dir("oblique_" + std::to_string(static_cast<int>(10 * vt)));
    const Result r =
        run_femdem("run '" + scene("oblique_impact.toml") + "' --quiet --out '" + out.string() +
                   "' --set bodies.ball.mesh.element_size=4e-3 --set 'bodies.ball.velocity=[" +
                   std::to_string(vt) + ",0,-1]'");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto s = read_json(out / "summary.json");
    const auto& ball = s["bodies"]["ball"];
    const double e = ball["vcom"][2].get<double>() / vn;
    const double vt_after = ball["vcom"][0].get<double>();
    const double spin = ball["angular_velocity"][1].get<double>();
    std::printf("v_t %.1f: e %.4f, v_t' %.4f m/s, spin %.2f rad/s (from the impulse %.2f)\n", vt, e,
                vt_after, spin, 2.5 * (vt - vt_after) / R);
    EXPECT_NEAR(e, 1.0, 0.02);
    if (vt > 7.0 / 2.0 * mu * (1 + e) * vn) {
      EXPECT_NEAR(vt_after, vt - mu * (1 + e) * vn, 0.01 * vt);
    } else {
      EXPECT_LT(vt - vt_after, mu * (1 + e) * vn);
      EXPECT_GT(vt - vt_after, 0.1 * vt);  // friction did act
    }
    // the lumped inertia of a coarse sphere is close to 2/5 m R^2
    EXPECT_NEAR(spin, 2.5 * (vt - vt_after) / R, 0.04 * 2.5 * (vt - vt_after) / R);
    EXPECT_LT(std::fabs(s["energy"]["balance_error"].get<double>()), 1e-3);
  }
}

// summary.json's maximum equivalent plastic strain of a yielding body is the largest over its
// Gauss points: at least the largest element average written in the last frame, and of the
// same size (a coarse Taylor bar, 10 us).
TEST(Scenes, SummaryReportsTheMaximumPlasticStrain) {
  const fs::path out = out_dir("taylor_short");
  const Result r =
      run_femdem("run '" + scene("taylor_bar.toml") + "' --quiet --out '" + out.string() +
                 "' --set bodies.rod.mesh.element_size=3.2e-3 --set "
                 "simulation.end_time=10e-6 --set simulation.output_interval=5e-6");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto s = read_json(out / "summary.json");
  const double reported = s["bodies"]["rod"]["max_equivalent_plastic_strain"].get<double>();
  hid_t f = H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t d = H5Dopen(f, "/frames/equivalent_plastic_strain", H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2];
  H5Sget_simple_extent_dims(sp, dims, nullptr);
  std::vector<double> all(dims[0] * dims[1]);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), 0);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  double last_frame_max = 0.0;
  for (hsize_t e = 0; e < dims[1]; ++e)
    last_frame_max = std::max(last_frame_max, all[(dims[0] - 1) * dims[1] + e]);
  std::printf("max eq. plastic strain: summary %.4f, largest element average %.4f\n", reported,
              last_frame_max);
  EXPECT_GT(last_frame_max, 0.1);
  EXPECT_GE(reported, last_frame_max);
  EXPECT_LT(reported, 2.0 * last_frame_max);
}

// The same run with 1 and 2 threads gives the same bits (deterministic gather).
TEST(Scenes, OneAndTwoThreadsGiveIdenticalResults) {
  std::string args =
      "' --quiet --set bodies.ball.mesh.element_size=2.5e-3 --set simulation.end_time=15e-6";
  const fs::path o1 = out_dir("threads1"), o2 = out_dir("threads2");
  ASSERT_EQ(
      run_femdem("run '" + scene("sphere_drop.toml") + "' --threads 1 --out '" + o1.string() + args)
          .code,
      0);
  ASSERT_EQ(
      run_femdem("run '" + scene("sphere_drop.toml") + "' --threads 2 --out '" + o2.string() + args)
          .code,
      0);
  auto s1 = read_json(o1 / "summary.json"), s2 = read_json(o2 / "summary.json");
  EXPECT_EQ(s1["threads"], 1);
  EXPECT_EQ(s2["threads"], 2);
  EXPECT_EQ(s1["energy"], s2["energy"]);
  EXPECT_EQ(s1["bodies"], s2["bodies"]);
  EXPECT_EQ(s1["steps"], s2["steps"]);
  auto h1 = read_history(o1 / "history.csv"), h2 = read_history(o2 / "history.csv");
  EXPECT_GT(std::fabs(h1["floor.force_z"].back()), 0.0);  // contact happened in this window
  EXPECT_EQ(h1, h2);
}

// A step far above the stable one: exit code 3, a message that says what to change, a summary
// that says "unstable", and results.h5 closed as incomplete.
TEST(Scenes, DivergingRunStopsWithCode3) {
  const fs::path out = out_dir("unstable");
  const Result r = run_femdem("run '" + scene("bar_vibration.toml") + "' --quiet --out '" +
                              out.string() + "' --set simulation.time_step=0.05");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("time_step"), std::string::npos) << r.output;
  const auto s = read_json(out / "summary.json");
  EXPECT_EQ(s["status"], "unstable");
  hid_t f = H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  int complete = -1;
  hid_t a = H5Aopen(f, "complete", H5P_DEFAULT);
  H5Aread(a, H5T_NATIVE_INT, &complete);
  H5Aclose(a);
  H5Fclose(f);
  EXPECT_EQ(complete, 0);
}

// SIGKILL half-way: every frame written so far is readable (as a SWMR reader: see
// docs/OUTPUTS.md), results.xdmf names only complete frames, and there is no summary.json.
TEST(Scenes, KilledRunLeavesReadableFrames) {
  const fs::path out = out_dir("killed");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(FEMDEM_EXE, FEMDEM_EXE, "run", scene("bar_vibration.toml").c_str(), "--quiet", "--out",
          out.c_str(), "--set", "simulation.output_interval=0.05", static_cast<char*>(nullptr));
    _exit(127);
  }
  // wait until a few frames are listed, then kill
  int frames = 0;
  for (int i = 0; i < 600 && frames < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::ifstream x(out / "results.xdmf");
    std::string text((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
    frames = 0;
    for (std::size_t p = text.find("<Time "); p != std::string::npos;
         p = text.find("<Time ", p + 1))
      ++frames;
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  ASSERT_GE(frames, 5);
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  hid_t f = H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t d = H5Dopen(f, "/frames/displacement", H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[3];
  H5Sget_simple_extent_dims(sp, dims, nullptr);
  EXPECT_GE(dims[0], static_cast<hsize_t>(frames));
  std::vector<double> all(dims[0] * dims[1] * dims[2]);
  EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()), 0);
  for (double v : all) ASSERT_TRUE(std::isfinite(v));
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
}

// Ctrl-C: the run stops cleanly, says so, and leaves ordinary (non-SWMR-marked) files.
TEST(Scenes, InterruptedRunClosesItsFiles) {
  const fs::path out = out_dir("interrupted");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(FEMDEM_EXE, FEMDEM_EXE, "run", scene("bar_vibration.toml").c_str(), "--quiet", "--out",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 500 && !fs::exists(out / "history.csv"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const auto s = read_json(out / "summary.json");
  EXPECT_EQ(s["status"], "interrupted");
  EXPECT_LT(s["end_time"].get<double>(), 40.0);
  hid_t f = H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0);
  if (f >= 0) H5Fclose(f);
}
