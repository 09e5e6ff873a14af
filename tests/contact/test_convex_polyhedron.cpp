// SPDX-License-Identifier: GPL-3.0-or-later
// The two clippers of the pair kernel's tests: the tetrahedron sets that runs use
// (tests/support/tetrahedron_set_clip.hpp) and the polyhedron clipper that checks them
// (tests/support/convex_polyhedron.hpp): volumes and centroids of known solids cut out of a
// tetrahedron (a cube, a corner, halves), invariance under the order of the planes, degenerate
// cuts (through vertices, edges, along faces), and agreement with each other on random cuts.
#include "support/convex_polyhedron.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "tests/support/tetrahedron_set_clip.hpp"

namespace {

using femdem::contact::TetrahedronSetClip;
using femdem::test::ConvexPolyhedron;
using P3 = std::array<double, 3>;
using Corners = std::array<P3, 4>;

struct Plane {
  double c;
  P3 g;  // keeps c + g . x >= 0
};

const Corners kCorner = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

template <class Clip>
void measure(const Corners& t, const std::vector<Plane>& planes, double& v, P3& m) {
  Clip c;
  c.set_tetrahedron(t);
  for (const Plane& p : planes) c.clip(p.c, p.g);
  c.moments(v, m);
}

Corners reversed(Corners t) {
  std::swap(t[1], t[2]);
  return t;
}

TEST(ConvexPolyhedron, TetrahedronVolumeAndCentroidInBothOrientations) {
  for (const Corners& t : {kCorner, reversed(kCorner)}) {
    double v;
    P3 m;
    measure<ConvexPolyhedron>(t, {}, v, m);
    EXPECT_NEAR(v, 1.0 / 6.0, 1e-16);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(m[d], v * 0.25, 1e-16);
  }
}

// The corner tetrahedron cut at x = 1/2: the kept part x <= 1/2 is the tetrahedron minus the
// corner tetrahedron at (1, 0, 0) scaled by 1/2 (volume 1/48, centroid (5/8, 1/8, 1/8)).
TEST(ConvexPolyhedron, HalfSpaceCutOfTheCornerTetrahedron) {
  for (const Corners& t : {kCorner, reversed(kCorner)}) {
    double v;
    P3 m;
    measure<TetrahedronSetClip>(t, {{0.5, {-1, 0, 0}}}, v, m);
    EXPECT_NEAR(v, 1.0 / 6.0 - 1.0 / 48.0, 1e-16) << "tetrahedron sets";
    measure<ConvexPolyhedron>(t, {{0.5, {-1, 0, 0}}}, v, m);
    const double v0 = 1.0 / 6.0, vc = 1.0 / 48.0;
    EXPECT_NEAR(v, v0 - vc, 1e-16);
    const P3 mc = {vc * 5.0 / 8.0, vc / 8.0, vc / 8.0};
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(m[d], v0 * 0.25 - mc[d], 1e-16) << d;
    // and the other side is the small corner
    measure<ConvexPolyhedron>(t, {{-0.5, {1, 0, 0}}}, v, m);
    EXPECT_NEAR(v, vc, 1e-16);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(m[d], mc[d], 1e-16) << d;
  }
}

// Six planes cut the unit cube out of a tetrahedron that contains it: volume 1, centroid at
// the cube's centre, whatever the order of the planes (six clips: the storage's limit).
TEST(ConvexPolyhedron, SixPlanesCutACubeOutOfATetrahedron) {
  const Corners big = {{{-1, -1, -1}, {6, -1, -1}, {-1, 6, -1}, {-1, -1, 6}}};
  std::vector<Plane> cube = {{0, {1, 0, 0}},  {1, {-1, 0, 0}}, {0, {0, 1, 0}},
                             {1, {0, -1, 0}}, {0, {0, 0, 1}},  {1, {0, 0, -1}}};
  std::mt19937 rng(3);
  for (int r = 0; r < 20; ++r) {
    std::shuffle(cube.begin(), cube.end(), rng);
    double v;
    P3 m;
    measure<ConvexPolyhedron>(r % 2 ? big : reversed(big), cube, v, m);
    EXPECT_NEAR(v, 1.0, 1e-14);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(m[d], 0.5, 1e-14);
  }
}

// Cuts through a vertex, along an edge and along a face: what is kept is exact, and a plane that
// keeps nothing but a face or an edge leaves zero volume.
TEST(ConvexPolyhedron, DegenerateCutsThroughVerticesEdgesAndFaces) {
  double v;
  P3 m;
  // along the slanted face: x + y + z <= 1 keeps the whole tetrahedron
  measure<ConvexPolyhedron>(kCorner, {{1.0, {-1, -1, -1}}}, v, m);
  EXPECT_NEAR(v, 1.0 / 6.0, 1e-16);
  // y <= x cuts through the edge on the z axis and the midpoint of the opposite edge: half
  measure<ConvexPolyhedron>(kCorner, {{0.0, {1, -1, 0}}}, v, m);
  EXPECT_NEAR(v, 1.0 / 12.0, 1e-16);
  // the opposite half, then both: the shared wall has no volume
  measure<ConvexPolyhedron>(kCorner, {{0.0, {-1, 1, 0}}}, v, m);
  EXPECT_NEAR(v, 1.0 / 12.0, 1e-16);
  measure<ConvexPolyhedron>(kCorner, {{0.0, {1, -1, 0}}, {0.0, {-1, 1, 0}}}, v, m);
  EXPECT_NEAR(v, 0.0, 1e-16);
  // z <= 0 keeps only the bottom face; z >= 0 keeps all
  measure<ConvexPolyhedron>(kCorner, {{0.0, {0, 0, -1}}}, v, m);
  EXPECT_NEAR(v, 0.0, 1e-16);
  measure<ConvexPolyhedron>(kCorner, {{0.0, {0, 0, 1}}}, v, m);
  EXPECT_NEAR(v, 1.0 / 6.0, 1e-16);
  // x >= 1 keeps only the vertex (1, 0, 0); x >= 2 keeps nothing
  measure<ConvexPolyhedron>(kCorner, {{-1.0, {1, 0, 0}}}, v, m);
  EXPECT_NEAR(v, 0.0, 1e-16);
  ConvexPolyhedron p;
  p.set_tetrahedron(kCorner);
  p.clip(-2.0, {1, 0, 0});
  EXPECT_TRUE(p.empty());
}

// Random tetrahedra cut by up to four random planes (the kernel's use): the two clippers give
// the same volume and first moment.
TEST(ConvexPolyhedron, AgreesWithTheTetrahedronSetClipperOnRandomCuts) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int nonempty = 0;
  for (int r = 0; r < 4000; ++r) {
    Corners t;
    for (auto& x : t) x = {u(rng), u(rng), u(rng)};
    std::vector<Plane> planes(1 + r % 4);
    for (Plane& p : planes) p = {0.4 * u(rng), {u(rng), u(rng), u(rng)}};
    double v1, v2;
    P3 m1, m2;
    measure<ConvexPolyhedron>(t, planes, v1, m1);
    measure<TetrahedronSetClip>(t, planes, v2, m2);
    EXPECT_NEAR(v1, v2, 1e-15) << "case " << r;
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(m1[d], m2[d], 1e-15) << "case " << r;
    nonempty += v2 > 1e-3;
  }
  EXPECT_GT(nonempty, 1000);  // the cuts leave something often enough to test
}

}  // namespace
