// SPDX-License-Identifier: GPL-3.0-or-later
// The V-Cross drop, the full scene (scenes/armour_unit_drop.toml; docs/VALIDATION.md section 6;
// thesis section 6.3.1): a 30 t concrete cruciform unit dropped flat at 2 m/s on a rigid base,
// elastic and Mohr-Coulomb (c 15 MPa, phi 30 deg), to 12 ms.
//
// The thesis' numbers: peak corner tension about 12 MPa elastic, about 3.5 MPa Mohr-Coulomb, and
// 5 MPa with only the impact leg plastic. Its mesh, its anvil's material and the unit's exact
// proportions are not published (ours are our reading, scenes/meshes/README.md); the base here
// is rigid, which hits harder than the thesis' 8 m anvil; and the peak sits at the re-entrant
// right-angle corner where an arm meets the core, where the elastic stress is singular (like
// r^-0.46), so the elastic peak grows as the mesh is refined (docs/VALIDATION.md section 6).
// The magnitudes therefore cannot be asserted against 12 and 3.5 MPa. What is asserted, and why:
//  - the elastic peak is at least the thesis' 12 MPa (a rigid base is the stiffest base);
//  - plasticity lowers it at least as much as in the thesis' leg-only case (5 / 12 = 0.42; the
//    fully plastic thesis run gives 0.29): Mohr-Coulomb / elastic <= 0.5;
//  - the Mohr-Coulomb peak is below the apex of the surface, c cot(phi) = 26.0 MPa (no
//    tension cut-off: near the corner the stress is not uniaxial, so the uniaxial strength
//    2 c cos(phi) / (1 + sin(phi)) = 17.3 MPa is no bound);
//  - the energy balance within 2e-3 (1e-3 measured: the penalty base takes the full-speed hit),
//    and the unit has bounced (it moves up at the end).
// The measured numbers are printed for docs/VALIDATION.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "support/scene_run.hpp"

namespace {

nlohmann::json run(const std::string& material) {
  const auto r =
      femdem::test::run_shipped_scene("armour_unit_drop.toml", "long/armour_unit_drop_" + material,
                                      "--threads 2 --set bodies.unit.material=" + material);
  EXPECT_EQ(r.command.code, 0) << r.command.output;
  return r.summary;
}

}  // namespace

TEST(ArmourUnitDrop, VCrossPeakTensionElasticAndMohrCoulomb) {
  const auto el = run("concrete_elastic");
  const auto mc = run("concrete_mc");
  const double peak_el = el["bodies"]["unit"]["max_principal_stress"].get<double>();
  const double peak_mc = mc["bodies"]["unit"]["max_principal_stress"].get<double>();
  const double c = 15e6, phi = 30.0 * M_PI / 180.0;
  const double apex = c / std::tan(phi);
  std::printf("elastic: peak %.3f MPa at %.3f ms (thesis 12), balance %.2e\n", peak_el / 1e6,
              1e3 * el["bodies"]["unit"]["max_principal_stress_time"].get<double>(),
              el["energy"]["balance_error"].get<double>());
  std::printf(
      "Mohr-Coulomb: peak %.3f MPa at %.3f ms (thesis 3.5), max eps_p %.3e, plastic work "
      "%.1f J, balance %.2e\n",
      peak_mc / 1e6, 1e3 * mc["bodies"]["unit"]["max_principal_stress_time"].get<double>(),
      mc["bodies"]["unit"]["max_equivalent_plastic_strain"].get<double>(),
      mc["energy"]["plastic_dissipation"].get<double>(),
      mc["energy"]["balance_error"].get<double>());
  EXPECT_GE(peak_el, 12e6);
  EXPECT_LE(peak_mc / peak_el, 0.5);
  EXPECT_LT(peak_mc, apex * (1 + 1e-6));
  for (const auto* s : {&el, &mc}) {
    EXPECT_LT(std::fabs((*s)["energy"]["balance_error"].get<double>()), 2e-3);
    EXPECT_GT((*s)["bodies"]["unit"]["vcom"][2].get<double>(), 0.0);
  }
}
