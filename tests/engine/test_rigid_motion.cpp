// SPDX-License-Identifier: GPL-3.0-or-later
// engine/rigid_motion.hpp: a body's rigid motion from its nodes, taken in one pass about its
// first node. Checked against the definitions computed here directly about the centre of mass
// in long double (the centre, the momentum over the mass, the inertia sum m (|r|^2 1 - r r^T),
// the angular momentum of the velocities about the centre's), on a cloud of nodes far from the
// origin, and on a velocity field that is rigid, where the spin must come back.
#include <gtest/gtest.h>

#include <random>

#include "engine/rigid_motion.hpp"

using femdem::Body;
using femdem::Model;
using femdem::RigidMotion;
using femdem::Vec3;

namespace {

struct Cloud {
  Model model;
  Body body;
};

// 60 nodes of random masses in a 0.3 m ball about `centre`, after 5 nodes of another body.
Cloud random_cloud(std::mt19937& rng, const Vec3& centre) {
  std::uniform_real_distribution<double> u(-0.3, 0.3), mass(0.5, 2.0);
  Cloud c;
  const int before = 5, count = 60;
  c.model.node_count = before + count;
  c.model.x.resize(3 * c.model.node_count);
  c.model.v.assign(3 * c.model.node_count, 0.0);
  c.model.mass.resize(c.model.node_count);
  for (int n = 0; n < c.model.node_count; ++n) {
    c.model.mass[n] = mass(rng);
    for (int k = 0; k < 3; ++k) c.model.x[3 * n + k] = centre[k] + u(rng);
  }
  c.body.first_node = before;
  c.body.node_count = count;
  return c;
}

Vec3 at(const std::vector<double>& a, int n) {
  return Vec3(a[3 * n], a[3 * n + 1], a[3 * n + 2]);
}

// The definitions about the centre, in long double, from velocities v + half_dt accel.
struct Direct {
  long double mass = 0;
  long double centre[3] = {}, velocity[3] = {}, momentum_about_centre[3] = {};
  long double inertia[3][3] = {};
};

Direct direct(const Cloud& c, const std::vector<double>* accel, double half_dt) {
  Direct d;
  const Model& m = c.model;
  auto velocity = [&](int n, int k) {
    long double v = m.v[3 * n + k];
    if (accel) v += static_cast<long double>(half_dt) * (*accel)[3 * n + k];
    return v;
  };
  const int n0 = c.body.first_node, n1 = n0 + c.body.node_count;
  for (int n = n0; n < n1; ++n) {
    d.mass += m.mass[n];
    for (int k = 0; k < 3; ++k) {
      d.centre[k] += m.mass[n] * static_cast<long double>(m.x[3 * n + k]);
      d.velocity[k] += m.mass[n] * velocity(n, k);
    }
  }
  for (int k = 0; k < 3; ++k) d.centre[k] /= d.mass, d.velocity[k] /= d.mass;
  for (int n = n0; n < n1; ++n) {
    long double r[3], w[3];
    for (int k = 0; k < 3; ++k) {
      r[k] = m.x[3 * n + k] - d.centre[k];
      w[k] = velocity(n, k) - d.velocity[k];
    }
    const long double mn = m.mass[n];
    d.momentum_about_centre[0] += mn * (r[1] * w[2] - r[2] * w[1]);
    d.momentum_about_centre[1] += mn * (r[2] * w[0] - r[0] * w[2]);
    d.momentum_about_centre[2] += mn * (r[0] * w[1] - r[1] * w[0]);
    const long double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) d.inertia[i][j] += mn * ((i == j ? rr : 0) - r[i] * r[j]);
  }
  return d;
}

void expect_matches(const RigidMotion& r, const Direct& d) {
  const double tol = 1e-11;
  EXPECT_NEAR(r.mass, static_cast<double>(d.mass), tol * static_cast<double>(d.mass));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.centre[k], static_cast<double>(d.centre[k]), 1e-12 * 1e3) << k;
    EXPECT_NEAR(r.velocity[k], static_cast<double>(d.velocity[k]), tol) << k;
  }
  const double scale = static_cast<double>(d.inertia[0][0] + d.inertia[1][1] + d.inertia[2][2]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(r.inertia(i, j), static_cast<double>(d.inertia[i][j]), 1e-9 * scale) << i << j;
  // I omega is the angular momentum about the centre
  const Vec3 L = r.inertia * r.angular_velocity;
  const double lscale = std::abs(static_cast<double>(d.momentum_about_centre[0])) +
                        std::abs(static_cast<double>(d.momentum_about_centre[1])) +
                        std::abs(static_cast<double>(d.momentum_about_centre[2]));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(L[k], static_cast<double>(d.momentum_about_centre[k]), 1e-9 * lscale) << k;
}

}  // namespace

TEST(RigidMotion, IsTheDefinitionsAboutTheCentreFarFromTheOrigin) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    // a body 1 km from the origin: sums about the origin would lose 7 digits of the inertia
    Cloud c = random_cloud(rng, Vec3(1000.0 + g(rng), -500.0 + g(rng), 250.0));
    for (double& v : c.model.v) v = g(rng);
    std::vector<double> accel(c.model.v.size());
    for (double& a : accel) a = 100.0 * g(rng);
    expect_matches(femdem::rigid_motion(c.model, c.body), direct(c, nullptr, 0.0));
    expect_matches(femdem::rigid_motion(c.model, c.body, accel.data(), 1e-3),
                   direct(c, &accel, 1e-3));
  }
}

TEST(RigidMotion, ARigidVelocityFieldGivesItsSpinBack) {
  std::mt19937 rng(8);
  Cloud c = random_cloud(rng, Vec3(40.0, 3.0, -7.0));
  const Vec3 v0(0.3, -1.2, 0.8), omega(2.0, -0.5, 1.5), about(40.1, 2.9, -7.05);
  for (int n = 0; n < c.model.node_count; ++n) {
    const Vec3 v = v0 + omega.cross(at(c.model.x, n) - about);
    for (int k = 0; k < 3; ++k) c.model.v[3 * n + k] = v[k];
  }
  const RigidMotion r = femdem::rigid_motion(c.model, c.body);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.angular_velocity[k], omega[k], 1e-10) << k;
  // and the field at each node of the body
  for (int n = c.body.first_node; n < c.body.first_node + c.body.node_count; ++n) {
    const Vec3 v = r.velocity_at(at(c.model.x, n));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[k], c.model.v[3 * n + k], 1e-10) << n;
  }
}
