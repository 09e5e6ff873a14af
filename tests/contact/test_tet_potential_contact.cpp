// SPDX-License-Identifier: GPL-3.0-or-later
// The tet-tet penalty-potential pair kernel: zero when apart, balanced and conservative forces,
// hand-derived energies, and invariance under rigid motions, corner order and swapping A, B.
#include "contact/tet_potential_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "contact/tet_potential_integral.hpp"
#include "support/convex_polyhedron.hpp"

namespace {

using femdem::contact::tet_potential_contact;
using femdem::contact::tet_potential_contact_with;
using femdem::contact::TetCorners;
using femdem::contact::TetPairContact;
using femdem::test::ConvexPolyhedron;
using P3 = std::array<double, 3>;

constexpr double kPenalty = 2.0e9;

double signed_volume(const TetCorners& t) {
  const P3 u = {t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]};
  const P3 v = {t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]};
  const P3 w = {t[3][0] - t[0][0], t[3][1] - t[0][1], t[3][2] - t[0][2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

// A tetrahedron of size about 1 around `centre`, not too flat (volume >= 0.03).
TetCorners random_tet(std::mt19937& rng, const P3& centre) {
  std::uniform_real_distribution<double> u(-0.7, 0.7);
  for (;;) {
    TetCorners t;
    for (auto& x : t)
      for (int d = 0; d < 3; ++d) x[d] = centre[d] + u(rng);
    if (std::abs(signed_volume(t)) >= 0.03) return t;
  }
}

// A random rotation matrix (from a random unit quaternion).
std::array<P3, 3> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  double q[4], s = 0.0;
  for (double& c : q) {
    c = n(rng);
    s += c * c;
  }
  s = std::sqrt(s);
  const double w = q[0] / s, x = q[1] / s, y = q[2] / s, z = q[3] / s;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

P3 rotate_point(const std::array<P3, 3>& r, const P3& x, const P3& shift = {0, 0, 0}) {
  P3 y;
  for (int i = 0; i < 3; ++i) y[i] = r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2] + shift[i];
  return y;
}

TetCorners transform(const std::array<P3, 3>& r, const TetCorners& t, const P3& shift) {
  TetCorners o;
  for (int k = 0; k < 4; ++k) o[k] = rotate_point(r, t[k], shift);
  return o;
}

double max_force(const TetPairContact& c) {
  double m = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d)
      m = std::max({m, std::abs(c.force_a[k][d]), std::abs(c.force_b[k][d])});
  return m;
}

// Random overlapping pairs: B is a random tet whose centre is within 0.5 of A's.
struct Pair {
  TetCorners a, b;
};
std::vector<Pair> overlapping_pairs(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Pair> pairs;
  while (static_cast<int>(pairs.size()) < n) {
    Pair p{random_tet(rng, {0, 0, 0}), random_tet(rng, {u(rng), u(rng), u(rng)})};
    TetPairContact c{};
    if (tet_potential_contact(p.a, p.b, kPenalty, c)) pairs.push_back(p);
  }
  return pairs;
}

// Apart: false, and the result is not written (a rejected pair costs no clearing).
void expect_zero(const TetCorners& a, const TetCorners& b) {
  TetPairContact c{};
  c.energy = 1.0;
  EXPECT_FALSE(tet_potential_contact(a, b, kPenalty, c));
  EXPECT_EQ(c.energy, 1.0);
  EXPECT_EQ(max_force(c), 0.0);
}

TEST(TetPotentialContact, SeparatedTetsGiveZero) {
  const TetCorners a = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  // Disjoint boxes.
  expect_zero(a, {{{2, 0, 0}, {3, 0, 0}, {2, 1, 0}, {2, 0, 1}}});
  // Boxes overlap, A's slanted face x + y + z = 1 separates.
  expect_zero(a, {{{0.6, 0.6, 0.6}, {0.45, 0.9, 0.9}, {0.9, 0.45, 0.9}, {0.9, 0.9, 0.45}}});
  // Touching along a face: zero overlap volume.
  expect_zero(a, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}}});
  // Two crossed edges 0.01 apart: no face plane of either tet separates them (only the
  // edge-edge direction does), so the zero must come from the clipping. Rotated so that the
  // boxes overlap.
  const TetCorners e1 = {{{-1, 0, 0}, {1, 0, 0}, {0, 1, -1}, {0, -1, -1}}};
  const TetCorners e2 = {{{0, -1, 0.01}, {0, 1, 0.01}, {1, 0, 1.01}, {-1, 0, 1.01}}};
  std::mt19937 rng(7);
  for (int r = 0; r < 20; ++r) {
    const auto rot = random_rotation(rng);
    expect_zero(transform(rot, e1, {0.3, 0.1, -0.2}), transform(rot, e2, {0.3, 0.1, -0.2}));
  }
  // ... and once they cross they do overlap (the test above can fail).
  const TetCorners e3 = {{{0, -1, -0.01}, {0, 1, -0.01}, {1, 0, 0.99}, {-1, 0, 0.99}}};
  TetPairContact c{};
  EXPECT_TRUE(tet_potential_contact(e1, e3, kPenalty, c));
  EXPECT_GT(c.energy, 0.0);
}

TEST(TetPotentialContact, ForcesEqualOppositeAndMomentFree) {
  for (const Pair& p : overlapping_pairs(200, 11)) {
    TetPairContact c{};
    ASSERT_TRUE(tet_potential_contact(p.a, p.b, kPenalty, c));
    const double fmax = max_force(c);
    ASSERT_GT(fmax, 0.0);
    P3 fa{}, fb{}, moment{};
    for (int k = 0; k < 4; ++k) {
      for (int d = 0; d < 3; ++d) {
        fa[d] += c.force_a[k][d];
        fb[d] += c.force_b[k][d];
      }
      const auto add_moment = [&](const P3& x, const P3& f) {
        moment[0] += x[1] * f[2] - x[2] * f[1];
        moment[1] += x[2] * f[0] - x[0] * f[2];
        moment[2] += x[0] * f[1] - x[1] * f[0];
      };
      add_moment(p.a[k], c.force_a[k]);
      add_moment(p.b[k], c.force_b[k]);
    }
    for (int d = 0; d < 3; ++d) {
      EXPECT_NEAR(fa[d] + fb[d], 0.0, 1e-12 * fmax);
      EXPECT_NEAR(moment[d], 0.0, 1e-11 * fmax);  // lever arms are about 1
    }
  }
}

TEST(TetPotentialContact, ForcesAreMinusTheEnergyGradient) {
  const double h = 1e-6;
  double worst = 0.0;
  for (const Pair& p : overlapping_pairs(100, 23)) {
    TetPairContact c{};
    ASSERT_TRUE(tet_potential_contact(p.a, p.b, kPenalty, c));
    const double fmax = max_force(c);
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) {
          Pair plus = p, minus = p;
          (t == 0 ? plus.a : plus.b)[k][d] += h;
          (t == 0 ? minus.a : minus.b)[k][d] -= h;
          TetPairContact cp{}, cm{};
          tet_potential_contact(plus.a, plus.b, kPenalty, cp);
          tet_potential_contact(minus.a, minus.b, kPenalty, cm);
          const double fd = -(cp.energy - cm.energy) / (2.0 * h);
          const double f = (t == 0 ? c.force_a : c.force_b)[k][d];
          worst = std::max(worst, std::abs(f - fd) / fmax);
          EXPECT_NEAR(f, fd, 1e-5 * fmax) << "tet " << t << " corner " << k << " dir " << d;
        }
  }
  std::printf("worst |f + dE/dx| / max|f| = %.2e\n", worst);
}

// Identical tets: phi = 4 lambda_i on region i (volume V/4, centroid where lambda_i = 1/16), so
// int phi = 4 * 4 * V/4 * 1/16 = V/4 per tet and E = p V/2. Scaling both about their centroid
// by s scales E by s^3, so sum_k f_k . (x_k - c) = -3E (a virial check on all 24 forces).
TEST(TetPotentialContact, CoincidentTetsHandDerived) {
  std::mt19937 rng(5);
  for (int r = 0; r < 10; ++r) {
    const TetCorners a = random_tet(rng, {0.2, -0.1, 0.3});
    const double v = std::abs(signed_volume(a));
    TetPairContact c{};
    ASSERT_TRUE(tet_potential_contact(a, a, kPenalty, c));
    EXPECT_NEAR(c.energy, 0.5 * kPenalty * v, 1e-12 * kPenalty * v);
    EXPECT_NEAR(c.overlap_volume, v, 1e-12 * v);
    P3 centre{};
    for (const auto& x : a)
      for (int d = 0; d < 3; ++d) centre[d] += 0.25 * x[d];
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(c.overlap_centroid[d], centre[d], 1e-12);
    double virial = 0.0;
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d)
        virial += (c.force_a[k][d] + c.force_b[k][d]) * (a[k][d] - centre[d]);
    EXPECT_NEAR(virial, -3.0 * c.energy, 1e-10 * c.energy);
  }
}

// A's apex pokes a depth d through the top face (z = 0) of a much larger B; A's opposite face is
// parallel to it. The overlap is A scaled by t = d/H_A about its apex. In barycentric
// coordinates (Jacobian 6 V_A) int_tip min(l0, l1, l2) dV = 6 V_A t^4/72 = V_A t^4/12; B's
// potential there is 4 (-z)/H_B and int_tip (-z) dV = S_tip d^2/12 with S_tip = S_A t^2. So
//   E = p S_A d^4 (1/(9 H_A^3) + 1/(3 H_A^2 H_B)),
// the resultant on A is (0, 0, dE/dd) = (0, 0, 4E/d) (sideways motion does not change E) and
// B gets the opposite.
TEST(TetPotentialContact, ApexThroughFlatFaceHandDerived) {
  const double ha = 1.0, hb = 5.0;
  const TetCorners b = {{{-10, -10, 0}, {20, -10, 0}, {-10, 20, 0}, {0, 0, -hb}}};
  for (double d : {0.02, 0.1, 0.25}) {
    const TetCorners a = {
        {{1.0, 0.0, ha - d}, {-0.5, 0.8, ha - d}, {-0.4, -0.9, ha - d}, {0.1, 0.05, -d}}};
    const double sa = 0.5 * std::abs((a[1][0] - a[0][0]) * (a[2][1] - a[0][1]) -
                                     (a[1][1] - a[0][1]) * (a[2][0] - a[0][0]));
    const double e =
        kPenalty * sa * std::pow(d, 4) * (1.0 / (9 * ha * ha * ha) + 1.0 / (3 * ha * ha * hb));
    TetPairContact c{};
    ASSERT_TRUE(tet_potential_contact(a, b, kPenalty, c));
    EXPECT_NEAR(c.energy, e, 1e-12 * e) << "d = " << d;
    EXPECT_NEAR(c.overlap_volume, sa * ha / 3 * std::pow(d / ha, 3), 1e-12) << "d = " << d;
    // the tip is A scaled by d / H_A about the apex: so is its centroid
    for (int i = 0; i < 3; ++i) {
      const double ca = 0.25 * (a[0][i] + a[1][i] + a[2][i] + a[3][i]);
      EXPECT_NEAR(c.overlap_centroid[i], a[3][i] + d / ha * (ca - a[3][i]), 1e-12) << i;
    }
    P3 fa{}, fb{};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i) {
        fa[i] += c.force_a[k][i];
        fb[i] += c.force_b[k][i];
      }
    const double fz = 4.0 * e / d;
    EXPECT_NEAR(fa[0], 0.0, 1e-10 * fz);
    EXPECT_NEAR(fa[1], 0.0, 1e-10 * fz);
    EXPECT_NEAR(fa[2], fz, 1e-10 * fz) << "d = " << d;
    EXPECT_NEAR(fb[2], -fz, 1e-10 * fz) << "d = " << d;
  }
}

TEST(TetPotentialContact, InvariantUnderRigidMotion) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (const Pair& p : overlapping_pairs(50, 41)) {
    TetPairContact c{}, cr{};
    ASSERT_TRUE(tet_potential_contact(p.a, p.b, kPenalty, c));
    const auto rot = random_rotation(rng);
    const P3 shift = {u(rng), u(rng), u(rng)};
    ASSERT_TRUE(tet_potential_contact(transform(rot, p.a, shift), transform(rot, p.b, shift),
                                      kPenalty, cr));
    EXPECT_NEAR(cr.energy, c.energy, 1e-11 * c.energy);
    const double fmax = max_force(c);
    for (int k = 0; k < 4; ++k) {
      const P3 fa = rotate_point(rot, c.force_a[k]), fb = rotate_point(rot, c.force_b[k]);
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(cr.force_a[k][d], fa[d], 1e-10 * fmax);
        EXPECT_NEAR(cr.force_b[k][d], fb[d], 1e-10 * fmax);
      }
    }
  }
}

TEST(TetPotentialContact, SymmetricInSwapAndCornerOrder) {
  for (const Pair& p : overlapping_pairs(50, 53)) {
    TetPairContact c{}, cs{}, cp{};
    ASSERT_TRUE(tet_potential_contact(p.a, p.b, kPenalty, c));
    ASSERT_TRUE(tet_potential_contact(p.b, p.a, kPenalty, cs));
    // Corners of A reordered (odd permutation: the orientation flips).
    const TetCorners a2 = {{p.a[2], p.a[0], p.a[3], p.a[1]}};
    const int map[4] = {2, 0, 3, 1};
    ASSERT_TRUE(tet_potential_contact(a2, p.b, kPenalty, cp));
    EXPECT_NEAR(cs.energy, c.energy, 1e-12 * c.energy);
    EXPECT_NEAR(cp.energy, c.energy, 1e-12 * c.energy);
    const double fmax = max_force(c);
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(cs.force_a[k][d], c.force_b[k][d], 1e-11 * fmax);
        EXPECT_NEAR(cs.force_b[k][d], c.force_a[k][d], 1e-11 * fmax);
        EXPECT_NEAR(cp.force_a[k][d], c.force_a[map[k]][d], 1e-11 * fmax);
        EXPECT_NEAR(cp.force_b[k][d], c.force_b[k][d], 1e-11 * fmax);
      }
  }
}

// B slides through A along a line from clear on one side to clear on the other. The energy must
// start and end at zero, never jump (each step's change is bounded by the largest force times
// the step), and equal the work of the contact force on B along the path (trapezoid rule).
TEST(TetPotentialContact, EnergyContinuousAlongAPathThroughTheOtherTet) {
  std::mt19937 rng(71);
  for (int path = 0; path < 5; ++path) {
    const TetCorners a = random_tet(rng, {0, 0, 0});
    const TetCorners b0 = random_tet(rng, {0, 0, 0});
    std::normal_distribution<double> n(0.0, 1.0);
    P3 dir = {n(rng), n(rng), n(rng)};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (double& x : dir) x /= len;
    const int steps = 4000;
    const double s0 = 3.0, h = 2.0 * s0 / steps;
    double work = 0.0, prev_e = 0.0, prev_f = 0.0, emax = 0.0, worst_gap = 0.0;
    for (int i = 0; i <= steps; ++i) {
      const double s = -s0 + i * h;
      TetCorners b = b0;
      for (auto& x : b)
        for (int d = 0; d < 3; ++d) x[d] += s * dir[d];
      TetPairContact c{};
      tet_potential_contact(a, b, kPenalty, c);
      double f = 0.0;  // force on B along the path
      for (int k = 0; k < 4; ++k)
        for (int d = 0; d < 3; ++d) f += c.force_b[k][d] * dir[d];
      if (i == 0 || i == steps) {
        EXPECT_EQ(c.energy, 0.0);
      } else {
        EXPECT_LE(std::abs(c.energy - prev_e),
                  1.01 * std::max(std::abs(f), std::abs(prev_f)) * h + 1e-9 * kPenalty * h * h);
        work += 0.5 * (f + prev_f) * h;
        worst_gap = std::max(worst_gap, std::abs(c.energy + work));
      }
      emax = std::max(emax, c.energy);
      prev_e = c.energy;
      prev_f = f;
    }
    ASSERT_GT(emax, 0.0);
    EXPECT_LT(worst_gap, 1e-4 * emax) << "path " << path;
  }
}

// The kernel (regions clipped into sets of tetrahedra) against the same integral with the
// regions clipped as polyhedra (tests/support/convex_polyhedron.hpp): two independent ways to
// the exact integral. Tetrahedra of size L about 1; energies agree to 1e-12 p L^3 and forces to
// 1e-12 p L^2, and, where the overlap is not a sliver (over 1e-4 L^3), to 1e-12 of the pair's
// own energy and largest force.
void expect_same_as_reference(const TetCorners& a, const TetCorners& b, const char* what) {
  TetPairContact ref{}, c{};
  const bool touching = tet_potential_contact_with<ConvexPolyhedron>(a, b, kPenalty, ref);
  const bool kernel_touching = tet_potential_contact(a, b, kPenalty, c);
  // A corner within round-off of a face (the rotated "vertex on face") overlaps it by a sliver
  // of about 1e-50 L^3 or by nothing, as the arithmetic falls: the two ways may differ there.
  if (std::max(ref.overlap_volume, c.overlap_volume) > 1e-30) {
    EXPECT_EQ(kernel_touching, touching) << what;
  }
  const bool big = ref.overlap_volume > 1e-4;
  const double fscale = big ? 1e-12 * max_force(ref) : 1e-12 * kPenalty;
  const double escale = big ? 1e-12 * ref.energy : 1e-12 * kPenalty;
  EXPECT_NEAR(c.energy, ref.energy, escale) << what;
  EXPECT_NEAR(c.overlap_volume, ref.overlap_volume, 1e-13) << what;
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) {
      EXPECT_NEAR(c.force_a[k][d], ref.force_a[k][d], fscale) << what;
      EXPECT_NEAR(c.force_b[k][d], ref.force_b[k][d], fscale) << what;
    }
}

TEST(TetPotentialContact, EqualsThePolyhedronClippedIntegralOnRandomPairs) {
  for (const Pair& p : overlapping_pairs(3000, 97)) expect_same_as_reference(p.a, p.b, "deep");
  // shallow: B moved along a random direction until the overlap is 1e-6 to 2 % of A's volume
  std::mt19937 rng(101);
  std::normal_distribution<double> n(0.0, 1.0);
  int shallow = 0;
  while (shallow < 2000) {
    const TetCorners a = random_tet(rng, {0, 0, 0}), b0 = random_tet(rng, {0, 0, 0});
    P3 dir = {n(rng), n(rng), n(rng)};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    const double target = std::pow(10.0, -6.0 + 4.3 * (shallow % 100) / 100.0);
    double lo = 0.0, hi = 3.0;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      TetCorners b = b0;
      for (auto& x : b)
        for (int d = 0; d < 3; ++d) x[d] += mid * dir[d] / len;
      TetPairContact c{};
      tet_potential_contact(a, b, kPenalty, c);
      const double f = c.overlap_volume / std::abs(signed_volume(a));
      if (f > 0.5 * target && f < 2.0 * target) {
        expect_same_as_reference(a, b, "shallow");
        ++shallow;
        break;
      }
      (f > target ? lo : hi) = mid;
    }
  }
}

TEST(TetPotentialContact, EqualsThePolyhedronClippedIntegralInDegenerateContacts) {
  const TetCorners a = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::mt19937 rng(5);
  for (int r = 0; r < 20; ++r) {
    const auto rot = random_rotation(rng);
    const P3 s = {0.1 * r, -0.2, 0.3};
    const auto both = [&](const TetCorners& b, const char* what) {
      expect_same_as_reference(transform(rot, a, s), transform(rot, b, s), what);
    };
    // face on face, touching and pressed 1e-3 into each other
    both({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}}}, "face on face, touching");
    both({{{0, 0, 1e-3}, {1, 0, 1e-3}, {0, 1, 1e-3}, {0, 0, -1}}}, "face on face, pressed");
    // coplanar faces overlapping in part, pressed
    both({{{0.3, 0.2, 1e-3}, {1.3, 0.2, 1e-3}, {0.3, 1.2, 1e-3}, {0.3, 0.2, -1}}},
         "coplanar faces shifted");
    // edge on edge, crossing at right angles, 1e-3 deep
    both({{{0.2, -0.5, 1e-3}, {0.2, 0.5, 1e-3}, {0.7, 0, -0.5}, {-0.3, 0, -0.5}}}, "edge on edge");
    // a vertex pushed 1e-3 into a face, and one exactly on it
    both({{{0.2, 0.2, 1e-3}, {0.5, 0.5, -1}, {-0.3, 0.6, -1}, {0.4, -0.5, -1}}}, "vertex in face");
    both({{{0.2, 0.2, 0}, {0.5, 0.5, -1}, {-0.3, 0.6, -1}, {0.4, -0.5, -1}}}, "vertex on face");
    // identical tetrahedra, and one sharing a corner and an edge direction
    both(a, "identical");
    both({{{0, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {0, 0, 0.5}}}, "corner shared");
  }
}

}  // namespace
