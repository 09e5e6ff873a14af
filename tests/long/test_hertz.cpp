// SPDX-License-Identifier: GPL-3.0-or-later
// Hertz impacts (VALIDATION.md section 3), on meshes refined at the contact point: an elastic
// steel sphere (R 10 mm, E 210 GPa, nu 0.3, rho 7850) on a rigid wall and on a fixed meshed
// plate at 1 m/s (Hertz: contact time 52.4 us, peak force 2.31 kN), and two such spheres
// head-on at 0.5 m/s each (equal to one sphere on a wall at 0.5 m/s: 60.2 us, 1.005 kN), all with
// the default (automatic) contact stiffness and stable step. Targets (issue 17): contact time
// within 2 %, peak force within 5 %, restitution within 0.01 of 1, and the step in contact at
// least half the step before it; head-on: momentum conserved to round-off and equal and opposite
// rebound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "support/scene_run.hpp"

namespace {

struct Impact {
  double contact_time = 0.0, peak_force = 0.0;
  double step_before = 0.0, step_in_contact = 0.0;  // the smallest time step before / in contact
  nlohmann::json summary;
  std::map<std::string, std::vector<double>> history;
};

Impact run(const std::string& scene, const std::string& body) {
  auto r = femdem::test::run_shipped_scene(scene + ".toml", "long/" + scene, "--threads 2");
  EXPECT_EQ(r.command.code, 0) << r.command.output;
  Impact im;
  im.summary = std::move(r.summary);
  im.history = std::move(r.history);
  const auto& t = im.history["time"];
  const auto& f = im.history[body + ".contact_force_z"];
  double first = -1.0, last = -1.0;
  for (double v : f) im.peak_force = std::max(im.peak_force, std::fabs(v));
  // contact: the force above 1e-3 of its peak (the history samples every 0.2 us)
  for (std::size_t i = 0; i < f.size(); ++i)
    if (std::fabs(f[i]) > 1e-3 * im.peak_force) {
      if (first < 0.0) first = t[i];
      last = t[i];
    }
  im.contact_time = last - first;
  const auto& dt = im.history["dt"];
  im.step_before = im.step_in_contact = HUGE_VAL;
  for (std::size_t i = 0; i < f.size() && t[i] <= last; ++i) {
    double& smallest = t[i] < first ? im.step_before : im.step_in_contact;
    smallest = std::min(smallest, dt[i]);
  }
  return im;
}

void expect_hertz(const Impact& im, const std::string& body, double t_c, double f_max) {
  const auto& e = im.summary["bodies"][body]["coefficient_of_restitution"];
  ASSERT_FALSE(e.is_null());
  std::printf(
      "%s: contact time %.2f us (Hertz %.1f), peak force %.4f kN (%.3f), restitution "
      "%.4f, energy balance %.2e, smallest step before / in contact %.3e / %.3e s\n",
      body.c_str(), 1e6 * im.contact_time, 1e6 * t_c, 1e-3 * im.peak_force, 1e-3 * f_max,
      e["com"].get<double>(), im.summary["energy"]["balance_error"].get<double>(), im.step_before,
      im.step_in_contact);
  EXPECT_NEAR(im.contact_time, t_c, 0.02 * t_c);
  EXPECT_NEAR(im.peak_force, f_max, 0.05 * f_max);
  EXPECT_NEAR(e["com"].get<double>(), 1.0, 0.01);
  EXPECT_GE(im.step_in_contact, 0.5 * im.step_before);
}

}  // namespace

TEST(Hertz, SphereOnRigidWall) {
  const Impact im = run("hertz_sphere_wall", "ball");
  expect_hertz(im, "ball", 52.4e-6, 2.31e3);
}

TEST(Hertz, SphereOnFixedMeshedPlate) {
  const Impact im = run("hertz_sphere_plate", "ball");
  expect_hertz(im, "ball", 52.4e-6, 2.31e3);
}

TEST(Hertz, TwoSpheresHeadOn) {
  const Impact im = run("hertz_two_spheres", "upper");
  expect_hertz(im, "upper", 60.2e-6, 1.005e3);
  const auto& b = im.summary["bodies"];
  const double vu = b["upper"]["vcom"][2].get<double>(), vl = b["lower"]["vcom"][2].get<double>();
  const double mu = b["upper"]["mass"].get<double>(), ml = b["lower"]["mass"].get<double>();
  EXPECT_NEAR(mu * vu + ml * vl, 0.0, 1e-12 * mu * 0.5);  // started at +-0.5 m/s
  // equal and opposite: the two refined meshes are not exact mirror images, hence 0.1 %
  EXPECT_NEAR(vu, -vl, 1e-3 * 0.5);
}
