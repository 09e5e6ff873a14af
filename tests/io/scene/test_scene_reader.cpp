// SPDX-License-Identifier: GPL-3.0-or-later
// Scene reader: strict validation (every bad input names file, line and key), defaults,
// --set overrides, mesh placement and relative mesh paths.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/mesh/mesh_generators.hpp"
#include "io/scene/scene_reader.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::InputError;
using femdem::load_scene;
using femdem::Vec3;

fs::path tmp_dir() {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "scene_reader";
  fs::create_directories(d);
  return d;
}

std::string write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path.string();
}

// A valid scene; the bad-input cases replace one of its lines (numbered from 1 in the comments)
// or append lines after its last one.
const std::vector<std::string> kBase = {
    R"(title = "base")",                                                                // 1
    R"([simulation])",                                                                  // 2
    R"(end_time = 1e-3)",                                                               // 3
    R"([[materials]])",                                                                 // 4
    R"(name = "steel")",                                                                // 5
    R"(model = "elastic")",                                                             // 6
    R"(density = 7800)",                                                                // 7
    R"(youngs_modulus = 200e9)",                                                        // 8
    R"(poisson_ratio = 0.3)",                                                           // 9
    R"([[bodies]])",                                                                    // 10
    R"(name = "ball")",                                                                 // 11
    R"(material = "steel")",                                                            // 12
    R"(mesh = { generator = "box", size = [0.02, 0.02, 0.02], element_size = 0.01 })",  // 13
    R"([[walls]])",                                                                     // 14
    R"(name = "floor")",                                                                // 15
    R"(normal = [0, 0, 1])",                                                            // 16
    R"([[constraints]])",                                                               // 17
    R"(body = "ball")",                                                                 // 18
    R"(fix = ["z"])",                                                                   // 19
};

// The base scene with line `line` (1-based; 0: none) replaced by `replacement` (which may hold
// several lines) and `extra` appended.
std::string scene_text(int line, const std::string& replacement, const std::string& extra = {}) {
  std::string s;
  for (std::size_t i = 0; i < kBase.size(); ++i)
    s += (static_cast<int>(i) + 1 == line ? replacement : kBase[i]) + "\n";
  return s + extra;
}

struct BadCase {
  const char* name;  // also the scene's file name
  int line;          // line of kBase to replace (0: none)
  std::string replacement;
  std::string extra;
  std::string key;       // expected InputError::key
  int expected_line;     // expected InputError::line
  std::string contains;  // expected part of the message
};

// clang-format off
const std::vector<BadCase> kBadCases = {
  {"unknown_top_level_key", 1, R"(titel = "x")", "", "titel", 1, "did you mean 'title'?"},
  {"unknown_simulation_key", 3, "end_tme = 1e-3", "", "simulation.end_tme", 3, "did you mean 'end_time'?"},
  {"missing_end_time", 3, "time_step_safety = 0.5", "", "simulation.end_time", 2, "required"},
  {"end_time_wrong_type", 3, R"(end_time = "soon")", "", "simulation.end_time", 3, "expected a number"},
  {"end_time_negative", 3, "end_time = -1.0", "", "simulation.end_time", 3, "must be positive"},
  {"safety_zero", 3, "end_time = 1e-3\ntime_step_safety = 0", "", "simulation.time_step_safety", 4, "must be positive"},
  {"safety_above_one", 3, "end_time = 1e-3\ntime_step_safety = 1.5", "", "simulation.time_step_safety", 4, "(0, 1]"},
  {"output_interval_zero", 3, "end_time = 1e-3\noutput_interval = 0.0", "", "simulation.output_interval", 4, "must be positive"},
  {"history_interval_negative", 3, "end_time = 1e-3\nhistory_interval = -1e-6", "", "simulation.history_interval", 4, "must be positive"},
  {"mass_scaling_negative", 3, "end_time = 1e-3\nmass_scaling_time_step = -1e-9", "", "simulation.mass_scaling_time_step", 4, "0 (off) or a positive"},
  {"mass_scaling_with_fixed_step", 3, "end_time = 1e-3\ntime_step = 1e-6\nmass_scaling_time_step = 1e-9", "", "simulation.mass_scaling_time_step", 5, "automatic step only"},
  {"contact_pair_unknown_body", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"bal\"]\nfriction = 0.2", "contact.pairs[0].bodies", 21, "did you mean 'ball'?"},
  {"impact_damping_one", 0, "", "[contact]\nimpact_damping = 1.0", "contact.impact_damping", 21, "[0, 1)"},
  {"contact_pair_same_body", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"ball\"]\nfriction = 0.2", "contact.pairs[0].bodies", 21, "same body twice"},
  {"contact_pair_names_a_wall", 0, "", "[[contact.pairs]]\nbodies = [\"ball\", \"floor\"]\nfriction = -0.2", "contact.pairs[0].bodies", 21, "unknown body 'floor'"},
  {"threads_not_integer", 3, "end_time = 1e-3\nthreads = 1.5", "", "simulation.threads", 4, "expected an integer"},
  {"gravity_two_components", 3, "end_time = 1e-3\ngravity = [0, -9.81]", "", "simulation.gravity", 4, "3 numbers"},
  {"misplaced_key", 2, "[contact]", "", "simulation", 1, "[simulation] is missing"},
  {"unknown_section", 2, "[simulaton]", "", "simulaton", 2, "did you mean 'simulation'?"},
  {"toml_syntax_error", 3, "end_time = ", "", "", 3, "TOML syntax error"},
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
  {"bad_fbar", 13, "mesh = { generator = \"box\", size = [0.02, 0.02, 0.02], element_size = 0.01 }\nfbar = \"sometimes\"", "", "bodies.ball.fbar", 14, "volume_average"},
  {"unknown_model", 6, R"(model = "elastik")", "", "materials.steel.model", 6, "did you mean 'elastic'?"},
  {"material_unknown_key", 7, "densty = 7800", "", "materials.steel.densty", 7, "did you mean 'density'?"},
  {"material_key_of_other_model", 9, "poisson_ratio = 0.3\nyield_stress = 400e6", "", "materials.steel.yield_stress", 10, "unknown key"},
  {"duplicate_material", 0, "", "[[materials]]\nname = \"steel\"\nmodel = \"elastic\"\ndensity = 1.0\nyoungs_modulus = 1.0\npoisson_ratio = 0.0\n", "materials.steel.name", 21, "duplicate name"},
  {"unknown_material_in_body", 12, R"(material = "stel")", "", "bodies.ball.material", 12, "did you mean 'steel'?"},
  {"missing_body_material", 12, "# no material", "", "bodies.ball.material", 10, "required"},
  {"missing_mesh", 13, "fixed = false", "", "bodies.ball.mesh", 10, "required"},
  {"mesh_not_a_table", 13, R"(mesh = "ball.msh")", "", "bodies.ball.mesh", 13, "expected a table"},
  {"body_name_with_dot", 11, R"(name = "my.ball")", "", "bodies.my.ball.name", 11, "names may contain only"},
  {"body_unknown_key", 13, kBase[12] + "\nvelocty = [0, 0, 1]", "", "bodies.ball.velocty", 14, "did you mean 'velocity'?"},
  {"body_velocity_two_components", 13, kBase[12] + "\nvelocity = [0, 1]", "", "bodies.ball.velocity", 14, "3 numbers"},
  {"body_velocity_string_element", 13, kBase[12] + "\nvelocity = [0, \"a\", 1]", "", "bodies.ball.velocity", 14, "element 2"},
  {"body_fixed_not_bool", 13, kBase[12] + "\nfixed = \"yes\"", "", "bodies.ball.fixed", 14, "true or false"},
  {"sphere_negative_radius", 13, R"(mesh = { generator = "sphere", radius = -1.0, element_size = 0.01 })", "", "bodies.ball.mesh.radius", 13, "must be positive"},
  {"cylinder_missing_length", 13, R"(mesh = { generator = "cylinder", radius = 0.01, element_size = 0.01 })", "", "bodies.ball.mesh.length", 13, "required"},
  {"box_size_two_components", 13, R"(mesh = { generator = "box", size = [1, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "3 numbers"},
  {"box_size_zero", 13, R"(mesh = { generator = "box", size = [1, 0, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "positive"},
  {"element_size_zero", 13, R"(mesh = { generator = "box", size = [1, 1, 1], element_size = 0 })", "", "bodies.ball.mesh.element_size", 13, "must be positive"},
  {"element_size_too_small", 13, R"(mesh = { generator = "box", size = [1, 1, 1], element_size = 1e-5 })", "", "bodies.ball.mesh.element_size", 13, "elements"},
  {"unknown_generator", 13, R"(mesh = { generator = "spere", radius = 1, element_size = 0.5 })", "", "bodies.ball.mesh.generator", 13, "did you mean 'sphere'?"},
  {"generator_wrong_key", 13, R"(mesh = { generator = "sphere", size = [1, 1, 1], element_size = 0.5 })", "", "bodies.ball.mesh.size", 13, "unknown key"},
  {"generator_and_file", 13, R"(mesh = { generator = "sphere", file = "a.msh", radius = 1.0, element_size = 0.5 })", "", "bodies.ball.mesh", 13, "not both"},
  {"mesh_without_source", 13, R"(mesh = { element_size = 0.5 })", "", "bodies.ball.mesh", 13, "needs 'generator'"},
  {"missing_mesh_file", 13, R"(mesh = { file = "no_such_mesh.msh" })", "", "bodies.ball.mesh.file", 13, "does not exist"},
  {"unsupported_mesh_type", 13, R"(mesh = { file = "mesh.xyz" })", "", "bodies.ball.mesh.file", 13, "unsupported mesh file type"},
  {"msh_with_element_size", 13, R"(mesh = { file = "mesh.msh", element_size = 0.1 })", "", "bodies.ball.mesh.element_size", 13, "unknown key"},
  {"duplicate_body_and_wall_name", 15, R"(name = "ball")", "", "walls.ball.name", 15, "duplicate name"},
  {"zero_wall_normal", 16, "normal = [0, 0, 0]", "", "walls.floor.normal", 16, "zero vector"},
  {"negative_wall_friction", 16, "normal = [0, 0, 1]\nfriction = -0.1", "", "walls.floor.friction", 17, "must not be negative"},
  {"zero_wall_penalty", 16, "normal = [0, 0, 1]\npenalty_factor = 0", "", "walls.floor.penalty_factor", 17, "must be positive"},
  {"wall_history_and_velocity", 16, "normal = [0, 0, 1]\nvelocity = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0]]", "", "walls.floor.velocity_history", 18, "not both"},
  {"wall_history_time_not_increasing", 16, "normal = [0, 0, 1]\nvelocity_history = [\n  [0, 0, 0, 0],\n  [1e-3, 0, 0, 1],\n  [1e-3, 0, 0, 2],\n]", "", "walls.floor.velocity_history", 20, "increase strictly: row 3 has t = 0.001 after t = 0.001"},
  {"wall_history_time_decreasing", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], [2e-3, 0, 0, 1], [1e-3, 0, 0, 2]]", "", "walls.floor.velocity_history", 17, "increase strictly"},
  {"wall_history_not_from_zero", 16, "normal = [0, 0, 1]\nvelocity_history = [[1e-3, 0, 0, 0], [2e-3, 0, 0, 1]]", "", "walls.floor.velocity_history", 17, "first row must be at t = 0"},
  {"wall_history_short_row", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], [1e-3, 0, 1]]", "", "walls.floor.velocity_history", 17, "row 2 must be [t, vx, vy, vz] (4 numbers), got 3"},
  {"wall_history_long_row", 16, "normal = [0, 0, 1]\nvelocity_history = [\n  [0, 0, 0, 0],\n  [1e-3, 0, 0, 1, 5],\n]", "", "walls.floor.velocity_history", 19, "got 5"},
  {"wall_history_row_not_array", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, 0, 0], 1e-3]", "", "walls.floor.velocity_history", 17, "row 2 must be"},
  {"wall_history_string_element", 16, "normal = [0, 0, 1]\nvelocity_history = [[0, 0, \"a\", 0]]", "", "walls.floor.velocity_history", 17, "element 3 is a string"},
  {"wall_history_empty", 16, "normal = [0, 0, 1]\nvelocity_history = []", "", "walls.floor.velocity_history", 17, "non-empty"},
  {"wall_history_not_array", 16, "normal = [0, 0, 1]\nvelocity_history = 1.0", "", "walls.floor.velocity_history", 17, "non-empty array"},
  {"wall_history_misspelt", 16, "normal = [0, 0, 1]\nvelocity_histroy = [[0, 0, 0, 0]]", "", "walls.floor.velocity_histroy", 17, "did you mean 'velocity_history'?"},
  {"unknown_body_in_constraint", 18, R"(body = "bal")", "", "constraints[0].body", 18, "did you mean 'ball'?"},
  {"unknown_fix_component", 19, R"(fix = ["x", "w"])", "", "constraints[0].fix", 19, "unknown component 'w'"},
  {"fix_not_array", 19, R"(fix = "x")", "", "constraints[0].fix", 19, "expected an array"},
  {"fix_and_velocity_empty", 19, "fix = []", "", "constraints[0]", 19, "does nothing"},
  {"no_fix_no_velocity", 19, "# nothing", "", "constraints[0]", 17, "does nothing"},
  {"fix_and_velocity_both", 19, "fix = [\"z\"]\nvelocity = [0, 0, 1]", "", "constraints[0].velocity", 20, "not both"},
  {"region_bad_string", 19, "fix = [\"z\"]\nregion = \"everything\"", "", "constraints[0].region", 20, "unknown region"},
  {"region_box_and_plane", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 0], plane_normal = [0, 0, 1] }", "", "constraints[0].region", 20, "mixes"},
  {"region_box_min_above_max", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 1], box_max = [1, 1, 0] }", "", "constraints[0].region.box_max", 20, "below box_min in z"},
  {"region_box_missing_max", 19, "fix = [\"z\"]\nregion = { box_min = [0, 0, 0] }", "", "constraints[0].region.box_max", 20, "required"},
  {"region_zero_plane_normal", 19, "fix = [\"z\"]\nregion = { plane_point = [0, 0, 0], plane_normal = [0, 0, 0] }", "", "constraints[0].region.plane_normal", 20, "zero vector"},
  {"region_unknown_key", 19, "fix = [\"z\"]\nregion = { plane_point = [0, 0, 0], plane_normal = [0, 0, 1], tolerence = 1e-9 }", "", "constraints[0].region.tolerence", 20, "did you mean 'tolerance'?"},
  {"contact_negative_penalty", 0, "", "[contact]\npenalty_factor = -1\n", "contact.penalty_factor", 21, "must be positive"},
  {"contact_unknown_key", 0, "", "[contact]\nfricton = 0.2\n", "contact.fricton", 21, "did you mean 'friction'?"},
  {"materials_as_plain_table", 4, "[materials.x]", "", "materials", 4, "array of tables"},
};
// clang-format on

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) {
  const BadCase& c = GetParam();
  const std::string path = write_file(tmp_dir() / "bad" / (std::string(c.name) + ".toml"),
                                      scene_text(c.line, c.replacement, c.extra));
  try {
    load_scene(path);
    FAIL() << "no InputError for case " << c.name;
  } catch (const InputError& e) {
    SCOPED_TRACE(e.describe());
    EXPECT_EQ(e.key, c.key);
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, c.expected_line);
    if (e.line > 0) {
      EXPECT_GT(e.column, 0);
    }
    EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
    // describe() reads "file:line:col: key: message"
    EXPECT_EQ(e.describe().rfind(path + ":" + std::to_string(c.expected_line) + ":", 0), 0u);
  } catch (const std::exception& e) {
    FAIL() << "wrong exception type for case " << c.name << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return std::string(info.param.name);
                         });

TEST(SceneReader, MissingSimulationTableAndNoBodies) {
  std::string no_sim;
  for (std::size_t i = 3; i < kBase.size(); ++i) no_sim += kBase[i] + "\n";
  try {
    load_scene(write_file(tmp_dir() / "no_simulation.toml", no_sim));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "simulation");
    EXPECT_NE(std::string(e.what()).find("[simulation] is missing"), std::string::npos);
  }
  std::string no_bodies;
  for (std::size_t i = 0; i < 9; ++i) no_bodies += kBase[i] + "\n";
  try {
    load_scene(write_file(tmp_dir() / "no_bodies.toml", no_bodies));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies");
    EXPECT_NE(std::string(e.what()).find("no bodies"), std::string::npos);
  }
}

TEST(SceneReader, ColumnPointsAtTheValue) {
  const std::string path =
      write_file(tmp_dir() / "column.toml", scene_text(7, "density =   -5", ""));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line, 7);
    EXPECT_EQ(e.column, 13);
  }
}

TEST(SceneReader, MissingSceneFile) {
  const std::string path = (tmp_dir() / "does_not_exist.toml").string();
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, 0);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

// CAD meshing itself is tested in test_cad_mesh.cpp; here only that its errors carry the
// scene's file, line and key.
TEST(SceneReader, CadMeshErrorsNameTheScenesKey) {
  write_file(tmp_dir() / "cad" / "part.stl", "solid part\nendsolid part\n");
  const std::string path =
      write_file(tmp_dir() / "cad" / "scene.toml",
                 scene_text(13, R"(mesh = { file = "part.stl", element_size = 0.01 })"));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "bodies.ball.mesh.file");
    EXPECT_EQ(e.line, 13);
    EXPECT_NE(std::string(e.what()).find("cannot mesh the surface"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("part.stl"), std::string::npos) << e.what();
  }
}

// Two TET4 elements sharing a face (gmsh 2.2 ASCII); the second one listed with the given
// corner order.
std::string two_tet4_msh(const std::string& second) {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
         "5 1 1 1\n$EndNodes\n$Elements\n2\n1 4 2 0 1 1 2 3 4\n2 4 2 0 1 " +
         second + "\n$EndElements\n";
}

TEST(SceneReader, InvertedMeshElementIsReportedWithTheScenesKey) {
  write_file(tmp_dir() / "inverted" / "bad.msh", two_tet4_msh("3 2 4 5"));
  const std::string path = write_file(tmp_dir() / "inverted" / "scene.toml",
                                      scene_text(13, R"(mesh = { file = "bad.msh" })"));
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    SCOPED_TRACE(e.describe());
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.key, "bodies.ball.mesh.file");
    EXPECT_EQ(e.line, 13);
  }
}

TEST(SceneReader, RelativeMeshPathIsResolvedAgainstTheScenesFolder) {
  write_file(tmp_dir() / "relative" / "meshes" / "two.msh", two_tet4_msh("2 3 4 5"));
  const std::string path = write_file(tmp_dir() / "relative" / "scene.toml",
                                      scene_text(13, R"(mesh = { file = "meshes/two.msh" })"));
  // From another working directory, so only the scene's folder can make the path work.
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());
  femdem::SceneFile s;
  EXPECT_NO_THROW(s = load_scene(path));
  fs::current_path(cwd);
  ASSERT_EQ(s.model.bodies.size(), 1u);
  EXPECT_EQ(s.model.bodies[0].mesh.elements.size(), 2u);
  EXPECT_EQ(s.model.bodies[0].mesh.nodes.size(), 5u + 9u);  // TET4 promoted: 9 edges
}

TEST(SceneReader, DefaultsAreFilledIn) {
  const std::string text = R"(
[simulation]
end_time = 2e-3
[[materials]]
name = "rubber"
model = "elastic"
density = 1100
youngs_modulus = 5e6
poisson_ratio = 0.45
[[bodies]]
name = "ball"
material = "rubber"
mesh = { generator = "sphere", radius = 0.05, element_size = 0.025 }
[[walls]]
[[constraints]]
body = "ball"
fix = ["x", "y"]
)";
  const std::string path = write_file(tmp_dir() / "defaults.toml", text);
  const femdem::SceneFile s = load_scene(path);
  EXPECT_EQ(s.path, path);
  EXPECT_EQ(s.stem, "defaults");
  const auto& m = s.model;
  EXPECT_EQ(m.title, "defaults");
  EXPECT_DOUBLE_EQ(m.simulation.end_time, 2e-3);
  EXPECT_DOUBLE_EQ(m.simulation.time_step_safety, 0.5);
  EXPECT_DOUBLE_EQ(m.simulation.time_step, 0.0);
  EXPECT_DOUBLE_EQ(m.simulation.output_interval, 2e-3 / 50);
  EXPECT_DOUBLE_EQ(m.simulation.history_interval, 2e-3 / 50 / 20);
  EXPECT_EQ(m.simulation.gravity, Vec3::Zero());
  EXPECT_EQ(m.simulation.threads, 0);
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_TRUE(m.materials[0].is<femdem::ElasticParams>());
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_EQ(m.bodies[0].material, 0);
  EXPECT_EQ(m.bodies[0].velocity, Vec3::Zero());
  EXPECT_EQ(m.bodies[0].angular_velocity, Vec3::Zero());
  EXPECT_FALSE(m.bodies[0].fixed);
  EXPECT_FALSE(m.bodies[0].mesh.elements.empty());
  ASSERT_EQ(m.walls.size(), 1u);
  EXPECT_EQ(m.walls[0].name, "wall1");
  EXPECT_EQ(m.walls[0].point, Vec3::Zero());
  EXPECT_EQ(m.walls[0].normal, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(m.walls[0].friction, 0.0);
  EXPECT_DOUBLE_EQ(m.walls[0].penalty_factor, 0.0);
  ASSERT_EQ(m.constraints.size(), 1u);
  EXPECT_EQ(m.constraints[0].body, 0);
  EXPECT_EQ(m.constraints[0].region.kind, femdem::RegionSpec::Kind::All);
  EXPECT_TRUE(m.constraints[0].fix[0] && m.constraints[0].fix[1] && !m.constraints[0].fix[2]);
  EXPECT_FALSE(m.constraints[0].velocity.has_value());
  EXPECT_DOUBLE_EQ(m.contact.penalty_factor, 100.0);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.0);

  // The resolved scene holds every default and is itself a valid scene giving the same model.
  for (const char* key : {"output_interval", "history_interval", "time_step_safety", "threads",
                          "penalty_factor", "angular_velocity", "wall1", "region"})
    EXPECT_NE(s.resolved_toml.find(key), std::string::npos) << key;
  const std::string again_path = write_file(tmp_dir() / "defaults_resolved.toml", s.resolved_toml);
  const femdem::SceneFile again = load_scene(again_path);
  EXPECT_EQ(again.resolved_toml, s.resolved_toml);
  EXPECT_EQ(again.model.bodies[0].mesh.nodes, m.bodies[0].mesh.nodes);
}

TEST(SceneReader, ExplicitValuesAreRead) {
  const std::string extra = R"(
[contact]
penalty_factor = 50
friction = 0.3
)";
  std::string text = scene_text(19,
                                "region = { box_min = [-1, -1, -1], box_max = [1, 1, 0.001] }\n"
                                "velocity = [0, 0, -0.5]",
                                extra);
  // a plane region on a second constraint, and wall values
  text +=
      "[[constraints]]\nbody = \"ball\"\nregion = { plane_point = [0, 0, 0], "
      "plane_normal = [0, 2, 0], tolerance = 1e-6 }\nfix = [\"y\"]\n";
  text +=
      "[[walls]]\nname = \"roof\"\npoint = [0, 0, 1]\nnormal = [0, 0, -3]\nfriction = 0.2\n"
      "penalty_factor = 10\nvelocity = [0, 0, -1]\n";
  const femdem::SceneFile s = load_scene(write_file(tmp_dir() / "explicit.toml", text));
  const auto& m = s.model;
  EXPECT_EQ(m.title, "base");
  ASSERT_EQ(m.constraints.size(), 2u);
  EXPECT_EQ(m.constraints[0].region.kind, femdem::RegionSpec::Kind::Box);
  EXPECT_EQ(m.constraints[0].region.box_max, Vec3(1, 1, 0.001));
  ASSERT_TRUE(m.constraints[0].velocity.has_value());
  EXPECT_EQ(*m.constraints[0].velocity, Vec3(0, 0, -0.5));
  EXPECT_EQ(m.constraints[1].region.kind, femdem::RegionSpec::Kind::Plane);
  EXPECT_EQ(m.constraints[1].region.plane_normal, Vec3(0, 1, 0));
  EXPECT_DOUBLE_EQ(m.constraints[1].region.tolerance, 1e-6);
  ASSERT_EQ(m.walls.size(), 2u);
  EXPECT_EQ(m.walls[1].normal, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(m.walls[1].penalty_factor, 10.0);
  EXPECT_DOUBLE_EQ(m.walls[1].friction, 0.2);
  EXPECT_EQ(m.walls[1].velocity, Vec3(0, 0, -1));
  EXPECT_DOUBLE_EQ(m.contact.penalty_factor, 50.0);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.3);
}

TEST(SceneReader, WallVelocityHistoryIsReadAndEchoed) {
  const std::string text = scene_text(16,
                                      "normal = [0, 0, 1]\n"
                                      "velocity_history = [[0, 0, 0, 0], [1e-3, 0, 0, 0.5],\n"
                                      "                    [2.5e-3, 1, 0, -0.25]]");
  const std::string path = write_file(tmp_dir() / "velocity_history.toml", text);
  const femdem::SceneFile s = load_scene(path);
  ASSERT_EQ(s.model.walls.size(), 1u);
  const auto& h = s.model.walls[0].velocity_history;
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0].time, 0.0);
  EXPECT_EQ(h[0].velocity, Vec3::Zero());
  EXPECT_EQ(h[1].time, 1e-3);
  EXPECT_EQ(h[1].velocity, Vec3(0, 0, 0.5));
  EXPECT_EQ(h[2].time, 2.5e-3);
  EXPECT_EQ(h[2].velocity, Vec3(1, 0, -0.25));
  // The resolved scene holds the history (and no constant velocity) and reads back the same.
  EXPECT_NE(s.resolved_toml.find("velocity_history = [[0"), std::string::npos) << s.resolved_toml;
  const std::size_t walls = s.resolved_toml.find("[[walls]]");
  ASSERT_NE(walls, std::string::npos);
  EXPECT_EQ(s.resolved_toml.find("velocity = ", walls), std::string::npos) << s.resolved_toml;
  const femdem::SceneFile again =
      load_scene(write_file(tmp_dir() / "velocity_history_resolved.toml", s.resolved_toml));
  EXPECT_EQ(again.resolved_toml, s.resolved_toml);
  ASSERT_EQ(again.model.walls[0].velocity_history.size(), 3u);
  EXPECT_EQ(again.model.walls[0].velocity_history[2].velocity, Vec3(1, 0, -0.25));
  // --set replaces it like any value (and one row is enough: a constant velocity)
  const femdem::SceneFile o = load_scene(path, {"walls.floor.velocity_history=[[0, 0, 0, -2]]"});
  ASSERT_EQ(o.model.walls[0].velocity_history.size(), 1u);
  EXPECT_EQ(o.model.walls[0].velocity_history[0].velocity, Vec3(0, 0, -2));
  try {
    load_scene(path, {"walls.floor.velocity=[0, 0, 1]"});
    FAIL() << "velocity and velocity_history together were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key, "walls.floor.velocity_history");
    EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what();
  }
}

TEST(SceneReader, OverridesAddressArraysOfTablesByName) {
  const std::string path = write_file(tmp_dir() / "overrides.toml", scene_text(0, ""));
  const femdem::SceneFile s =
      load_scene(path, {"bodies.ball.velocity=[0,0,-5.4]", "materials.steel.density=7000",
                        "simulation.end_time=2e-3", "simulation.threads=2", "contact.friction=0.25",
                        "walls.floor.normal = [0, 1, 0]", "title=Hello world",
                        "bodies.ball.angular_velocity=[0, 0, 10]"});
  const auto& m = s.model;
  EXPECT_EQ(m.bodies[0].velocity, Vec3(0, 0, -5.4));
  EXPECT_EQ(m.bodies[0].angular_velocity, Vec3(0, 0, 10));
  EXPECT_DOUBLE_EQ(m.materials[0].density, 7000.0);
  EXPECT_DOUBLE_EQ(m.simulation.end_time, 2e-3);
  EXPECT_DOUBLE_EQ(m.simulation.output_interval, 2e-3 / 50);  // default follows the override
  EXPECT_EQ(m.simulation.threads, 2);
  EXPECT_DOUBLE_EQ(m.contact.friction, 0.25);
  EXPECT_EQ(m.walls[0].normal, Vec3(0, 1, 0));
  EXPECT_EQ(m.title, "Hello world");  // not TOML: taken as a bare string
  EXPECT_NE(s.resolved_toml.find("-5.4"), std::string::npos);
}

TEST(SceneReader, BadOverridesNameTheOverride) {
  const std::string path = write_file(tmp_dir() / "bad_overrides.toml", scene_text(0, ""));
  struct Case {
    std::string set, key, contains;
  };
  const std::vector<Case> cases = {
      {"bodies.bal.velocity=[0,0,1]", "bodies.bal.velocity", "did you mean 'ball'?"},
      {"simulation.end_time=-1", "simulation.end_time", "must be positive"},
      {"simulation.end_tme=1", "simulation.end_tme", "did you mean 'end_time'?"},
      {"bodies.ball.velocity=[0,0]", "bodies.ball.velocity", "3 numbers"},
      {"materials.steel.yield_stress=350e6", "materials.steel.yield_stress", "unknown key"},
      {"simulation.end_time.x=1", "simulation.end_time.x", "not a table"},
      {"simulation", "simulation", "expected KEY=VALUE"},
      {"bodies.ball=1", "bodies.ball", "cannot replace a whole entry"},
      {"simulation..end_time=1", "simulation..end_time", "malformed key"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.set);
    try {
      load_scene(path, {c.set});
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.key, c.key);
      EXPECT_EQ(e.line, 0);
      EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--set " + c.set), std::string::npos) << e.what();
    }
  }
}

TEST(SceneReader, RotationThenPositionPlaceTheGeneratedMesh) {
  const Vec3 size(0.02, 0.04, 0.06), pos(1, 2, 3);
  const double h = 0.02;
  const femdem::Tet10Mesh ref = femdem::generate_box(size, h);
  struct Case {
    std::string rotation;
    // the expected image of a reference point before the translation
    Vec3 (*turn)(const Vec3&);
  };
  const std::vector<Case> cases = {
      {"[0, 0, 90]", [](const Vec3& p) { return Vec3(-p.y(), p.x(), p.z()); }},
      {"[90, 0, 0]", [](const Vec3& p) { return Vec3(p.x(), -p.z(), p.y()); }},
      {"[0, 90, 0]", [](const Vec3& p) { return Vec3(p.z(), p.y(), -p.x()); }},
      // about x first, then about z: (x, y, z) -> (x, -z, y) -> (z, x, y)
      {"[90, 0, 90]", [](const Vec3& p) { return Vec3(p.z(), p.x(), p.y()); }},
  };
  int i = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.rotation);
    const std::string mesh_line =
        R"(mesh = { generator = "box", size = [0.02, 0.04, 0.06], element_size = 0.02 })";
    const std::string path =
        write_file(tmp_dir() / ("rotation" + std::to_string(i++) + ".toml"),
                   scene_text(13, mesh_line + "\nposition = [1, 2, 3]\nrotation = " + c.rotation));
    const femdem::SceneFile s = load_scene(path);
    const auto& mesh = s.model.bodies[0].mesh;
    ASSERT_EQ(mesh.nodes.size(), ref.nodes.size());
    ASSERT_EQ(mesh.elements, ref.elements);
    double worst = 0.0;
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
      worst = std::max(worst, (mesh.nodes[n] - (c.turn(ref.nodes[n]) + pos)).norm());
    EXPECT_LT(worst, 1e-12);
  }
}

}  // namespace
