// SPDX-License-Identifier: GPL-3.0-or-later
// Particle packings (io/packing/packing.hpp): lattices, size distributions, random packings
// settled under gravity, determinism and the parameter checks. The packing file, the scene
// section [[packings]] and `femdem pack` have their own files (test_packing_file.cpp,
// test_packing_scene.cpp, tests/tools/test_pack_command.cpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/packing/packing.hpp"
#include "support/packing_checks.hpp"

namespace {

using femdem::InputError;
using femdem::Packing;
using femdem::PackingParams;
using femdem::Vec3;
constexpr double kPi = std::numbers::pi;
using femdem::test::expect_inside;
using femdem::test::min_relative_gap;
using femdem::test::random_box;

PackingParams thesis_box() {
  PackingParams p;
  p.size = Vec3(0.01, 0.01, 0.01);
  p.arrangement = "simple_cubic";
  p.diameter = 2.5e-3;
  return p;
}

// The thesis' set-up: 64 spheres of 2.5 mm in simple-cubic order fill the 10 mm box exactly.
TEST(Packing, SimpleCubicThesisBox) {
  const PackingParams p = thesis_box();
  const Packing pk = femdem::generate_packing(p);
  ASSERT_EQ(pk.particles.size(), 64u);
  EXPECT_NEAR(pk.stats.packing_fraction, kPi / 6.0, 1e-12);
  EXPECT_NEAR(pk.stats.container_fraction, kPi / 6.0, 1e-12);
  EXPECT_NEAR(pk.stats.bed_height, 0.01, 1e-15);
  EXPECT_GE(min_relative_gap(pk), -1e-12);
  EXPECT_LE(min_relative_gap(pk), 1e-12);  // neighbours touch
  expect_inside(p, pk);
  // bottom layer first, sites at 1.25 + 2.5 k mm
  EXPECT_NEAR(pk.particles[0].centre.x(), 1.25e-3, 1e-15);
  EXPECT_NEAR(pk.particles[63].centre.z(), 8.75e-3, 1e-15);
  for (const auto& q : pk.particles) {
    EXPECT_DOUBLE_EQ(q.radius, 1.25e-3);
    EXPECT_EQ(q.orientation.w(), 1.0);  // spheres keep their mesh's orientation
    EXPECT_EQ(q.shape, "sphere");
  }
}

// A long thin box (found by fuzzing, tests/fuzz/corpus/scene_reader/regression-timeout-*): the
// lattice searched the square of its longest side, 1.4e9 sites for 4 m x 10 mm x 10 mm at
// 0.5 mm, over a minute; now each side's own cells (3.9e6), and a lattice with more candidate
// sites than 1e6 is refused on its diameter before the search.
TEST(Packing, LongThinBoxLatticeSearchesItsOwnCellsAndHugeLatticesAreRefused) {
  PackingParams p = thesis_box();
  p.size = Vec3(0.4, 0.01, 0.01);  // 800 x 20 x 20 sites
  p.diameter = 0.5e-3;
  EXPECT_EQ(femdem::generate_packing(p).particles.size(), 800u * 20u * 20u);
  p.size = Vec3(4.01, 0.01, 0.01);
  try {
    femdem::generate_packing(p);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "diameter");
    EXPECT_NE(std::string(e.what()).find("up to 3882164 sites in the container, more than 1000000"),
              std::string::npos)
        << e.what();
  }
}

// Body- and face-centred cubic lattices in boxes that fit a whole number of cells: counts and
// fractions from the lattice geometry.
TEST(Packing, BccAndFccLatticeCountsAndFractions) {
  const double d = 1e-3, r = 0.5 * d;
  {
    PackingParams p;
    p.arrangement = "body_centred_cubic";
    p.diameter = d;
    const double a = 2.0 * d / std::sqrt(3.0), L = 2.0 * r + 3.0 * a;
    p.size = Vec3(L, L, L);
    const Packing pk = femdem::generate_packing(p);
    EXPECT_EQ(pk.particles.size(), 64u + 27u);  // 4^3 corners, 3^3 centres
    EXPECT_NEAR(pk.stats.packing_fraction, 91.0 * kPi / 6.0 * d * d * d / (L * L * L), 1e-12);
    EXPECT_GE(min_relative_gap(pk), -1e-9);
    expect_inside(p, pk);
  }
  {
    PackingParams p;
    p.arrangement = "face_centred_cubic";
    p.diameter = d;
    const double a = std::sqrt(2.0) * d, L = 2.0 * r + 2.0 * a;
    p.size = Vec3(L, L, L);
    const Packing pk = femdem::generate_packing(p);
    EXPECT_EQ(pk.particles.size(), 27u + 3u * 12u);  // 3^3 corners, 3 x 2 x 2 x 3 face sites
    EXPECT_NEAR(pk.stats.packing_fraction, 63.0 * kPi / 6.0 * d * d * d / (L * L * L), 1e-12);
    EXPECT_GE(min_relative_gap(pk), -1e-9);
    expect_inside(p, pk);
  }
  {  // a large fcc block tends to the densest packing pi / sqrt(18)
    PackingParams p;
    p.arrangement = "face_centred_cubic";
    p.diameter = d;
    const double a = std::sqrt(2.0) * d, L = 2.0 * r + 12.0 * a;
    p.size = Vec3(L, L, L);
    const Packing pk = femdem::generate_packing(p);
    EXPECT_GT(pk.stats.packing_fraction, 0.6);
    EXPECT_LT(pk.stats.packing_fraction, kPi / std::sqrt(18.0));
  }
  {  // a lattice in a cylinder; count takes the lowest sites
    PackingParams p;
    p.container = "cylinder";
    p.radius = 5e-3;
    p.height = 4e-3;
    p.arrangement = "simple_cubic";
    p.diameter = d;
    const Packing all = femdem::generate_packing(p);
    EXPECT_GT(all.particles.size(), 200u);
    expect_inside(p, all);
    EXPECT_GE(min_relative_gap(all), -1e-9);
    p.count = 50;
    const Packing some = femdem::generate_packing(p);
    ASSERT_EQ(some.particles.size(), 50u);
    EXPECT_NEAR(some.particles.back().centre.z(), r, 1e-15);  // all in the bottom layer
    p.count = 100000;
    EXPECT_THROW(femdem::generate_packing(p), InputError);
  }
}

// The three distributions against their moments, within 4 standard errors for n draws.
TEST(Packing, SizeDistributionsMatchTheirMoments) {
  const std::int64_t n = 20000;
  auto moments = [](const std::vector<double>& v, double& mean, double& sd) {
    mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double s = 0.0;
    for (double x : v) s += (x - mean) * (x - mean);
    sd = std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  PackingParams p;
  p.size = Vec3(0.1, 0.1, 0.1);
  p.count = n;
  double mean, sd;
  {
    p.distribution = "monodisperse";
    p.diameter = 1e-3;
    for (double x : femdem::packing_diameters(p, n)) EXPECT_EQ(x, 1e-3);
  }
  {
    p.distribution = "uniform";
    p.diameter_min = 1e-3;
    p.diameter_max = 3e-3;
    const auto v = femdem::packing_diameters(p, n);
    moments(v, mean, sd);
    const double sd_true = 2e-3 / std::sqrt(12.0);
    EXPECT_NEAR(mean, 2e-3, 4.0 * sd_true / std::sqrt(double(n)));
    EXPECT_NEAR(sd, sd_true, 4.0 * sd_true / std::sqrt(2.0 * double(n)));
    for (double x : v) {
      EXPECT_GE(x, 1e-3);
      EXPECT_LE(x, 3e-3);
    }
  }
  {  // lognormal: the truncated distribution's moments by quadrature
    p.distribution = "lognormal";
    p.diameter_mean = 1e-3;
    p.sigma = 0.3;
    p.diameter_min = 0.6e-3;
    p.diameter_max = 2e-3;
    const auto v = femdem::packing_diameters(p, n);
    moments(v, mean, sd);
    const double mu = std::log(1e-3) - 0.5 * 0.09;
    double w = 0, m1 = 0, m2 = 0;
    const int steps = 20000;
    const double a = std::log(0.6e-3), b = std::log(2e-3), h = (b - a) / steps;
    for (int i = 0; i < steps; ++i) {  // midpoint rule in ln d
      const double t = a + (i + 0.5) * h, x = std::exp(t);
      const double pdf = std::exp(-0.5 * (t - mu) * (t - mu) / 0.09);
      w += pdf;
      m1 += pdf * x;
      m2 += pdf * x * x;
    }
    m1 /= w;
    m2 /= w;
    const double sd_true = std::sqrt(m2 - m1 * m1);
    EXPECT_NEAR(mean, m1, 4.0 * sd_true / std::sqrt(double(n)));
    EXPECT_NEAR(sd, sd_true, 5.0 * sd_true / std::sqrt(2.0 * double(n)));
    for (double x : v) {
      EXPECT_GE(x, 0.6e-3);
      EXPECT_LE(x, 2e-3);
    }
    // the unclipped mean is diameter_mean: with a wide default window (3 sigma) it shows
    p.diameter_min = p.diameter_max = 0.0;
    moments(femdem::packing_diameters(p, n), mean, sd);
    EXPECT_NEAR(mean, 1e-3, 4.0 * 0.31e-3 / std::sqrt(double(n)) + 0.003e-3);
  }
}

// Poured monodisperse spheres: a loose random packing (random loose to random close packing,
// 0.55-0.64; friction 0.5 gives about 0.6 in the bulk), at rest, without overlaps, inside.
TEST(Packing, RandomMonodisperseSettlesToLooseRandomPacking) {
  const PackingParams p = random_box(1000, 10.0, 25.0);
  const auto t0 = std::chrono::steady_clock::now();
  const Packing pk = femdem::generate_packing(p);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(pk.particles.size(), 1000u);
  const auto& s = pk.stats;
  std::printf("1000 spheres: %.3f s, %lld steps, core fraction %.4f, bed fraction %.4f\n", seconds,
              static_cast<long long>(s.settle_steps), s.core_packing_fraction, s.packing_fraction);
  EXPECT_TRUE(s.at_rest);
  EXPECT_LT(s.max_speed, 1e-3);
  ASSERT_TRUE(std::isfinite(s.core_packing_fraction));
  EXPECT_GT(s.core_packing_fraction, 0.55);
  EXPECT_LT(s.core_packing_fraction, 0.64);
  // the whole bed, with its rough top and the looser layers at the walls, is less dense
  EXPECT_LT(s.packing_fraction, s.core_packing_fraction);
  EXPECT_GT(s.packing_fraction, 0.45);
  EXPECT_GE(min_relative_gap(pk), -1e-8);
  EXPECT_NEAR(s.min_gap, min_relative_gap(pk), 1e-12);
  expect_inside(p, pk);
}

// Polydisperse particles in a cylinder; a non-spherical shape gets random unit orientations.
TEST(Packing, LognormalInCylinderWithRandomOrientations) {
  PackingParams p;
  p.container = "cylinder";
  p.radius = 4e-3;
  p.height = 10e-3;
  p.count = 200;
  p.distribution = "lognormal";
  p.diameter_mean = 1e-3;
  p.sigma = 0.25;
  p.shape = "grain";
  const Packing pk = femdem::generate_packing(p);
  ASSERT_EQ(pk.particles.size(), 200u);
  EXPECT_TRUE(pk.stats.at_rest);
  EXPECT_GE(min_relative_gap(pk), -1e-8);
  expect_inside(p, pk);
  double w_sum = 0.0;
  for (const auto& q : pk.particles) {
    EXPECT_EQ(q.shape, "grain");
    EXPECT_NEAR(q.orientation.norm(), 1.0, 1e-12);
    w_sum += std::abs(q.orientation.w());
  }
  EXPECT_LT(w_sum / 200.0, 0.95);  // not the identity
  const auto text = femdem::packing_params_text(p);
  EXPECT_NE(text.find("orientation = \"random\""), std::string::npos) << text;
}

TEST(Packing, SameSeedSameBytesOtherSeedOtherPacking) {
  PackingParams p = random_box(150, 6.0, 20.0);
  p.distribution = "uniform";
  p.diameter_min = 0.8e-3;
  p.diameter_max = 1.2e-3;
  const std::string a = femdem::packing_file_text(femdem::generate_packing(p));
  const std::string b = femdem::packing_file_text(femdem::generate_packing(p));
  EXPECT_EQ(a, b);
  p.seed = 8;
  const std::string c = femdem::packing_file_text(femdem::generate_packing(p));
  EXPECT_NE(a, c);
  EXPECT_NE(a.find("seed = 7"), std::string::npos);
}

TEST(Packing, BadParametersNameTheKey) {
  auto key_of = [](PackingParams p) {
    const auto e = femdem::check_packing_params(p);
    return e ? e->key : std::string("(none)");
  };
  const PackingParams ok = random_box(10, 5, 5);
  EXPECT_EQ(key_of(ok), "(none)");
  PackingParams p = ok;
  p.container = "sphere";
  EXPECT_EQ(key_of(p), "container");
  p = ok;
  p.size.y() = 0;
  EXPECT_EQ(key_of(p), "size");
  p = ok;
  p.count = 0;
  EXPECT_EQ(key_of(p), "count");
  p = ok;
  p.arrangement = "hexagonal";
  EXPECT_EQ(key_of(p), "arrangement");
  p = ok;
  p.diameter = 6e-3;  // larger than the box
  EXPECT_EQ(key_of(p), "diameter");
  p = ok;
  p.distribution = "uniform";
  p.diameter_min = 1e-3;
  p.diameter_max = 0.5e-3;
  EXPECT_EQ(key_of(p), "diameter_max");
  p.diameter_max = 30e-3;
  EXPECT_EQ(key_of(p), "diameter_max");
  p = ok;
  p.distribution = "lognormal";
  p.diameter_mean = 1e-3;
  p.sigma = 0.0;
  EXPECT_EQ(key_of(p), "sigma");
  p.sigma = 0.2;
  p.diameter_min = 3e-3;  // the window holds almost nothing
  p.diameter_max = 4e-3;
  EXPECT_EQ(key_of(p), "diameter_min");
  p = thesis_box();
  p.distribution = "uniform";
  p.diameter_min = 1e-3;
  p.diameter_max = 2e-3;
  EXPECT_EQ(key_of(p), "distribution");
  p = ok;
  p.container = "cylinder";  // found by fuzzing: overflowed the settling grid's cell index
  p.radius = 1e13;
  p.height = 6e-3;
  EXPECT_EQ(key_of(p), "radius");
  p = ok;
  p.size.z() = 1e5 * 1.01 * ok.diameter;
  EXPECT_EQ(key_of(p), "size");
  p = ok;
  p.orientation = "sideways";
  EXPECT_EQ(key_of(p), "orientation");
  p = ok;
  p.friction = -1;
  EXPECT_EQ(key_of(p), "friction");
  p = ok;
  p.count = 2000;  // 2000 spheres of 1 mm do not fit in a 5 mm cube
  try {
    femdem::generate_packing(p);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "count");
  }
}

}  // namespace
