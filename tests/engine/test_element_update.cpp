// SPDX-License-Identifier: GPL-3.0-or-later
// The SIMD element update (engine/element_update/) against the scalar kernel it replaces
// (engine/element_kernel.hpp, the reference): forces, Cauchy stresses, Gauss-point history and
// the elements' energies agree to 1e-12 relative over a load path that yields some points and
// not others in the same pack, starts from repeated principal stretches (a homogeneous
// uniaxial stretch of the undeformed block) and goes on with random ones, for every material
// model the SIMD update has, every F-bar mode (the nodal one with its corner pressure weights),
// straight-sided and curved elements, and every instruction set this machine runs (which also agree
// with each other to 1e-12); the pressure-dependent models to 3e-12 (see Case::tolerance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "engine/element_pass.hpp"
#include "engine/simulation.hpp"
#include "support/kuhn_box.hpp"
#include "support/test_material.hpp"

namespace femdem {
namespace {

MaterialBase steel_base() {
  MaterialBase b;
  b.name = "steel";
  b.density = 7800.0;
  b.youngs_modulus = 200e9;
  b.poisson_ratio = 0.3;
  return b;
}

MaterialParams elastic() {
  MaterialParams p;
  static_cast<MaterialBase&>(p) = steel_base();
  return p;
}

MaterialParams von_mises(VonMisesParams v) {
  MaterialParams p;
  static_cast<MaterialBase&>(p) = steel_base();
  p.model = v;
  return p;
}

VonMisesParams linear(double H) {
  VonMisesParams v;
  v.yield_stress = 250e6;
  v.hardening_modulus = H;
  return v;
}

struct Case {
  std::string name;
  MaterialParams material;
  // Elastic and von Mises: 1e-12. The pressure-dependent models' returns are worse conditioned
  // (their apex, edge and softening returns amplify the last-bit differences of the trial
  // strains more): 3e-12, measured up to 2.2e-12 (Mohr-Coulomb with softening).
  double tolerance = 1e-12;
};

// A soft-rock-like frictional material (E 10 GPa, c 15 MPa): the path's strains go past its
// strength, into tension (apex returns), compression and the equal principal stretches of the
// first step (edge returns of Mohr-Coulomb). (The two kernels' rounding differences grow with
// E / strength, the return mapping's condition number: about 1e-16 E / c per step; a concrete's
// E / c of 2000 puts them at 2-4e-12, this one's 670 below 1e-12, like steel's 800.)
template <class P>
MaterialParams frictional(P params) {
  MaterialParams p;
  p.name = "rock";
  p.density = 2400.0;
  p.youngs_modulus = 10e9;
  p.poisson_ratio = 0.2;
  p.model = params;
  return p;
}

template <class P>
P frictional_params(double c, double phi, double psi, double H = 0.0, double residual = 0.0) {
  P p;
  p.cohesion = c;
  p.friction_angle = phi;
  p.dilatancy_angle = psi;
  p.cohesion_hardening_modulus = H;
  p.residual_cohesion = residual;
  return p;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  out.push_back({"elastic", elastic()});
  out.push_back({"von_mises_linear", von_mises(linear(1e9))});
  out.push_back({"von_mises_softening", von_mises(linear(-2e9))});
  VonMisesParams tab;
  tab.hardening = HardeningLaw::Tabulated;
  tab.hardening_curve = {{0.0, 250e6}, {0.002, 300e6}, {0.01, 320e6}, {0.05, 330e6}};
  tab.yield_stress = 250e6;
  out.push_back({"von_mises_tabulated", von_mises(tab)});
  VonMisesParams swift;
  swift.hardening = HardeningLaw::Swift;
  swift.swift_K = 600e6;
  swift.swift_eps0 = 0.01;
  swift.swift_n = 0.2;
  swift.yield_stress = swift.swift_K * std::pow(swift.swift_eps0, swift.swift_n);
  out.push_back({"von_mises_swift", von_mises(swift)});
  VonMisesParams jc = linear(1e9);
  jc.jc_C = 0.02;
  jc.jc_epsdot0 = 1.0;
  out.push_back({"von_mises_johnson_cook", von_mises(jc)});
  const std::size_t first_frictional = out.size();
  out.push_back({"drucker_prager_associated",
                 frictional(frictional_params<DruckerPragerParams>(15e6, 30.0, 30.0))});
  out.push_back({"drucker_prager_softening",
                 frictional(frictional_params<DruckerPragerParams>(15e6, 30.0, 10.0, -2e8, 3e6))});
  auto dp_inner = frictional_params<DruckerPragerParams>(15e6, 30.0, 0.0);
  dp_inner.cone = DruckerPragerCone::Inner;
  out.push_back({"drucker_prager_no_dilatancy", frictional(dp_inner)});
  out.push_back({"mohr_coulomb_associated",
                 frictional(frictional_params<MohrCoulombParams>(15e6, 30.0, 30.0))});
  out.push_back({"mohr_coulomb_softening",
                 frictional(frictional_params<MohrCoulombParams>(15e6, 30.0, 10.0, -2e8, 3e6))});
  out.push_back({"mohr_coulomb_no_dilatancy",
                 frictional(frictional_params<MohrCoulombParams>(15e6, 30.0, 0.0, 2e8))});
  out.push_back({"tresca", frictional(frictional_params<MohrCoulombParams>(15e6, 0.0, 0.0))});
  PiecewiseDruckerPragerParams pw;
  pw.pieces = {{0.42, 8e6}, {0.30, 14e6}, {0.14, 30e6}, {0.07, 40.5e6}, {0.035, 49.25e6}};
  pw.pieces_dilatancy = 0.02;
  out.push_back({"piecewise_drucker_prager", frictional(pw)});
  for (std::size_t i = first_frictional; i < out.size(); ++i) out[i].tolerance = 3e-12;
  return out;
}

Model block(const MaterialParams& mat, FbarMode fbar, bool curved) {
  ModelSpec s;
  s.materials.push_back(mat);
  BodySpec b;
  b.name = std::string("block");
  b.material = 0;
  // 3 x 2 x 1 cells of 6: 36 elements, with corners jittered (general shapes)
  b.mesh = test::kuhn_box(3, 2, 1, Vec3(0.03, 0.02, 0.01), 0.2, 7);
  if (curved) {
    // mid-edge nodes off their edges' midpoints by up to 3 % of the cell size
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::size_t corners = 4 * 3 * 2;  // (3+1)(2+1)(1+1) corner nodes come first
    for (std::size_t n = corners; n < b.mesh.nodes.size(); ++n)
      b.mesh.nodes[n] += 3e-4 * Vec3(u(rng), u(rng), u(rng));
  }
  b.fbar = fbar;
  s.bodies.push_back(b);
  return build_model(s);
}

// Step s of the load path: first the undeformed block stretched 0.5 % along x (two equal
// principal stretches, every point yielding: 0.125 % is this steel's yield strain); then random
// increments of 0.5 % weighted by (X / L)^2 along the block, with a fixed random nodal field:
// the points at the far end go on yielding, those near X = 0 barely move (elastic), so elastic
// and plastic points share packs. (Strains of this size keep the comparison well conditioned:
// the rounding of det F and of the log strains is relative to 1, so at a strain d two correct
// kernels differ by about 1e-16 / d relative.)
void deform(Model& m, int s, std::mt19937& rng, Eigen::Matrix3d& H) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  G(0, 0) = 5e-3;
  if (s == 1)
    H = Eigen::Matrix3d::Zero();
  else
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H(i, j) += 5e-3 * u(rng);
  std::mt19937 field(5);
  double length = 0.0;
  for (std::int32_t n = 0; n < m.node_count; ++n) length = std::fmax(length, m.X[3 * n]);
  for (std::int32_t n = 0; n < m.node_count; ++n) {
    const Vec3 X(m.X[3 * n], m.X[3 * n + 1], m.X[3 * n + 2]);
    const Vec3 r(u(field), u(field), u(field));
    const double a = (X.x() / length) * (X.x() / length);
    Vec3 x = X + G * X + a * (H * X);
    if (s > 1) x += 1e-6 * r;
    for (int k = 0; k < 3; ++k) m.x[3 * n + k] = x[k];
  }
}

double max_abs(const double* a, int n) {
  double m = 0.0;
  for (int i = 0; i < n; ++i) m = std::fmax(m, std::fabs(a[i]));
  return m;
}

// Largest difference of a and b over n numbers, relative to the largest |b| (or `floor`).
double relative_difference(const double* a, const double* b, int n, double floor = 0.0) {
  double d = 0.0;
  for (int i = 0; i < n; ++i) d = std::fmax(d, std::fabs(a[i] - b[i]));
  return d / std::fmax(max_abs(b, n), floor);
}

struct PassResult {
  std::vector<double> force, stress, pressure_weight, volume;
  std::vector<ElementStates> states;
  std::vector<ElementResult> results;
  int plastic_points = 0;
};

// The load path through one kernel.
std::vector<PassResult> run_path(const MaterialParams& mat, FbarMode fbar, bool curved,
                                 ElementKernelChoice choice) {
  Model m = block(mat, fbar, curved);
  const std::vector<MaterialKernel> kernels = {compile_material(mat)};
  ElementPass pass(m, kernels);
  pass.choose(choice);
  if (choice == ElementKernelChoice::simd) {
    EXPECT_EQ(pass.simd_elements(), m.element_count);
  }
  std::vector<double> force(30 * static_cast<std::size_t>(m.element_count));
  std::vector<ElementResult> results(m.element_count);
  // nodal F-bar's input: each corner node's volume ratio over the elements around it, from
  // the elements' volumes as this kernel's pass computes them (as Simulation::compute_forces)
  const bool nodal = fbar == FbarMode::Nodal;
  const std::size_t ne = static_cast<std::size_t>(m.element_count);
  std::vector<double> node_J(nodal ? m.node_count : 0), V(node_J.size(), 0.0), volume(ne);
  std::vector<double> pressure_weight(nodal ? 4 * ne : 0), volume_gradient(nodal ? 30 * ne : 0);
  for (std::size_t e = 0; e < ne && nodal; ++e)
    for (int c = 0; c < 4; ++c)
      for (int g = 0; g < 4; ++g) V[m.conn[e][c]] += m.gauss_weight[4 * e + g];
  auto corner_volume_ratios = [&] {
    pass.nodal_volumes(m, volume.data());
    std::vector<double> v(node_J.size(), 0.0);
    for (std::size_t e = 0; e < ne; ++e)
      for (int c = 0; c < 4; ++c) v[m.conn[e][c]] += volume[e];
    for (std::size_t n = 0; n < node_J.size(); ++n) node_J[n] = V[n] > 0.0 ? v[n] / V[n] : 1.0;
  };
  // ... and its pressure forces from the elements' corner weights and volume gradients, added
  // to the elements' forces (compute_forces' step 1b): the elements' whole forces are compared,
  // since at an apex return the deviatoric part the pass writes alone is round-off
  auto add_nodal_pressure = [&] {
    std::vector<double> Q(node_J.size(), 0.0);
    for (std::size_t e = 0; e < ne; ++e)
      for (int c = 0; c < 4; ++c) Q[m.conn[e][c]] += pressure_weight[4 * e + c];
    for (std::size_t e = 0; e < ne; ++e) {
      double q = 0.0;
      for (int c = 0; c < 4; ++c) q += Q[m.conn[e][c]] / V[m.conn[e][c]];
      for (int i = 0; i < 30; ++i) force[30 * e + i] += q * volume_gradient[30 * e + i];
    }
  };
  std::mt19937 rng(3);
  Eigen::Matrix3d H;
  std::vector<PassResult> path;
  for (int s = 1; s <= 6; ++s) {
    deform(m, s, rng, H);
    if (nodal) corner_volume_ratios();
    NodalFbarArrays arrays;
    if (nodal) arrays = {node_J.data(), pressure_weight.data(), volume_gradient.data()};
    pass.update(m, kernels, 1e-7, arrays, force, results);
    if (nodal) add_nodal_pressure();
    PassResult r{
        force,   m.stress, pressure_weight, nodal ? volume : std::vector<double>(), m.states,
        results, 0};
    std::vector<ElementStates> before =
        path.empty() ? std::vector<ElementStates>(m.element_count) : path.back().states;
    for (std::int32_t e = 0; e < m.element_count; ++e)
      for (int g = 0; g < 4; ++g) r.plastic_points += m.states[e].eps_p[g] > before[e].eps_p[g];
    path.push_back(std::move(r));
  }
  return path;
}

// The SIMD path against the reference, every step: the largest difference of each quantity
// over all elements relative to its largest value over all elements (normwise, as the error of
// a force vector is measured); the energies relative to the step's total.
void expect_agree(const std::vector<PassResult>& simd, const std::vector<PassResult>& ref,
                  const std::string& what, double tol) {
  ASSERT_EQ(simd.size(), ref.size());
  double worst_f = 0.0, worst_s = 0.0, worst_state = 0.0, worst_e = 0.0, worst_q = 0.0;
  for (std::size_t s = 0; s < ref.size(); ++s) {
    const int ne = static_cast<int>(ref[s].results.size());
    worst_f =
        std::fmax(worst_f, relative_difference(simd[s].force.data(), ref[s].force.data(), 30 * ne));
    worst_s = std::fmax(worst_s,
                        relative_difference(simd[s].stress.data(), ref[s].stress.data(), 24 * ne));
    if (!ref[s].pressure_weight.empty())
      worst_q = std::fmax(worst_q, relative_difference(simd[s].pressure_weight.data(),
                                                       ref[s].pressure_weight.data(), 4 * ne));
    if (!ref[s].volume.empty())
      worst_q =
          std::fmax(worst_q, relative_difference(simd[s].volume.data(), ref[s].volume.data(), ne));
    const auto* a = reinterpret_cast<const double*>(simd[s].states.data());
    const auto* b = reinterpret_cast<const double*>(ref[s].states.data());
    static_assert(sizeof(ElementStates) == 32 * sizeof(double));
    for (int e = 0; e < ne; ++e) {
      // Cp^-1 (24 numbers, about 1) and eps_p, kappa (relative to 1e-3 at least)
      worst_state = std::fmax(worst_state, relative_difference(a + 32 * e, b + 32 * e, 24, 1.0));
      worst_state =
          std::fmax(worst_state, relative_difference(a + 32 * e + 24, b + 32 * e + 24, 8, 1e-3));
    }
    // each element's energy and dissipation relative to the largest over the elements; its
    // det F and largest eps_p likewise
    double largest = 0.0, diff = 0.0, min_J = 0.0, eps = 0.0, eps_largest = 1e-3;
    double altitude = 0.0, altitude_largest = 0.0;
    for (int e = 0; e < ne; ++e) {
      const ElementResult &ra = simd[s].results[e], &rb = ref[s].results[e];
      largest = std::fmax(largest, std::fmax(std::fabs(rb.energy), std::fabs(rb.dissipation)));
      diff = std::fmax(diff, std::fabs(ra.energy - rb.energy));
      diff = std::fmax(diff, std::fabs(ra.dissipation - rb.dissipation));
      min_J = std::fmax(min_J, std::fabs(ra.min_J - rb.min_J));
      eps = std::fmax(eps, std::fabs(ra.max_eps_p - rb.max_eps_p));
      eps_largest = std::fmax(eps_largest, rb.max_eps_p);
      altitude = std::fmax(altitude, std::fabs(ra.min_altitude - rb.min_altitude));
      altitude_largest = std::fmax(altitude_largest, rb.min_altitude);
    }
    EXPECT_GT(altitude_largest, 0.0) << what;
    worst_e = std::fmax(worst_e, altitude / altitude_largest);
    worst_e = std::fmax(worst_e, std::fmax(diff / largest, std::fmax(min_J, eps / eps_largest)));
  }
  EXPECT_LT(worst_f, tol) << what << ": forces";
  EXPECT_LT(worst_s, tol) << what << ": stresses";
  EXPECT_LT(worst_state, tol) << what << ": state";
  EXPECT_LT(worst_e, tol) << what << ": energies, det F, eps_p, altitude";
  EXPECT_LT(worst_q, tol) << what << ": nodal F-bar pressure weights and volumes";
  std::printf("%-52s force %.1e stress %.1e state %.1e energy %.1e pressure %.1e\n", what.c_str(),
              worst_f, worst_s, worst_state, worst_e, worst_q);
}

TEST(ElementUpdate, SimdAgreesWithScalarKernelOnEveryInstructionSet) {
  const std::vector<std::string> targets = element_update_targets();
  ASSERT_FALSE(targets.empty());
  std::printf("instruction sets: ");
  for (const auto& t : targets) std::printf("%s ", t.c_str());
  std::printf("\n");
  for (const Case& c : cases())
    for (FbarMode fbar : {FbarMode::Off, FbarMode::VolumeAverage, FbarMode::Centroid,
                          FbarMode::Nodal, FbarMode::SubTet})
      for (bool curved : {false, true}) {
        const auto ref = run_path(c.material, fbar, curved, ElementKernelChoice::scalar);
        if (c.name != "elastic") {
          // every point yields at the first step; later some unload while others yield
          EXPECT_EQ(ref[0].plastic_points, 4 * 36) << c.name;
          int mixed = 0;
          for (std::size_t s = 1; s < ref.size(); ++s)
            mixed += ref[s].plastic_points > 0 && ref[s].plastic_points < 4 * 36;
          EXPECT_GT(mixed, 0) << c.name;
          if (fbar == FbarMode::Off && !curved) {
            std::printf("%s: plastic points per step", c.name.c_str());
            for (const auto& r : ref) std::printf(" %d", r.plastic_points);
            std::printf(" (of 144)\n");
          }
        }
        std::vector<PassResult> best;
        for (const std::string& t : targets) {
          ASSERT_TRUE(use_element_update_target(t));
          const auto simd = run_path(c.material, fbar, curved, ElementKernelChoice::simd);
          const std::string what = c.name + " " + to_string(fbar) + (curved ? " curved " : " ") + t;
          expect_agree(simd, ref, what, c.tolerance);
          if (best.empty())
            best = simd;
          else
            expect_agree(simd, best, what + " vs " + targets.front(), c.tolerance);
        }
        use_element_update_target("");
      }
}

TEST(ElementUpdate, TargetsCanBeChosenAndRestored) {
  const std::vector<std::string> targets = element_update_targets();
  EXPECT_EQ(element_update_target(), targets.front());
  EXPECT_FALSE(use_element_update_target("no-such-set"));
  ASSERT_TRUE(use_element_update_target(targets.back()));
  EXPECT_EQ(element_update_target(), targets.back());
  EXPECT_TRUE(use_element_update_target(""));
  EXPECT_EQ(element_update_target(), targets.front());
}

}  // namespace
}  // namespace femdem
