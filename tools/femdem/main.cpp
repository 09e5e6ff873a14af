// SPDX-License-Identifier: GPL-3.0-or-later
// The femdem command-line program: `femdem run|check|sweep SCENE ...`, `femdem pack FILE ...`
// and `femdem mesh SURFACE --size H` (docs/SCENES.md): the options of each command, and the
// exit code of what went wrong (exit_codes.hpp). The commands themselves live beside it.
#include <fmt/core.h>
#include <charconv>
#include <cmath>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "engine/distributed/communicator.hpp"
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

// A positive finite number, said in words (CLI11's own PositiveNumber prints its range with the
// 309 digits of the largest double).
const CLI::Validator kPositiveNumber(
    [](std::string& text) {
      double v = 0.0;
      const char* end = text.data() + text.size();
      const auto r = std::from_chars(text.data(), end, v);
      if (r.ec != std::errc() || r.ptr != end || !(v > 0.0) || !std::isfinite(v))
        return "must be a positive number, got '" + text + "'";
      return std::string();
    },
    "POSITIVE");

// --threads: the scene key's bounds (simulation.threads), in CLI11's words "in range 0 - 4096".
const CLI::Range kThreadsRange(0, 4096);

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

// A command: its options (declared on `app`) and what it does once they are parsed. The
// options live in `state`, which the action shares.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> action;
};

// The words of the command line, for run.log.
std::string command_line_of(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

Command add_run(CLI::App& app, const std::string& exe, const std::string& command_line) {
  struct State {
    std::string scene_path, out_dir;
    std::vector<std::string> overrides;
    int threads = -1;
    bool quiet = false, no_plot = false, force = false;
  };
  auto s = std::make_shared<State>();
  CLI::App* run = app.add_subcommand("run", "Run a scene and write its results");
  run->add_option("scene", s->scene_path, "Scene file (TOML)")->required();
  CLI::Option* out_option =
      run->add_option("--out", s->out_dir, "Output folder (default: out/<scene file stem>/)");
  run->add_option("--set", s->overrides, "Override a scene value: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  run->add_option("--threads", s->threads, "Number of threads (0: all cores; default: the scene's)")
      ->check(kThreadsRange);
  run->add_flag("--quiet", s->quiet, "Print nothing but errors");
  run->add_flag("--force", s->force,
                "Replace the outputs of an earlier run in the output folder (without it, such a "
                "folder is refused: femdem resume continues that run)");
  run->add_flag("--no-plot", s->no_plot,
                "Do not call tools/plot_compaction.py after a run with [compaction]");
  return {run, [s, exe, command_line, out_option] {
            femdem::SceneFile scene = femdem::load_scene(s->scene_path, s->overrides);
            femdem::RunOptions options;
            // --out '' is refused (run_scene), not taken for the default
            options.out_dir = out_option->count() == 0 ? default_out_dir(scene) : s->out_dir;
            options.threads = s->threads;
            options.quiet = s->quiet;
            if (!s->no_plot && scene.model.compaction)
              options.plot_script = femdem::find_plot_script(exe, "plot_compaction.py");
            options.command_line = command_line;
            options.overrides = s->overrides;
            options.force = s->force;
            return femdem::run_scene(scene, options);
          }};
}

Command add_resume(CLI::App& app, const std::string& exe, const std::string& command_line) {
  struct State {
    femdem::ResumeOptions options;
    bool no_plot = false;
  };
  auto s = std::make_shared<State>();
  CLI::App* resume = app.add_subcommand(
      "resume",
      "Continue a run from the checkpoint in its output folder (after a kill, a signal or a "
      "crash; or, with a later simulation.end_time, extend a finished run), appending to its "
      "outputs");
  resume->add_option("out", s->options.run.out_dir, "The run's output folder")->required();
  resume
      ->add_option("--set", s->options.overrides,
                   "Change what does not alter the past: simulation.end_time, output_interval, "
                   "history_interval, checkpoint_interval, checkpoint_wall_interval, "
                   "rest_kinetic_fraction, rest_hold_time, rebalance_threshold, threads, "
                   "contact_time_step_safety "
                   "(KEY=VALUE, repeatable)")
      ->allow_extra_args(false);
  resume
      ->add_option("--threads", s->options.run.threads,
                   "Number of threads (0: all cores; default: the run's)")
      ->check(kThreadsRange);
  resume->add_flag("--quiet", s->options.run.quiet, "Print nothing but errors");
  resume->add_flag("--no-plot", s->no_plot,
                   "Do not call tools/plot_compaction.py after a run with [compaction]");
  return {resume, [s, exe, command_line] {
            femdem::ResumeOptions& o = s->options;
            o.run.command_line = command_line;
            if (!s->no_plot)
              o.run.plot_script = femdem::find_plot_script(exe, "plot_compaction.py");
            return femdem::resume_run(o);
          }};
}

Command add_check(CLI::App& app) {
  struct State {
    std::string scene_path, material_name, strain_path;
    std::vector<std::string> overrides;
    int substeps = 10;
  };
  auto s = std::make_shared<State>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Read the scene, build the model, time its first steps and print a summary; write "
      "nothing");
  check->add_option("scene", s->scene_path, "Scene file (TOML)")->required();
  check->add_option("--set", s->overrides, "Override a scene value: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  check->add_option("--material", s->material_name,
                    "With --strain-path: drive this material of the scene through a homogeneous "
                    "deformation history and print the stress path as CSV");
  check->add_option("--strain-path", s->strain_path,
                    "File of target deformation gradients, 9 numbers (row-major F) per line");
  check->add_option("--substeps", s->substeps, "Increments between two targets (default 10)")
      ->check(CLI::Range(1, 1000000));
  return {check, [s] {
            const femdem::SceneFile scene = femdem::load_scene(s->scene_path, s->overrides);
            if (s->material_name.empty() != s->strain_path.empty())
              throw femdem::InputError("--material and --strain-path go together");
            if (!s->material_name.empty())
              return femdem::material_point(scene, s->material_name, s->strain_path, s->substeps);
            for (const auto& note : scene.notes) fmt::print("{}\n", note);
            if (!scene.notes.empty()) fmt::print("\n");
            femdem::print_scene_summary(scene);
            return kExitOk;
          }};
}

Command add_sweep(CLI::App& app, const std::string& exe) {
  struct State {
    femdem::SweepOptions options;
    bool no_plot = false;
    std::string launcher;
  };
  auto s = std::make_shared<State>();
  femdem::SweepOptions& o = s->options;
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "Run a scene for every combination of --vary values, each run in its own sub-folder, "
      "and collect the results in DIR/sweep.csv (plus plots)");
  sweep->add_option("scene", o.scene_path, "Scene file (TOML)")->required();
  sweep
      ->add_option("--vary", o.vary,
                   "KEY=V1,V2,...: values of one scene key (repeatable; the runs are the "
                   "cartesian product). Commas inside [..] separate array elements, not values: "
                   "bodies.ball.velocity=[0,0,-5],[0,0,-10]. Ranges: START:STOP:STEP, "
                   "linspace(A,B,N), logspace(A,B,N)")
      ->required()
      ->allow_extra_args(false);
  sweep
      ->add_option("--set", o.overrides,
                   "Override a scene value in every run: KEY=VALUE (repeatable)")
      ->allow_extra_args(false);
  sweep->add_option("--out", o.out_dir, "Sweep folder (default: out/<scene file stem>_sweep/)");
  sweep->add_option("--jobs", o.jobs, "Runs at a time (default: cores / threads per job)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("--threads-per-job", o.threads_per_job, "Threads of each run (default 1)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("--launcher", s->launcher,
                    "Start each run through this command, e.g. 'mpirun -np 2' (each run on 2 MPI "
                    "ranks; words split at spaces, the first looked up on PATH)");
  sweep->add_flag("--no-plot", s->no_plot, "Do not call tools/plot_sweep.py at the end");
  sweep->add_flag("--quiet", o.quiet, "Print nothing but errors");
  return {sweep, [s, exe] {
            s->options.plot = !s->no_plot;
            s->options.femdem_exe = exe;
            std::istringstream words(s->launcher);
            for (std::string w; words >> w;) s->options.launcher.push_back(w);
            if (!s->launcher.empty() && s->options.launcher.empty())
              throw femdem::InputError("--launcher is empty (give a command, e.g. 'mpirun -np 2')",
                                       "", 0, 0, "--launcher");
            s->options.plot_script = femdem::find_plot_script(exe, "plot_sweep.py");
            return femdem::run_sweep(s->options);
          }};
}

Command add_pack(CLI::App& app) {
  struct State {
    femdem::PackingParams pp;
    std::string out;
    bool quiet = false;
    std::vector<double> size;
  };
  auto s = std::make_shared<State>();
  femdem::PackingParams& pp = s->pp;
  CLI::App* pack = app.add_subcommand(
      "pack",
      "Generate a particle packing (lattice, or random and settled under gravity) and write it "
      "to a file for [[packings]] in scenes (docs/SCENES.md, docs/OUTPUTS.md)");
  pack->add_option("out", s->out, "Packing file to write (CSV)")->required();
  pack->add_option("--container", pp.container, "box (default) or cylinder");
  pack->add_option("--size", s->size, "Box size lx ly lz (m); the box spans [0, l]")
      ->expected(3)
      ->delimiter(',');
  pack->add_option("--radius", pp.radius, "Cylinder radius (m); axis z through the origin");
  pack->add_option("--height", pp.height, "Cylinder height (m)");
  pack->add_option("--arrangement", pp.arrangement,
                   "random (default: dropped and settled under gravity), simple_cubic, "
                   "body_centred_cubic, face_centred_cubic");
  pack->add_option("--count", pp.count,
                   "Number of particles (random: required; lattice: default all that fit)");
  pack->add_option("--distribution", pp.distribution, "monodisperse (default), uniform, lognormal");
  pack->add_option("--diameter", pp.diameter, "Monodisperse diameter (m)");
  pack->add_option("--diameter-min", pp.diameter_min,
                   "Uniform: smallest diameter; lognormal: clip (default mean exp(-3 sigma))");
  pack->add_option("--diameter-max", pp.diameter_max,
                   "Uniform: largest diameter; lognormal: clip (default mean exp(3 sigma))");
  pack->add_option("--diameter-mean", pp.diameter_mean, "Lognormal: mean diameter (m)");
  pack->add_option("--sigma", pp.sigma, "Lognormal: standard deviation of ln d");
  pack->add_option("--seed", pp.seed, "Random seed (default 1)");
  pack->add_option("--shape", pp.shape,
                   "Shape name stored per particle (default sphere; a CAD shape is settled "
                   "by its bounding sphere)");
  pack->add_option("--orientation", pp.orientation,
                   "identity or random (default: identity for spheres, random otherwise)");
  pack->add_option("--friction", pp.friction, "Friction while settling (default 0.5)");
  pack->add_flag("--quiet", s->quiet, "Print nothing but errors");
  return {pack, [s] {
            if (!s->size.empty()) s->pp.size = femdem::Vec3(s->size[0], s->size[1], s->size[2]);
            return femdem::pack_command(s->pp, s->out, s->quiet);
          }};
}

Command add_mesh(CLI::App& app) {
  struct State {
    std::string input, output;
    femdem::CadMeshOptions options;
    bool no_perturb = false, no_exude = false, no_repair = false;
  };
  auto s = std::make_shared<State>();
  femdem::CadMeshOptions& o = s->options;
  CLI::App* mesh = app.add_subcommand(
      "mesh",
      "Mesh a closed CAD surface (STL, OBJ, PLY, OFF, glTF, 3MF, ... anything assimp reads) "
      "into TET10 elements and write a gmsh .msh file");
  mesh->add_option("input", s->input, "Surface file")->required();
  mesh->add_option("--size", o.element_size,
                   "Target edge length of the tetrahedra, in m (after --scale)")
      ->required()
      ->check(kPositiveNumber);
  mesh->add_option("--scale", o.scale,
                   "Factor from the file's units to m, e.g. 0.001 for mm (default 1)")
      ->check(kPositiveNumber);
  mesh->add_option("-o,--output", s->output, "Output .msh file (default: INPUT with .msh)");
  mesh->add_option("--feature-angle", o.feature_angle,
                   "Edges whose faces' normals differ by more than this (degrees) are kept "
                   "sharp (default 60)")
      ->check(CLI::Range(0.0, 180.0));
  mesh->add_flag("--odt", o.odt,
                 "ODT smoothing after refinement (better elements, 1.3-2.4x slower; may crash "
                 "inside CGAL 5.5 on some coarse meshes)");
  mesh->add_flag("--lloyd", o.lloyd, "Lloyd smoothing after refinement (slower)");
  mesh->add_flag("--no-perturb", s->no_perturb, "Skip the sliver perturbation");
  mesh->add_flag("--no-exude", s->no_exude, "Skip the sliver exudation");
  mesh->add_flag("--no-repair", s->no_repair,
                 "Report what would be repaired (orientation, degenerate triangles) as errors");
  return {mesh, [s] {
            s->options.perturb = !s->no_perturb;
            s->options.exude = !s->no_exude;
            s->options.repair = !s->no_repair;
            return femdem::mesh_command(s->input, s->output, s->options);
          }};
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
  const std::string exe = self_exe(argv[0]);
  const Command commands[] = {add_run(app, exe, command_line_of(argc, argv)),
                              add_resume(app, exe, command_line_of(argc, argv)),
                              add_check(app),
                              add_sweep(app, exe),
                              add_pack(app),
                              add_mesh(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // (every rank of an mpirun finds the same command line wrong: rank 0 alone says so)
    const int code = femdem::Communicator::launcher_rank() > 0 ? e.get_exit_code() : app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  // Under mpirun every rank runs this. Before the ranks' first step together, a failure of some
  // ranks (bad input all find alike, or a file one cannot read) is agreed by all: the lowest
  // failing rank says why (rank 0 when all fail alike) and every rank exits with its code. When
  // the ranks end together (rank 0 stopped them), rank 0 reports (bad input, a diverging run),
  // the others stay quiet. Any other failure of a rank stops them all.
  const femdem::Communicator& world = femdem::Communicator::world();
  auto failed = [&world](int code, const std::string& message) {
    if (world.size() == 1) {
      std::fprintf(stderr, "error: %s\n", message.c_str());
      return code;
    }
    auto say = [&] {
      if (world.rank() == 0)
        std::fprintf(stderr, "error: %s\n", message.c_str());
      else
        std::fprintf(stderr, "error (rank %d of %d): %s\n", world.rank(), world.size(),
                     message.c_str());
    };
    if (!world.started()) {
      const femdem::RanksFailed agreed = world.report_start_failure(code, message);
      if (agreed.rank == world.rank()) say();
      return agreed.code;
    }
    if (world.ending()) {
      if (world.rank() == 0) say();
      return code;
    }
    std::fprintf(stderr, "error (rank %d of %d): %s\n", world.rank(), world.size(),
                 message.c_str());
    world.abort(code);
  };
  try {
    if (world.size() > 1 && !commands[0].app->parsed() && !commands[1].app->parsed())
      throw femdem::InputError("femdem " + app.get_subcommands().front()->get_name() +
                               " runs as one process: only run and resume take several ranks "
                               "(mpirun -np N femdem run SCENE)");
    for (const Command& c : commands)
      if (c.app->parsed()) return c.action();
  } catch (const femdem::RanksFailed& e) {
    return e.code;  // (another rank failed before the start and said why)
  } catch (const femdem::InputError& e) {
    return failed(kExitBadInput, e.describe());
  } catch (const femdem::InstabilityError& e) {
    return failed(kExitUnstable, std::string("the simulation became unstable: ") + e.what());
  } catch (const std::exception& e) {
    return failed(kExitFailure, e.what());
  }
  return kExitFailure;
}
