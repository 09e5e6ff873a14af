// SPDX-License-Identifier: GPL-3.0-or-later
// Compaction, engine side: a force-driven wall (a punch under a prescribed load) against the
// analytic static answer, and the Heckel and Kawakita fits against exact synthetic curves.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/compaction.hpp"
#include "engine/contact_stiffness.hpp"
#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"

using namespace femdem;

namespace {

constexpr double kE = 1e7, kNu = 0.3, kRho = 1000.0;
constexpr double kA = 0.1 * 0.1, kL = 0.2;  // block cross-section and length

// A 0.1 x 0.1 x 0.2 m elastic block standing on a fixed floor (z = 0), both walls frictionless,
// and a punch wall on its top face (z = L, facing down) loaded by `force` (N) along its normal.
// penalty_factor 0: the automatic wall stiffness.
ModelSpec block_under_punch(std::vector<ForcePoint> force, double punch_mass,
                            double penalty_factor = 0.0) {
  ModelSpec s;
  s.contact.penalty_factor = penalty_factor;
  MaterialParams mat;
  mat.name = "soft";
  mat.density = kRho;
  mat.youngs_modulus = kE;
  mat.poisson_ratio = kNu;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = "block";
  b.material = 0;
  b.mesh = test::kuhn_box(2, 2, 4, Vec3(0.1, 0.1, kL));
  s.bodies.push_back(b);
  WallSpec floor;
  floor.name = "floor";
  floor.normal = Vec3(0, 0, 1);
  s.walls.push_back(floor);
  WallSpec punch;
  punch.name = "punch";
  punch.point = Vec3(0, 0, kL);
  punch.normal = Vec3(0, 0, -1);
  punch.force_history = std::move(force);
  punch.mass = punch_mass;
  s.walls.push_back(punch);
  return s;
}

// The static shortening under F: the block's F L / (E A), plus with the automatic stiffness the
// two walls' layers of node springs, F h / (3.2 M A) each (h = 0.05 m the element depth, M the
// P-wave modulus; engine/contact_stiffness.hpp). With factor 100 the springs (100 E) add 0.5 %,
// left to the tolerances.
double static_displacement(double F, double penalty_factor) {
  const double p_wave = kE * (1 - kNu) / ((1 + kNu) * (1 - 2 * kNu)), h = 0.05;
  const double walls = penalty_factor > 0.0 ? 0.0 : 2.0 * F * h / (kAutoWallFactor * p_wave * kA);
  return F * kL / (kE * kA) + walls;
}

}  // namespace

// Uniaxial stress: the block shortens by F L / (E A) (small strain, 5e-4 here). The load rises
// over 10 periods of the punch-on-block system and is then held for 6; the punch oscillates about
// the static position with what the ramp left, so its mean over the hold is compared. Each wall
// adds the compliance of its layer of node springs, F / sum(k) (static_displacement): 11.6 % of
// the answer with the automatic stiffness, which this checks.
TEST(Compaction, ForceDrivenPunchReachesTheStaticDisplacement) {
  const double F = 50.0, M = 1.0;
  const double k = kE * kA / kL;  // 5e5 N/m
  const double period = 2.0 * std::acos(-1.0) * std::sqrt((M + kRho * kA * kL / 3.0) / k);
  const double t_ramp = 10.0 * period, t_end = t_ramp + 6.0 * period;
  for (const double penalty_factor : {100.0, 0.0}) {
    Simulation sim(build_model(block_under_punch({{0.0, 0.0}, {t_ramp, F}}, M, penalty_factor)));
    double sum = 0.0, force_sum = 0.0, wsum = 0.0;
    while (sim.time() < t_end) {
      sim.step(t_end - sim.time());
      if (sim.time() > t_ramp) {
        const double dt = sim.dt();
        sum += dt * (kL - sim.wall_position(1).z());
        force_sum += dt * sim.wall_force(1).z();  // the block pushes the punch up
        wsum += dt;
      }
    }
    const double mean = sum / wsum, expected = static_displacement(F, penalty_factor);
    std::printf(
        "penalty factor %g: punch displacement %.6e m, F L / (E A) + walls = %.6e m (%+.2f %%); "
        "force %.3f N (load %.1f N); %lld steps\n",
        penalty_factor, mean, expected, 100.0 * (mean / expected - 1.0), force_sum / wsum, F,
        static_cast<long long>(sim.steps()));
    EXPECT_NEAR(mean / expected, 1.0, 0.015);
    EXPECT_NEAR(force_sum / wsum / F, 1.0, 0.01);
  }
}

// Unloading by the force: a ramp up, then down to zero. The block springs back and pushes the
// punch away, after which the punch carries no force.
TEST(Compaction, ForceDrivenPunchUnloads) {
  const double F = 50.0, M = 1.0;
  const double k = kE * kA / kL;
  const double period = 2.0 * std::acos(-1.0) * std::sqrt((M + kRho * kA * kL / 3.0) / k);
  const double t1 = 8.0 * period, t2 = 16.0 * period, t_end = 19.0 * period;
  Simulation sim(build_model(block_under_punch({{0.0, 0.0}, {t1, F}, {t2, 0.0}}, M)));
  const double expected = static_displacement(F, 0.0);
  double max_disp = 0.0;
  while (sim.time() < t_end) {
    sim.step(t_end - sim.time());
    max_disp = std::max(max_disp, kL - sim.wall_position(1).z());
  }
  std::printf(
      "largest punch displacement %.4e m (static %.4e m); final force %.3g N, final "
      "displacement %.3e m\n",
      max_disp, expected, sim.wall_force(1).z(), kL - sim.wall_position(1).z());
  EXPECT_NEAR(max_disp / expected, 1.0, 0.05);
  EXPECT_LT(std::fabs(sim.wall_force(1).z()), 0.02 * F);
  EXPECT_LT(kL - sim.wall_position(1).z(), 0.1 * expected);
}

TEST(Compaction, BodiesVolumeIsTheMeshVolume) {
  Simulation sim(build_model(block_under_punch({{0.0, 0.0}}, 1.0)));
  const std::uint8_t mask[] = {1}, none[] = {0};
  EXPECT_NEAR(sim.bodies_volume(mask), kA * kL, 1e-15);
  EXPECT_EQ(sim.bodies_volume(none), 0.0);
}

// Heckel: D = 1 - exp(-(K P + A)) is a straight line in ln(1 / (1 - D)); points outside the
// pressure range are off the line and must be left out.
TEST(Compaction, HeckelFitRecoversKAndA) {
  const double K = 2.5e-8, A = 0.7;  // yield pressure 40 MPa
  std::vector<double> P, D;
  for (int i = 0; i <= 50; ++i) {
    const double p = 1e6 + i * 4e6;
    P.push_back(p);
    D.push_back(1.0 - std::exp(-(K * p + A)));
  }
  // an off-line early (rearrangement) part below 10 MPa
  for (std::size_t i = 0; i < P.size(); ++i)
    if (P[i] < 10e6) D[i] *= 0.8;
  const HeckelFit h = fit_heckel(P, D, 10e6, 1e9);
  EXPECT_NEAR(h.K / K, 1.0, 1e-10);
  EXPECT_NEAR(h.A, A, 1e-10);
  EXPECT_NEAR(h.yield_pressure, 1.0 / K, 1e-10 / K);
  EXPECT_NEAR(h.r2, 1.0, 1e-12);
  EXPECT_EQ(h.points, 48);
  // with the off-line points the fit is worse: the range matters
  EXPECT_LT(fit_heckel(P, D, 0.0, 1e9).r2, 0.9999);
}

// Kawakita: C = a b P / (1 + b P), so P / C = P / a + 1 / (a b).
TEST(Compaction, KawakitaFitRecoversAAndB) {
  const double a = 0.45, b = 3e-8;
  std::vector<double> P, C;
  for (int i = 1; i <= 40; ++i) {
    const double p = i * 5e6;
    P.push_back(p);
    C.push_back(a * b * p / (1.0 + b * p));
  }
  const KawakitaFit k = fit_kawakita(P, C, 0.0, 1e12);
  EXPECT_NEAR(k.a, a, 1e-10);
  EXPECT_NEAR(k.b / b, 1.0, 1e-9);
  EXPECT_NEAR(k.r2, 1.0, 1e-12);
  EXPECT_EQ(k.points, 40);
}

TEST(Compaction, LineFitNeedsTwoDistinctAbscissae) {
  const double x[] = {1.0, 1.0}, y[] = {2.0, 3.0};
  EXPECT_EQ(fit_line(x, y).points, 0);
  EXPECT_TRUE(std::isnan(fit_line(x, y).slope));
  EXPECT_EQ(fit_line(std::span<const double>(x, 1), std::span<const double>(y, 1)).points, 0);
}
