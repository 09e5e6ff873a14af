// SPDX-License-Identifier: GPL-3.0-or-later
// contact/tet_distance_bound.hpp: the lower bound of two tetrahedra's distance and the test for
// faces about to close flush, which the stable step uses to count a flat contact before a pair
// touches. Checked against distances measured independently (pairs of points sampled in both
// tetrahedra: any such pair is at least the true distance apart), against tetrahedra a plane
// separates by a known margin, and on faces set parallel at a known gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "contact/tet_distance_bound.hpp"

using namespace femdem::contact;

namespace {

using Tet = std::array<P3, 4>;

Tet random_tet(std::mt19937& rng, const P3& centre, double size) {
  std::uniform_real_distribution<double> u(-size, size);
  Tet t;
  for (P3& p : t) p = {centre[0] + u(rng), centre[1] + u(rng), centre[2] + u(rng)};
  return t;
}

P3 point_in(const Tet& t, std::mt19937& rng) {
  std::exponential_distribution<double> e(1.0);  // normalised: uniform on the simplex
  double w[4], sum = 0.0;
  for (double& x : w) sum += (x = e(rng));
  P3 p = {0.0, 0.0, 0.0};
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) p[d] += w[k] / sum * t[k][d];
  return p;
}

double norm(const P3& a) {
  return std::sqrt(dot(a, a));
}

// An upper bound of the distance: the closest of many sampled pairs of points (corners too).
double sampled_distance(const Tet& a, const Tet& b, std::mt19937& rng) {
  double best = HUGE_VAL;
  for (const P3& p : a)
    for (const P3& q : b) best = std::min(best, norm(sub(p, q)));
  for (int s = 0; s < 4000; ++s)
    best = std::min(best, norm(sub(point_in(a, rng), point_in(b, rng))));
  return best;
}

}  // namespace

TEST(TetDistanceBound, NeverExceedsTheDistanceOfAnyTwoPoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-1.5, 1.5);
  int separated = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Tet a = random_tet(rng, {0.0, 0.0, 0.0}, 1.0);
    const Tet b = random_tet(rng, {offset(rng), offset(rng), offset(rng)}, 1.0);
    const double bound = tet_distance_lower_bound(a, b);
    const double sampled = sampled_distance(a, b, rng);
    EXPECT_LE(bound, sampled + 1e-12) << "trial " << trial;
    separated += bound > 0.0;
  }
  EXPECT_GT(separated, 30);  // (the draws include pairs apart, not only overlapping ones)
}

// Two tetrahedra on either side of a plane, at least `margin` apart across it: by the
// separating-axis theorem one of the tried axes separates them, so the bound is positive.
TEST(TetDistanceBound, PositiveForEveryPairAPlaneSeparates) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    P3 n = {g(rng), g(rng), g(rng)};
    const double len = norm(n);
    for (double& x : n) x /= len;
    const double margin = 1e-3;
    Tet a = random_tet(rng, {0.0, 0.0, 0.0}, 1.0), b = random_tet(rng, {0.0, 0.0, 0.0}, 1.0);
    // push every corner of a below the plane n . x = 0 and every corner of b above n . x = margin
    for (P3& p : a) {
      const double h = dot(n, p);
      if (h > 0.0)
        for (int d = 0; d < 3; ++d) p[d] -= 1.5 * h * n[d];
    }
    for (P3& p : b) {
      const double h = dot(n, p) - margin;
      if (h < 0.0)
        for (int d = 0; d < 3; ++d) p[d] -= 1.5 * h * n[d];
    }
    const double bound = tet_distance_lower_bound(a, b);
    EXPECT_GT(bound, 0.0) << "trial " << trial;
    EXPECT_LE(bound, sampled_distance(a, b, rng) + 1e-12) << "trial " << trial;
  }
}

// A face of b parallel to a face of a at gap 0.01: the bound is the gap, and the faces are flush
// within any reach of at least the gap. Tilted so that only one corner of b comes within reach
// first, they are not, though the bound still is a lower bound.
TEST(TetDistanceBound, FacesSetParallelAcrossAGap) {
  const Tet a = {P3{0.0, 0.0, 0.0}, P3{1.0, 0.0, 0.0}, P3{0.0, 1.0, 0.0}, P3{0.2, 0.2, -0.8}};
  const double gap = 0.01;
  const Tet b = {P3{0.1, 0.1, gap}, P3{0.9, 0.0, gap}, P3{0.0, 0.8, gap}, P3{0.3, 0.3, 0.7}};
  EXPECT_NEAR(tet_distance_lower_bound(a, b), gap, 1e-12);
  EXPECT_TRUE(faces_flush_within(a, b, 1.5 * gap));
  EXPECT_TRUE(faces_flush_within(b, a, 1.5 * gap));
  EXPECT_FALSE(faces_flush_within(a, b, 0.5 * gap));
  Tet tilted = b;
  tilted[1][2] += 0.2;  // two corners of the face lifted: a corner meets a's face first
  tilted[2][2] += 0.3;
  EXPECT_NEAR(tet_distance_lower_bound(a, tilted), gap, 1e-12);
  EXPECT_FALSE(faces_flush_within(a, tilted, 1.5 * gap));
  // overlapping: no axis separates them, the bound is not positive, and nothing is "flush"
  Tet sunk = b;
  for (P3& p : sunk) p[2] -= 0.1;
  EXPECT_LE(tet_distance_lower_bound(a, sunk), 0.0);
  EXPECT_FALSE(faces_flush_within(a, sunk, 1.0));
}

// The stable step's one-pass decision (may_close_flush_within) is the bound and the flush test
// above composed, on pairs apart, touching and set nearly flush, each at reaches from below to
// above their gap: the early exits change no answer. The gap it reports for the pair (body
// contact's clearance) is never above the bound.
TEST(TetDistanceBound, TheStepsDecisionIsTheBoundAndTheFlushTestComposed) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> small(-0.02, 0.02);
  int counted = 0, flush_counted = 0, apart_not_flush = 0, trials = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Tet a = random_tet(rng, {0.0, 0.0, 0.0}, 0.5);
    Tet b;
    if (trial % 3 == 0) {
      b = random_tet(rng, {u(rng), u(rng), u(rng)}, 0.5);  // apart, touching or overlapping
    } else {
      // a face of a (0, 1, 2) copied a little beyond itself, each corner moved a little, and a
      // fourth corner behind it: faces nearly flush across a small gap (or slightly crossing)
      const P3 n = cross(sub(a[1], a[0]), sub(a[2], a[0]));
      const double len = norm(n);
      if (!(len > 0.0)) continue;
      P3 out = {n[0] / len, n[1] / len, n[2] / len};
      if (dot(out, sub(a[3], a[0])) > 0.0) out = {-out[0], -out[1], -out[2]};
      const double gap = 0.03 * (u(rng) + 0.8);
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) b[k][d] = a[k][d] + gap * out[d] + small(rng);
      for (int d = 0; d < 3; ++d) b[3][d] = (a[0][d] + a[1][d] + a[2][d]) / 3.0 + 0.6 * out[d];
    }
    const double g = tet_distance_lower_bound(a, b);
    for (const double reach : {0.0, 1e-3, 0.01, 0.03, 0.1, 0.5, 2.0}) {
      const bool composed = g <= reach && (g <= 0.0 || faces_flush_within(a, b, reach));
      double bound = 0.0;
      ASSERT_EQ(may_close_flush_within(a, b, reach, bound), composed)
          << "trial " << trial << " reach " << reach << " bound " << g;
      // the gap it reports is one of the bound's axes (so below the distance, tested above),
      // and positive whenever the bound is
      ASSERT_LE(bound, g) << "trial " << trial;
      if (g > 0.0) {
        ASSERT_GT(bound, 0.0) << "trial " << trial;
      }
      ++trials;
      counted += composed;
      flush_counted += composed && g > 0.0;
      apart_not_flush += g > 0.0 && g <= reach && !composed;
    }
  }
  // each branch of the decision met many times
  EXPECT_GT(counted, 1000);
  EXPECT_GT(flush_counted, 500);
  EXPECT_GT(apart_not_flush, 500);
  EXPECT_GT(trials, 15000);
}
