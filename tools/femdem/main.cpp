// SPDX-License-Identifier: GPL-3.0-or-later
// The femdem command-line program: `femdem run|check|sweep SCENE ...`, `femdem pack FILE ...`
// and `femdem mesh SURFACE --size H` (docs/SCENES.md): the options of each command, and the
// exit code of what went wrong (exit_codes.hpp). The commands themselves live beside it.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "femdem_version.hpp"
#include "tools/femdem/check_command.hpp"
#include "tools/femdem/exit_codes.hpp"
#include "tools/femdem/mesh_command.hpp"
#include "tools/femdem/pack_command.hpp"
#include "tools/femdem/run/plot_script.hpp"
#include "tools/femdem/run/run_scene.hpp"
#include "tools/femdem/sweep/sweep.hpp"

namespace {

using femdem::kExitBadInput;
using femdem::kExitFailure;
using femdem::kExitOk;
using femdem::kExitUnstable;

std::string version_string() {
  return std::string("femdem ") + FEMDEM_VERSION + " (git " + FEMDEM_GIT_REVISION + ")";
}

// This program's own path, for the sweep's child processes.
std::string self_exe(const char* argv0) {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec && !p.empty()) return p.string();
  return std::filesystem::absolute(argv0, ec).string();
}

std::string default_out_dir(const femdem::SceneFile& scene) {
  return (std::filesystem::path("out") / scene.stem).string() + "/";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"femdem: explicit FEM-DEM simulation of deformable bodies (ten-node tetrahedra)",
               "femdem"};
  app.set_version_flag("--version", version_string());
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 bad input, 3 the simulation became unstable, 1 other errors.\n"
      "Scene keys: docs/SCENES.md");

  std::string scene_path, out_dir;
  std::vector<std::string> overrides;
  int threads = -1;
  bool quiet = false;

  CLI::App* run = app.add_subcommand("run", "Run a scene and write its results");
  run->add_option("scene", scene_path, "Scene file (TOML)")->required();
  run->add_option("--out", out_dir, "Output folder (default: out/<scene file stem>/)");
  run->add_option("--set", overrides, "Override a scene value: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  run->add_option("--threads", threads, "Number of threads (0: all cores; default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet", quiet, "Print nothing but errors");
  bool run_no_plot = false;
  run->add_flag("--no-plot", run_no_plot,
                "Do not call tools/plot_compaction.py after a run with [compaction]");

  CLI::App* check = app.add_subcommand(
      "check", "Read the scene, build the model and print a summary; run and write nothing");
  check->add_option("scene", scene_path, "Scene file (TOML)")->required();
  check->add_option("--set", overrides, "Override a scene value: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  std::string material_name, strain_path;
  int substeps = 10;
  check->add_option("--material", material_name,
                    "With --strain-path: drive this material of the scene through a homogeneous "
                    "deformation history and print the stress path as CSV");
  check->add_option("--strain-path", strain_path,
                    "File of target deformation gradients, 9 numbers (row-major F) per line");
  check->add_option("--substeps", substeps, "Increments between two targets (default 10)")
      ->check(CLI::PositiveNumber);

  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Run a scene for every combination of --vary values, each run in its own sub-folder, "
      "and collect the results in DIR/sweep.csv (plus plots)");
  femdem::SweepOptions sweep_options;
  sweep->add_option("scene", sweep_options.scene_path, "Scene file (TOML)")->required();
  sweep
      ->add_option("--vary", sweep_options.vary,
                   "KEY=V1,V2,...: values of one scene key (repeatable; the runs are the "
                   "cartesian product). Commas inside [..] separate array elements, not values: "
                   "bodies.ball.velocity=[0,0,-5],[0,0,-10]. Ranges: START:STOP:STEP, "
                   "linspace(A,B,N), logspace(A,B,N)")
      ->required()
      ->allow_extra_args(false);
  sweep
      ->add_option("--set", sweep_options.overrides,
                   "Override a scene value in every run: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  sweep->add_option("--out", sweep_options.out_dir,
                    "Sweep folder (default: out/<scene file stem>_sweep/)");
  sweep
      ->add_option("--jobs", sweep_options.jobs,
                   "Runs at a time (default: cores / threads per job)")
      ->check(CLI::PositiveNumber);
  sweep
      ->add_option("--threads-per-job", sweep_options.threads_per_job,
                   "Threads of each run (default 1)")
      ->check(CLI::PositiveNumber);
  bool no_plot = false;
  sweep->add_flag("--no-plot", no_plot, "Do not call tools/plot_sweep.py at the end");
  sweep->add_flag("--quiet", sweep_options.quiet, "Print nothing but errors");

  CLI::App* pack_cmd = app.add_subcommand(
      "pack",
      "Generate a particle packing (lattice, or random and settled under gravity) and write it "
      "to a file for [[packings]] in scenes (docs/SCENES.md, docs/OUTPUTS.md)");
  femdem::PackingParams pp;
  std::string pack_out;
  bool pack_quiet = false;
  std::vector<double> pack_size;
  pack_cmd->add_option("out", pack_out, "Packing file to write (CSV)")->required();
  pack_cmd->add_option("--container", pp.container, "box (default) or cylinder");
  pack_cmd->add_option("--size", pack_size, "Box size lx ly lz (m); the box spans [0, l]")
      ->expected(3)
      ->delimiter(',');
  pack_cmd->add_option("--radius", pp.radius, "Cylinder radius (m); axis z through the origin");
  pack_cmd->add_option("--height", pp.height, "Cylinder height (m)");
  pack_cmd->add_option("--arrangement", pp.arrangement,
                       "random (default: dropped and settled under gravity), simple_cubic, "
                       "body_centred_cubic, face_centred_cubic");
  pack_cmd->add_option("--count", pp.count,
                       "Number of particles (random: required; lattice: default all that fit)");
  pack_cmd->add_option("--distribution", pp.distribution,
                       "monodisperse (default), uniform, lognormal");
  pack_cmd->add_option("--diameter", pp.diameter, "Monodisperse diameter (m)");
  pack_cmd->add_option("--diameter-min", pp.diameter_min,
                       "Uniform: smallest diameter; lognormal: clip (default mean exp(-3 sigma))");
  pack_cmd->add_option("--diameter-max", pp.diameter_max,
                       "Uniform: largest diameter; lognormal: clip (default mean exp(3 sigma))");
  pack_cmd->add_option("--diameter-mean", pp.diameter_mean, "Lognormal: mean diameter (m)");
  pack_cmd->add_option("--sigma", pp.sigma, "Lognormal: standard deviation of ln d");
  pack_cmd->add_option("--seed", pp.seed, "Random seed (default 1)");
  pack_cmd->add_option("--shape", pp.shape,
                       "Shape name stored per particle (default sphere; a CAD shape is settled "
                       "by its bounding sphere)");
  pack_cmd->add_option("--orientation", pp.orientation,
                       "identity or random (default: identity for spheres, random otherwise)");
  pack_cmd->add_option("--friction", pp.friction, "Friction while settling (default 0.5)");
  pack_cmd->add_flag("--quiet", pack_quiet, "Print nothing but errors");
  CLI::App* mesh = app.add_subcommand(
      "mesh",
      "Mesh a closed CAD surface (STL, OBJ, PLY, OFF, glTF, 3MF, ... anything assimp reads) "
      "into TET10 elements and write a gmsh .msh file");
  std::string mesh_input, mesh_output;
  femdem::CadMeshOptions mesh_options;
  bool no_perturb = false, no_exude = false;
  mesh->add_option("input", mesh_input, "Surface file")->required();
  mesh->add_option("--size", mesh_options.element_size,
                   "Target edge length of the tetrahedra, in m (after --scale)")
      ->required()
      ->check(CLI::PositiveNumber);
  mesh->add_option("--scale", mesh_options.scale,
                   "Factor from the file's units to m, e.g. 0.001 for mm (default 1)")
      ->check(CLI::PositiveNumber);
  mesh->add_option("-o,--output", mesh_output, "Output .msh file (default: INPUT with .msh)");
  mesh->add_option("--feature-angle", mesh_options.feature_angle,
                   "Edges whose faces' normals differ by more than this (degrees) are kept "
                   "sharp (default 60)")
      ->check(CLI::Range(0.0, 180.0));
  mesh->add_flag("--odt", mesh_options.odt,
                 "ODT smoothing after refinement (better elements, 1.3-2.4x slower; may crash "
                 "inside CGAL 5.5 on some coarse meshes)");
  mesh->add_flag("--lloyd", mesh_options.lloyd, "Lloyd smoothing after refinement (slower)");
  mesh->add_flag("--no-perturb", no_perturb, "Skip the sliver perturbation");
  mesh->add_flag("--no-exude", no_exude, "Skip the sliver exudation");
  bool no_repair = false;
  mesh->add_flag("--no-repair", no_repair,
                 "Report what would be repaired (orientation, degenerate triangles) as errors");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help/version (code 0) or the error
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (pack_cmd->parsed()) {
      if (!pack_size.empty()) pp.size = femdem::Vec3(pack_size[0], pack_size[1], pack_size[2]);
      return femdem::pack_command(pp, pack_out, pack_quiet);
    }
    if (mesh->parsed()) {
      mesh_options.perturb = !no_perturb;
      mesh_options.exude = !no_exude;
      mesh_options.repair = !no_repair;
      return femdem::mesh_command(mesh_input, mesh_output, mesh_options);
    }
    if (check->parsed()) {
      const femdem::SceneFile scene = femdem::load_scene(scene_path, overrides);
      if (material_name.empty() != strain_path.empty())
        throw femdem::InputError("--material and --strain-path go together");
      if (!material_name.empty())
        return femdem::material_point(scene, material_name, strain_path, substeps);
      for (const auto& note : scene.notes) fmt::print("{}\n", note);
      if (!scene.notes.empty()) fmt::print("\n");
      femdem::print_scene_summary(scene);
      return kExitOk;
    }
    if (sweep->parsed()) {
      sweep_options.plot = !no_plot;
      sweep_options.femdem_exe = self_exe(argv[0]);
      sweep_options.plot_script =
          femdem::find_plot_script(sweep_options.femdem_exe, "plot_sweep.py");
      return femdem::run_sweep(sweep_options);
    }
    if (run->parsed()) {
      femdem::SceneFile scene = femdem::load_scene(scene_path, overrides);
      femdem::RunOptions options;
      options.out_dir = out_dir.empty() ? default_out_dir(scene) : out_dir;
      options.threads = threads;
      options.quiet = quiet;
      if (!run_no_plot && scene.model.compaction)
        options.plot_script = femdem::find_plot_script(self_exe(argv[0]), "plot_compaction.py");
      for (int i = 0; i < argc; ++i) {
        if (i) options.command_line += ' ';
        options.command_line += argv[i];
      }
      return femdem::run_scene(scene, options);
    }
  } catch (const femdem::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.describe().c_str());
    return kExitBadInput;
  } catch (const femdem::InstabilityError& e) {
    std::fprintf(stderr, "error: the simulation became unstable: %s\n", e.what());
    return kExitUnstable;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitFailure;
  }
  return kExitFailure;
}
