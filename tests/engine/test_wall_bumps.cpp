// SPDX-License-Identifier: GPL-3.0-or-later
// A studded wall (engine/wall_bumps.hpp, Wall::push): hemispheres of radius r centred on the
// plane at the nodes of a hexagonal lattice. Checked against geometry worked out by hand (a
// point above a bump's top, the pocket between three touching bumps) and against a brute-force
// search over every bump of a patch of the lattice (random points, tilted walls, spacings wider
// than the bumps), and the reader's rows for the key.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/model.hpp"

using namespace femdem;

namespace {

Wall studded(const Vec3& point, const Vec3& normal, double diameter, double spacing) {
  Wall w;
  w.point0 = w.point = point;
  w.normal = normal.normalized();
  w.bumps.radius = 0.5 * diameter;
  w.bumps.spacing = spacing;
  w.bumps.orient(w.normal);
  return w;
}

// Every bump of the patch |i|, |j| <= 30 around the wall's point: the deepest, or the plane.
Wall::Push brute_force(const Wall& w, const Vec3& p) {
  Wall::Push out{(w.point - p).dot(w.normal), w.normal};
  const double s = w.bumps.spacing, row = s * std::sqrt(3.0) / 2.0;
  for (int i = -30; i <= 30; ++i)
    for (int j = -30; j <= 30; ++j) {
      const Vec3 c = w.point + (i + 0.5 * j) * s * w.bumps.u + j * row * w.bumps.v;
      const double depth = w.bumps.radius - (p - c).norm();
      if (depth > out.depth) out = {depth, (p - c).normalized()};
    }
  return out;
}

}  // namespace

TEST(WallBumps, APointAboveABumpsTopIsPushedStraightOutOfIt) {
  const double d = 2e-3;
  const Wall w = studded(Vec3(0.1, -0.2, 0.05), Vec3(0, 0, 1), d, d);
  // lattice node (i, j) = (2, 1): origin + (2.5 s, sqrt(3)/2 s) along x, y (u = x on a floor)
  const Vec3 top = w.point + Vec3(2.5 * d, std::sqrt(3.0) / 2.0 * d, 0.0);
  const Wall::Push in = w.push(top + Vec3(0, 0, 0.75e-3));
  EXPECT_NEAR(in.depth, 0.25e-3, 1e-15);
  EXPECT_NEAR((in.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_LT(w.push(top + Vec3(0, 0, 1.01e-3)).depth, 0.0);  // above the top: free
  EXPECT_DOUBLE_EQ(w.relief(), 1e-3);
}

TEST(WallBumps, APocketBetweenThreeTouchingBumpsHoldsABallOfTheirSizeAtTwoRadiiHigh) {
  // A ball of the bumps' radius r in the pocket of three touching bumps (spacing 2r) touches
  // all three: its centre is 2r from each, above the triangle's centroid, s / sqrt(3) from the
  // corners, so at height sqrt(4 r^2 - 4 r^2 / 3) = 1.633 r. There the three contact points are
  // each the centre's nearest on the wall, at depth 0 for the ball's radius: a node at the
  // contact point (r from the bump's centre, halfway to the ball's) is at depth 0.
  const double r = 1e-3, s = 2 * r;
  const Wall w = studded(Vec3::Zero(), Vec3(0, 0, 1), 2 * r, s);
  const Vec3 centroid(0.5 * s, s / (2.0 * std::sqrt(3.0)), 0.0);
  const Vec3 ball = centroid + Vec3(0, 0, std::sqrt(4 * r * r - s * s / 3.0));
  EXPECT_NEAR(ball.z(), 1.63299 * r, 1e-8);
  for (const Vec3& corner :
       {Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0.5 * s, 0.5 * std::sqrt(3.0) * s, 0)}) {
    const Vec3 contact = 0.5 * (ball + corner);
    const Wall::Push at = w.push(contact);
    EXPECT_NEAR(at.depth, 0.0, 1e-15);
    EXPECT_NEAR((at.normal - (ball - corner).normalized()).norm(), 0.0, 1e-12);
    // a node pressed 1 um further into that bump, along the line of centres
    EXPECT_NEAR(w.push(contact - 1e-6 * (ball - corner).normalized()).depth, 1e-6, 1e-15);
  }
  // the gap between three touching bumps (inscribed radius 2r / sqrt(3) - r = 0.155 r) lets
  // nothing of the ball's size down to the plane: the centroid just above the plane is outside
  // every bump, only the plane pushes it
  const Wall::Push floor = w.push(centroid - Vec3(0, 0, 1e-6));
  EXPECT_NEAR(floor.depth, 1e-6, 1e-15);
  EXPECT_EQ(floor.normal, Vec3::UnitZ());
}

TEST(WallBumps, TheNearestOfFourCornersIsTheDeepestOfAllBumps) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  struct Case {
    Vec3 normal;
    double diameter, spacing;
  };
  for (const Case& c : {Case{Vec3(0, 0, 1), 1.0, 1.0}, Case{Vec3(0.3, -0.5, 0.8), 1.0, 1.0},
                        Case{Vec3(1, 0, 0), 1.0, 2.5}, Case{Vec3(0, -1, 0.01), 1.0, 0.8}}) {
    const Wall w = studded(Vec3(0.3, 0.1, -0.2), c.normal, c.diameter, c.spacing);
    EXPECT_NEAR(w.bumps.u.dot(w.normal), 0.0, 1e-14);
    EXPECT_NEAR(w.bumps.v.dot(w.normal), 0.0, 1e-14);
    EXPECT_NEAR(w.bumps.u.dot(w.bumps.v), 0.0, 1e-14);
    int inside_bumps = 0;
    for (int k = 0; k < 4000; ++k) {
      // within 8 spacings of the point in the plane, from below the plane to above the bumps
      const Vec3 p = w.point + 8.0 * c.spacing * (unit(rng) * w.bumps.u + unit(rng) * w.bumps.v) +
                     (0.6 * c.diameter * unit(rng)) * w.normal;
      const Wall::Push got = w.push(p), want = brute_force(w, p);
      ASSERT_NEAR(got.depth, want.depth, 1e-12) << k;
      if (got.depth > (w.point - p).dot(w.normal)) {
        ++inside_bumps;
        ASSERT_NEAR((got.normal - want.normal).norm(), 0.0, 1e-9) << k;
      }
    }
    EXPECT_GT(inside_bumps, 500);  // the points test the bumps, not only the plane
  }
}
