// SPDX-License-Identifier: GPL-3.0-or-later
// Particle packings (io/packing.hpp): lattices, size distributions, random packings settled
// under gravity, the packing file, the scene section [[packings]] and `femdem pack`.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/packing/packing.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::InputError;
using femdem::Packing;
using femdem::PackingParams;
using femdem::Vec3;
constexpr double kPi = std::numbers::pi;

fs::path tmp_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "packing" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// Brute force over all pairs: the smallest (distance - r_i - r_j) / (r_i + r_j).
double min_relative_gap(const Packing& pk) {
  double g = std::numeric_limits<double>::infinity();
  const auto& ps = pk.particles;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      const double rs = ps[i].radius + ps[j].radius;
      g = std::min(g, ((ps[i].centre - ps[j].centre).norm() - rs) / rs);
    }
  return g;
}

// Every particle inside the container (top included), within a relative tolerance.
void expect_inside(const PackingParams& p, const Packing& pk, double tol = 1e-9) {
  for (const auto& q : pk.particles) {
    const Vec3& c = q.centre;
    const double r = q.radius, t = tol * r;
    if (p.container == "box") {
      EXPECT_GE(c.x() - r, -t);
      EXPECT_GE(c.y() - r, -t);
      EXPECT_GE(c.z() - r, -t);
      EXPECT_LE(c.x() + r, p.size.x() + t);
      EXPECT_LE(c.y() + r, p.size.y() + t);
      EXPECT_LE(c.z() + r, p.size.z() + t);
    } else {
      EXPECT_LE(std::hypot(c.x(), c.y()) + r, p.radius + t);
      EXPECT_GE(c.z() - r, -t);
      EXPECT_LE(c.z() + r, p.height + t);
    }
  }
}

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

PackingParams random_box(std::int64_t count, double side_d, double height_d) {
  PackingParams p;
  const double d = 1e-3;
  p.size = Vec3(side_d * d, side_d * d, height_d * d);
  p.arrangement = "random";
  p.count = count;
  p.diameter = d;
  p.seed = 7;
  return p;
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

TEST(Packing, SaveLoadRoundTrip) {
  PackingParams p = random_box(60, 5.0, 10.0);
  p.shape = "grain";
  const Packing pk = femdem::generate_packing(p);
  const fs::path file = tmp_dir("roundtrip") / "grains.csv";
  femdem::write_packing(file.string(), pk);
  const Packing back = femdem::read_packing(file.string());
  ASSERT_EQ(back.particles.size(), pk.particles.size());
  for (std::size_t i = 0; i < pk.particles.size(); ++i) {
    EXPECT_EQ(back.particles[i].centre, pk.particles[i].centre);
    EXPECT_EQ(back.particles[i].radius, pk.particles[i].radius);
    EXPECT_EQ(back.particles[i].orientation.coeffs(), pk.particles[i].orientation.coeffs());
    EXPECT_EQ(back.particles[i].shape, "grain");
  }
  EXPECT_EQ(back.params_text, femdem::packing_params_text(p));
  EXPECT_EQ(back.generator, pk.generator);
  // a hand-written file needs only the column line
  write_text(file, "id,shape,x,y,z,radius,qw,qx,qy,qz\n1,sphere,0,0,1,1,1,0,0,0\n");
  EXPECT_EQ(femdem::read_packing(file.string()).particles.size(), 1u);
}

TEST(Packing, BadFilesNameTheLine) {
  const fs::path dir = tmp_dir("badfiles");
  const std::string head = "# x\nid,shape,x,y,z,radius,qw,qx,qy,qz\n";
  struct Case {
    std::string text;
    int line;
    std::string contains;
  } cases[] = {
      {"id,x,y\n", 1, "column line"},
      {head + "1,sphere,0,0,1,1,1,0,0\n", 3, "10 fields"},
      {head + "1,sphere,0,zero,1,1,1,0,0,0\n", 3, "'zero'"},
      {head + "1,sphere,0,0,1,-1,1,0,0,0\n", 3, "radius"},
      {head + "1,sphere,0,0,1,1,1,0,0,0\n2,sphere,0,0,1,1,2,0,0,0\n", 4, "unit length"},
      {head, 0, "no particles"},
  };
  for (const auto& c : cases) {
    write_text(dir / "bad.csv", c.text);
    try {
      femdem::read_packing((dir / "bad.csv").string());
      ADD_FAILURE() << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line, c.line) << e.describe();
      EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.describe();
    }
  }
  EXPECT_THROW(femdem::read_packing((dir / "missing.csv").string()), InputError);
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

// ---------------------------------------------------------------------------------------------
// Scenes

const char* kSceneHead = R"(title = "packing"
[simulation]
end_time = 1e-5
[[materials]]
name = "powder"
model = "von_mises"
density = 7800
youngs_modulus = 110e9
poisson_ratio = 0.3
yield_stress = 30e6
hardening_modulus = 0.1e9
)";

TEST(PackingScene, GeneratedLatticeBecomesOneBodyPerParticle) {
  const fs::path dir = tmp_dir("scene_lattice");
  write_text(dir / "s.toml", std::string(kSceneHead) + R"(
[[packings]]
material = "powder"
mesh = { generator = "sphere", cells_per_radius = 1 }
generate = { container = "box", size = [0.01, 0.01, 0.01], arrangement = "simple_cubic", diameter = 2.5e-3 }
position = [1.0, 0.0, 0.0]
)");
  const femdem::SceneFile s = femdem::load_scene((dir / "s.toml").string());
  ASSERT_EQ(s.model.bodies.size(), 64u);
  EXPECT_EQ(s.model.bodies[0].name, "p0001");
  EXPECT_EQ(s.model.bodies[63].name, "p0064");
  // each sphere: radius 1.25 mm about its site (+ position)
  const auto& b = s.model.bodies[0];
  Vec3 lo = b.mesh.nodes[0], hi = b.mesh.nodes[0];
  for (const Vec3& x : b.mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  EXPECT_NEAR(lo.x(), 1.0, 1e-12);
  EXPECT_NEAR(hi.x(), 1.0025, 1e-12);
  EXPECT_NEAR(lo.z(), 0.0, 1e-12);
  EXPECT_NE(s.resolved_toml.find("[[packings]]"), std::string::npos) << s.resolved_toml;
  EXPECT_NE(s.resolved_toml.find("arrangement = \"simple_cubic\""), std::string::npos);
  // the resolved scene reads back to the same bodies
  write_text(dir / "resolved.toml", s.resolved_toml);
  const femdem::SceneFile r = femdem::load_scene((dir / "resolved.toml").string());
  ASSERT_EQ(r.model.bodies.size(), 64u);
  EXPECT_EQ(r.model.bodies[40].mesh.nodes, s.model.bodies[40].mesh.nodes);
}

// `rotation` turns the whole packing about the container's origin, before `position`: a
// layer settled in a box is laid on a slope. Every node of the turned scene is R x + position
// of the same node in the unturned one, with R = Rz(30) Ry(-20) Rx(10) built here from the
// documented convention (docs/SCENES.md), not from the reader's helper.
TEST(PackingScene, RotationTurnsTheWholePackingAboutTheContainerOrigin) {
  const fs::path dir = tmp_dir("scene_rotation");
  const std::string packing = R"(
[[packings]]
material = "powder"
mesh = { generator = "sphere", cells_per_radius = 1 }
generate = { container = "box", size = [0.01, 0.01, 0.01], arrangement = "simple_cubic", diameter = 2.5e-3 }
position = [1.0, 2.0, 3.0]
)";
  write_text(dir / "plain.toml", std::string(kSceneHead) + packing);
  write_text(dir / "turned.toml", std::string(kSceneHead) + packing + "rotation = [10, -20, 30]\n");
  const femdem::SceneFile a = femdem::load_scene((dir / "plain.toml").string());
  const femdem::SceneFile b = femdem::load_scene((dir / "turned.toml").string());
  ASSERT_EQ(a.model.bodies.size(), 64u);
  ASSERT_EQ(b.model.bodies.size(), 64u);
  const double k = std::numbers::pi / 180.0;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(30 * k, Vec3::UnitZ()) * Eigen::AngleAxisd(-20 * k, Vec3::UnitY()) *
       Eigen::AngleAxisd(10 * k, Vec3::UnitX()))
          .toRotationMatrix();
  const Vec3 position(1.0, 2.0, 3.0);
  double worst = 0.0;
  for (std::size_t i = 0; i < 64; ++i) {
    const auto& xa = a.model.bodies[i].mesh.nodes;
    const auto& xb = b.model.bodies[i].mesh.nodes;
    ASSERT_EQ(xa.size(), xb.size());
    for (std::size_t n = 0; n < xa.size(); ++n)
      worst = std::max(worst, (xb[n] - (R * (xa[n] - position) + position)).norm());
  }
  EXPECT_LT(worst, 1e-14);  // coordinates of order 3 m: a few ulp
  EXPECT_NE(b.resolved_toml.find("rotation = [10.0, -20.0, 30.0]"), std::string::npos)
      << b.resolved_toml;
}

TEST(PackingScene, CacheIsWrittenReusedAndRegeneratedWhenStale) {
  const fs::path dir = tmp_dir("scene_cache");
  const std::string scene = std::string(kSceneHead) + R"(
[[packings]]
name = "g"
material = "powder"
mesh = { generator = "sphere", element_size = 1e-3 }
generate = { size = [5e-3, 5e-3, 8e-3], count = 20, diameter = 1e-3, seed = 3 }
cache = "cache/g.csv"
)";
  write_text(dir / "s.toml", scene);
  fs::create_directories(dir / "cache");
  const femdem::SceneFile a = femdem::load_scene((dir / "s.toml").string());
  ASSERT_EQ(a.model.bodies.size(), 20u);
  EXPECT_EQ(a.model.bodies[19].name, "g0020");
  ASSERT_TRUE(fs::exists(dir / "cache" / "g.csv"));
  // Reused: mark the cached file (a moved particle); the scene then has the marked position.
  std::string text = read_text(dir / "cache" / "g.csv");
  const Packing pk = femdem::read_packing((dir / "cache" / "g.csv").string());
  Packing moved = pk;
  moved.particles[0].centre.x() += 1e-6;
  femdem::write_packing((dir / "cache" / "g.csv").string(), moved);
  const femdem::SceneFile b = femdem::load_scene((dir / "s.toml").string());
  EXPECT_NEAR(b.model.bodies[0].mesh.nodes[0].x() - a.model.bodies[0].mesh.nodes[0].x(), 1e-6,
              1e-15);
  // Stale (another seed): generated again and the cache replaced.
  const femdem::SceneFile c =
      femdem::load_scene((dir / "s.toml").string(), {"packings.g.generate.seed=4"});
  EXPECT_NE(read_text(dir / "cache" / "g.csv"), text);
  EXPECT_NE(read_text(dir / "cache" / "g.csv").find("seed = 4"), std::string::npos);
  // and a file given as `file` is read as it is
  write_text(dir / "f.toml", std::string(kSceneHead) + R"(
[[packings]]
material = "powder"
mesh = { generator = "sphere", cells_per_radius = 2 }
file = "cache/g.csv"
)");
  const femdem::SceneFile f = femdem::load_scene((dir / "f.toml").string());
  EXPECT_EQ(f.model.bodies.size(), 20u);
}

TEST(PackingScene, BadInputNamesFileLineAndKey) {
  const fs::path dir = tmp_dir("scene_bad");
  struct Case {
    std::string body;
    std::string key;
    int line;  // of the offending value, counted in kSceneHead + "\n[[packings]]\n" + body
  } cases[] = {
      {"material = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\n",
       "packings.p", 0},
      {"material = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\nfile = "
       "\"nope.csv\"\n",
       "packings.p.file", 16},
      {"material = \"steel\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\nfile = "
       "\"p.csv\"\n",
       "packings.p.material", 14},
      {"material = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\ngenerate = "
       "{ size = [0.01, 0.01, 0.01], count = 5, diameter = -1 }\n",
       "packings.p.generate.diameter", 16},
      {"material = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\ngenerate = "
       "{ size = [0.01, 0.01, 0.01], count = 5, diameter = 1e-3, sigma = 1 }\n",
       "packings.p.generate.sigma", 16},
      {"material = \"powder\"\nmesh = { generator = \"sphere\", radius = 1 }\nfile = \"p.csv\"\n",
       "packings.p.mesh.radius", 15},
      {"material = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius = 1 }\nfile = "
       "\"p.csv\"\nspeed = 1\n",
       "packings.p.speed", 17},
      {"name = \"ball\"\nmaterial = \"powder\"\nmesh = { generator = \"sphere\", cells_per_radius "
       "= 1 "
       "}\nfile = \"bad.csv\"\n",
       "packings.ball.file", 17},
  };
  write_text(dir / "p.csv", "id,shape,x,y,z,radius,qw,qx,qy,qz\n1,sphere,0,0,1,1,1,0,0,0\n");
  write_text(dir / "bad.csv", "id,shape,x,y,z,radius,qw,qx,qy,qz\n1,sphere,0,0,1\n");
  int i = 0;
  for (const auto& c : cases) {
    std::string name = "s";  // built by appending: GCC 12 warns (-Wrestrict) on "s" + string
    name += std::to_string(i++);
    name += ".toml";
    const fs::path scene = dir / name;
    write_text(scene, std::string(kSceneHead) + "\n[[packings]]\n" + c.body);
    try {
      femdem::load_scene(scene.string());
      ADD_FAILURE() << c.body;
    } catch (const InputError& e) {
      EXPECT_EQ(e.key, c.key) << e.describe();
      if (c.line > 0) {
        EXPECT_EQ(e.line, c.line) << e.describe();
      }
      EXPECT_EQ(e.file, scene.string()) << e.describe();
    }
  }
  // through the program: exit code 2 and the usual message
  const auto r = femdem::test::run_command(std::string("'") + FEMDEM_EXE + "' check '" +
                                           (dir / "s1.toml").string() + "'");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("s1.toml:16:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("packings.p.file"), std::string::npos) << r.output;
}

// ---------------------------------------------------------------------------------------------
// The program

TEST(PackingCli, PackWritesTheFileAndReportsIt) {
  const fs::path dir = tmp_dir("cli");
  const std::string exe = std::string("'") + FEMDEM_EXE + "'";
  auto r = femdem::test::run_command(
      exe + " pack '" + (dir / "sc.csv").string() +
      "' --size 0.01,0.01,0.01 --arrangement simple_cubic --diameter 2.5e-3");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("64 particles"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.5236"), std::string::npos) << r.output;
  EXPECT_EQ(femdem::read_packing((dir / "sc.csv").string()).particles.size(), 64u);

  const std::string random = " --size 0.005,0.005,0.01 --count 40 --diameter 1e-3 --seed 5";
  r = femdem::test::run_command(exe + " pack '" + (dir / "a.csv").string() + "'" + random);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("at rest"), std::string::npos) << r.output;
  r = femdem::test::run_command(exe + " pack '" + (dir / "b.csv").string() + "'" + random);
  EXPECT_EQ(read_text(dir / "a.csv"), read_text(dir / "b.csv"));

  r = femdem::test::run_command(exe + " pack '" + (dir / "c.csv").string() +
                                "' --size 0.005,0.005,0.01 --count 40 --diameter -1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--diameter"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "c.csv"));
  r = femdem::test::run_command(exe + " pack '" + (dir / "c.csv").string() +
                                "' --size 0.005,0.005 --count 40 --diameter 1e-3");
  EXPECT_EQ(r.code, 2) << r.output;
}

}  // namespace

namespace {

// The shipped packing for die compaction (scenes/packings/powder_die_250.csv, written by the
// `femdem pack` command in docs/OUTPUTS.md): complete, without overlaps, inside its die.
TEST(Packing, ShippedDiePackingIsValid) {
  const Packing pk =
      femdem::read_packing(std::string(FEMDEM_SOURCE_DIR) + "/scenes/packings/powder_die_250.csv");
  ASSERT_EQ(pk.particles.size(), 250u);
  PackingParams p;
  p.container = "cylinder";
  p.radius = 4e-3;
  p.height = 12e-3;
  EXPECT_GE(min_relative_gap(pk), 0.0);
  expect_inside(p, pk);
  EXPECT_NE(pk.params_text.find("count = 250"), std::string::npos) << pk.params_text;
  EXPECT_NE(pk.params_text.find("friction = 0.5"), std::string::npos) << pk.params_text;
}

}  // namespace
