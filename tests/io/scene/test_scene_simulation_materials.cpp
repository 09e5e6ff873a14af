// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader, [simulation] and [[materials]]: every bad value names file, line and key, with
// the checks of each material model (Mohr-Coulomb, Drucker-Prager, piece-wise Drucker-Prager,
// von Mises).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/scene/scene_reader.hpp"
#include "support/scene_cases.hpp"

namespace {

using femdem::test::BadCase;
using femdem::test::BadScene;
using femdem::test::expect_bad_scene;

// clang-format off
const std::vector<BadCase> kBadCases = {
  {"unknown_simulation_key", 3, "end_tme = 1e-3", "", "simulation.end_tme", 3, "did you mean 'end_time'?"},
  {"missing_end_time", 3, "time_step_safety = 0.5", "", "simulation.end_time", 2, "required"},
  {"end_time_wrong_type", 3, R"(end_time = "soon")", "", "simulation.end_time", 3, "expected a number"},
  {"end_time_negative", 3, "end_time = -1.0", "", "simulation.end_time", 3, "must be positive"},
  {"safety_zero", 3, "end_time = 1e-3\ntime_step_safety = 0", "", "simulation.time_step_safety", 4, "must be positive"},
  {"safety_above_one", 3, "end_time = 1e-3\ntime_step_safety = 1.5", "", "simulation.time_step_safety", 4, "(0, 1]"},
  {"contact_safety_zero", 3, "end_time = 1e-3\ncontact_time_step_safety = 0", "", "simulation.contact_time_step_safety", 4, "must be positive"},
  {"contact_safety_above_one", 3, "end_time = 1e-3\ncontact_time_step_safety = 1.2", "", "simulation.contact_time_step_safety", 4, "(0, 1]"},
  {"output_interval_zero", 3, "end_time = 1e-3\noutput_interval = 0.0", "", "simulation.output_interval", 4, "must be positive"},
  {"history_interval_negative", 3, "end_time = 1e-3\nhistory_interval = -1e-6", "", "simulation.history_interval", 4, "must be positive"},
  {"mass_scaling_negative", 3, "end_time = 1e-3\nmass_scaling_time_step = -1e-9", "", "simulation.mass_scaling_time_step", 4, "0 (off) or a positive"},
  {"mass_scaling_with_fixed_step", 3, "end_time = 1e-3\ntime_step = 1e-6\nmass_scaling_time_step = 1e-9", "", "simulation.mass_scaling_time_step", 5, "automatic step only"},
  {"stable_step_unknown", 3, "end_time = 1e-3\nstable_step = \"global\"", "", "simulation.stable_step", 4, "\"assembled\""},
  {"stable_step_interval_zero", 3, "end_time = 1e-3\nstable_step_interval = 0", "", "simulation.stable_step_interval", 4, "[1, 1000000]"},
  {"stable_step_interval_not_integer", 3, "end_time = 1e-3\nstable_step_interval = 2.5", "", "simulation.stable_step_interval", 4, "expected an integer"},
  {"threads_not_integer", 3, "end_time = 1e-3\nthreads = 1.5", "", "simulation.threads", 4, "expected an integer"},
  {"gravity_two_components", 3, "end_time = 1e-3\ngravity = [0, -9.81]", "", "simulation.gravity", 4, "3 numbers"},
  {"density_zero", 7, "density = 0", "", "materials.steel.density", 7, "must be positive"},
  {"youngs_modulus_negative", 8, "youngs_modulus = -1e9", "", "materials.steel.youngs_modulus", 8, "must be positive"},
  {"poisson_half", 9, "poisson_ratio = 0.5", "", "materials.steel.poisson_ratio", 9, "(-1, 0.5)"},
  {"poisson_below_minus_one", 9, "poisson_ratio = -1.0", "", "materials.steel.poisson_ratio", 9, "(-1, 0.5)"},
  {"poisson_string", 9, R"(poisson_ratio = "0.3")", "", "materials.steel.poisson_ratio", 9, "expected a number"},
  {"missing_density", 7, "# no density", "", "materials.steel.density", 4, "required"},
  {"missing_material_name", 5, "# no name", "", "materials[0].name", 4, "required"},
  {"missing_model", 6, "# no model", "", "materials.steel.model", 4, "required"},
  {"mohr_coulomb_without_cohesion", 6, "model = \"mohr_coulomb\"\nfriction_angle = 30", "", "materials.steel.cohesion", 4, "required"},
  {"mohr_coulomb_angle_90", 6, "model = \"mohr_coulomb\"\ncohesion = 1e6\nfriction_angle = 90", "", "materials.steel.friction_angle", 8, "[0, 90)"},
  {"mohr_coulomb_dilatancy_above_friction", 6, "model = \"mohr_coulomb\"\ncohesion = 1e6\nfriction_angle = 20\ndilatancy_angle = 25", "", "materials.steel.dilatancy_angle", 9, "[0, friction_angle = 20]"},
  {"mohr_coulomb_no_strength", 6, "model = \"mohr_coulomb\"\ncohesion = 0\nfriction_angle = 0", "", "materials.steel.cohesion", 7, "no strength"},
  {"mohr_coulomb_residual_without_softening", 6, "model = \"mohr_coulomb\"\ncohesion = 1e6\nfriction_angle = 20\nresidual_cohesion = 1e5", "", "materials.steel.residual_cohesion", 9, "needs cohesion_hardening_modulus < 0"},
  {"mohr_coulomb_snap_back", 6, "model = \"mohr_coulomb\"\ncohesion = 1e6\nfriction_angle = 20\ncohesion_hardening_modulus = -1e15", "", "materials.steel.cohesion_hardening_modulus", 9, "snap-back"},
  {"mohr_coulomb_cone_key", 6, "model = \"mohr_coulomb\"\ncohesion = 1e6\nfriction_angle = 20\ncone = \"outer\"", "", "materials.steel.cone", 9, "unknown key"},
  {"drucker_prager_bad_cone", 6, "model = \"drucker_prager\"\ncohesion = 1e6\nfriction_angle = 20\ncone = \"outter\"", "", "materials.steel.cone", 9, "did you mean 'outer'?"},
  {"piecewise_without_pieces", 6, "model = \"piecewise_drucker_prager\"", "", "materials.steel.pieces", 4, "required"},
  {"piecewise_not_pairs", 6, "model = \"piecewise_drucker_prager\"\npieces = [[0.42, 8e6], [0.3]]", "", "materials.steel.pieces", 7, "[A, B]"},
  {"piecewise_not_convex", 6, "model = \"piecewise_drucker_prager\"\npieces = [[0.3, 8e6], [0.42, 14e6]]", "", "materials.steel.pieces", 7, "decrease strictly"},
  {"piecewise_two_dilatancies", 6, "model = \"piecewise_drucker_prager\"\npieces = [[0.42, 8e6]]\ndilatancy = 0.1\ndilatancy_angle = 5", "", "materials.steel.dilatancy_angle", 9, "not both"},
  {"piecewise_negative_dilatancy", 6, "model = \"piecewise_drucker_prager\"\npieces = [[0.42, 8e6]]\ndilatancy = -0.1", "", "materials.steel.dilatancy", 8, "dilatancy must lie in [0, A of the last piece"},
  {"von_mises_without_yield_stress", 6, R"(model = "von_mises")", "", "materials.steel.yield_stress", 4, "required"},
  {"von_mises_two_hardening_laws", 6, "model = \"von_mises\"\nyield_stress = 1e8\nhardening_modulus = 1e9\nhardening_curve = [[0.0, 1e8], [0.1, 2e8]]", "", "materials.steel", 4, "one hardening law"},
  {"von_mises_curve_not_pairs", 6, "model = \"von_mises\"\nhardening_curve = [[0.0, 1e8], [0.1]]", "", "materials.steel.hardening_curve", 7, "two numbers"},
  {"von_mises_negative_yield", 6, "model = \"von_mises\"\nyield_stress = -1e8", "", "materials.steel.yield_stress", 7, "positive"},
  {"unknown_model", 6, R"(model = "elastik")", "", "materials.steel.model", 6, "did you mean 'elastic'?"},
  {"material_unknown_key", 7, "densty = 7800", "", "materials.steel.densty", 7, "did you mean 'density'?"},
  {"material_key_of_other_model", 9, "poisson_ratio = 0.3\nyield_stress = 400e6", "", "materials.steel.yield_stress", 10, "unknown key"},
  {"duplicate_material", 0, "", "[[materials]]\nname = \"steel\"\nmodel = \"elastic\"\ndensity = 1.0\nyoungs_modulus = 1.0\npoisson_ratio = 0.0\n", "materials.steel.name", 21, "duplicate name"},
  {"materials_as_plain_table", 4, "[materials.x]", "", "materials", 4, "array of tables"},
};
// clang-format on

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  expect_bad_scene(GetParam());
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
