// SPDX-License-Identifier: GPL-3.0-or-later
// The femdem command-line program: `femdem run|check|sweep SCENE ...`, `femdem pack FILE ...`
// and `femdem mesh SURFACE --size H` (see docs/SCENES.md and /work/shared/SCENE_FORMAT.md). Exit
// codes: 0 success, 2 bad input, 3 unstable, 1 otherwise.
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

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "femdem_version.hpp"
#include "io/cad_mesh.hpp"
#include "io/gmsh_io.hpp"
#include "io/packing.hpp"
#include "io/runner.hpp"
#include "io/scene_reader.hpp"
#include "io/strain_path.hpp"
#include "io/sweep.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitUnstable = 3;

std::string version_string() {
  return std::string("femdem ") + FEMDEM_VERSION + " (git " + FEMDEM_GIT_REVISION + ")";
}

std::string vec(const femdem::Vec3& v) {
  return fmt::format("[{:g}, {:g}, {:g}]", v.x(), v.y(), v.z());
}

std::string indent(const std::string& text, const std::string& prefix) {
  std::string out = prefix;
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '\n' && i + 1 < text.size()) out += prefix;
  }
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

// `femdem check`: what the scene builds, without running anything.
void print_summary(const femdem::SceneFile& scene) {
  const femdem::ModelSpec& m = scene.model;
  const auto& s = m.simulation;
  fmt::print("Scene     {}\n", scene.path);
  fmt::print("Title     {}\n\n", m.title);

  fmt::print("Simulation\n");
  fmt::print("  end time          {:g} s\n", s.end_time);
  if (s.time_step > 0.0)
    fmt::print("  time step         {:g} s (fixed)\n", s.time_step);
  else
    fmt::print("  time step         automatic, {:g} x the stable step\n", s.time_step_safety);
  fmt::print("  output interval   {:g} s (about {} frames)\n", s.output_interval,
             static_cast<long long>(std::floor(s.end_time / s.output_interval + 1e-9)) + 1);
  fmt::print("  history interval  {:g} s\n", s.history_interval);
  fmt::print("  gravity           {} m/s^2\n", vec(s.gravity));
  if (s.bulk_viscosity_linear > 0.0 || s.bulk_viscosity_quadratic > 0.0)
    fmt::print("  bulk viscosity    linear {:g}, quadratic {:g}\n", s.bulk_viscosity_linear,
               s.bulk_viscosity_quadratic);
  if (s.threads == 0)
    fmt::print("  threads           all cores\n\n");
  else
    fmt::print("  threads           {}\n\n", s.threads);

  fmt::print("Materials ({})\n", m.materials.size());
  for (const auto& mat : m.materials) {
    const double cp = std::sqrt(mat.p_wave_modulus() / mat.density);
    const double cs = std::sqrt(mat.shear_modulus() / mat.density);
    const bool plastic = mat.model == femdem::MaterialModel::VonMises;
    fmt::print("  {}: {}, density {:g} kg/m^3, E = {:g} Pa, nu = {:g}\n", mat.name,
               femdem::material_model_name(mat.model), mat.density, mat.youngs_modulus,
               mat.poisson_ratio);
    if (mat.model == femdem::MaterialModel::MohrCoulomb ||
        mat.model == femdem::MaterialModel::DruckerPrager) {
      fmt::print("    cohesion {:g} Pa, friction angle {:g} deg, dilatancy angle {:g} deg\n",
                 mat.cohesion, mat.friction_angle, mat.dilatancy_angle);
      if (mat.model == femdem::MaterialModel::DruckerPrager)
        fmt::print("    cone matched to Mohr-Coulomb: {}\n",
                   femdem::drucker_prager_cone_name(mat.cone));
      if (mat.cohesion_hardening_modulus != 0.0)
        fmt::print("    cohesion hardening {:g} Pa, residual cohesion {:g} Pa\n",
                   mat.cohesion_hardening_modulus, mat.residual_cohesion);
    }
    if (mat.model == femdem::MaterialModel::PiecewiseDruckerPrager) {
      fmt::print("    {} pieces [A, B Pa]:", mat.pieces.size());
      for (const auto& [a, b] : mat.pieces) fmt::print(" [{:g}, {:g}]", a, b);
      fmt::print(", dilatancy {:g}\n", mat.pieces_dilatancy);
    }
    if (plastic) {
      switch (mat.hardening) {
        case femdem::HardeningLaw::Linear:
          fmt::print("    yield stress {:g} Pa, linear hardening {:g} Pa\n", mat.yield_stress,
                     mat.hardening_modulus);
          break;
        case femdem::HardeningLaw::Tabulated:
          fmt::print("    tabulated hardening, {} points, yield stress {:g} Pa\n",
                     mat.hardening_curve.size(), mat.yield_stress);
          break;
        case femdem::HardeningLaw::Swift:
          fmt::print("    Swift hardening {:g} ({:g} + eps_p)^{:g} Pa, yield stress {:g} Pa\n",
                     mat.swift_K, mat.swift_eps0, mat.swift_n, mat.yield_stress);
          break;
      }
      if (mat.jc_C > 0.0)
        fmt::print("    Johnson-Cook rate factor C = {:g}, reference rate {:g} 1/s\n", mat.jc_C,
                   mat.jc_epsdot0);
    }
    fmt::print("    K = {:g} Pa, G = {:g} Pa, wave speed {:g} m/s (P), {:g} m/s (S)\n",
               mat.bulk_modulus(), mat.shear_modulus(), cp, cs);
  }
  fmt::print("\n");

  long long total_nodes = 0, total_elements = 0;
  double total_mass = 0.0;
  fmt::print("Bodies ({})\n", m.bodies.size());
  for (const auto& b : m.bodies) {
    const auto& mat = m.materials[static_cast<std::size_t>(b.material)];
    const femdem::MeshQuality q = femdem::mesh_quality(b.mesh);
    const double volume = q.total_volume;
    const double mass = mat.density * volume;
    femdem::Vec3 lo = b.mesh.nodes.front(), hi = b.mesh.nodes.front();
    for (const auto& p : b.mesh.nodes) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    total_nodes += static_cast<long long>(b.mesh.nodes.size());
    total_elements += static_cast<long long>(b.mesh.elements.size());
    total_mass += mass;
    const femdem::FbarMode fbar = b.fbar.value_or(femdem::default_fbar_mode(mat));
    fmt::print("  {}: material {}, {} nodes, {} elements, F-bar {}{}\n", b.name, mat.name,
               b.mesh.nodes.size(), b.mesh.elements.size(), femdem::to_string(fbar),
               b.fixed ? ", fixed" : "");
    fmt::print("    volume {:g} m^3, mass {:g} kg\n", volume, mass);
    fmt::print("    bounding box {} to {} m\n", vec(lo), vec(hi));
    fmt::print("    velocity {} m/s, angular velocity {} rad/s\n", vec(b.velocity),
               vec(b.angular_velocity));
    fmt::print("{}", indent(femdem::format_mesh_quality(q), "    "));
  }
  fmt::print("  total: {} nodes, {} elements, mass {:g} kg\n\n", total_nodes, total_elements,
             total_mass);

  if (!m.walls.empty()) {
    fmt::print("Walls ({})\n", m.walls.size());
    for (const auto& w : m.walls) {
      fmt::print(
          "  {}: point {}, normal {}, {}, friction {:g}, penalty factor {:g}, "
          "damping {:g}\n",
          w.name, vec(w.point), vec(w.normal),
          w.velocity_history.empty()
              ? "velocity " + vec(w.velocity) + " m/s"
              : fmt::format("velocity history of {} points, from {} m/s at t = 0 to {} m/s "
                            "from t = {:g} s on",
                            w.velocity_history.size(), vec(w.velocity_history.front().velocity),
                            vec(w.velocity_history.back().velocity),
                            w.velocity_history.back().time),
          w.friction, w.penalty_factor > 0.0 ? w.penalty_factor : m.contact.penalty_factor,
          w.damping);
      if (!w.force_history.empty())
        fmt::print(
            "    force-driven: mass {:g} kg, force history of {} points, {:g} N at t = 0, "
            "{:g} N from t = {:g} s on\n",
            w.mass, w.force_history.size(), w.force_history.front().force,
            w.force_history.back().force, w.force_history.back().time);
      if (w.bounded)
        fmt::print("    acts only up to {:g} m along {}\n", w.bound_max, vec(w.bound_axis));
    }
    fmt::print("\n");
  }
  if (m.compaction) {
    const femdem::CompactionSpec& c = *m.compaction;
    std::string die, powder;
    for (int wi : c.die_walls)
      die += (die.empty() ? "" : ", ") + m.walls[static_cast<std::size_t>(wi)].name;
    for (int bi : c.powder)
      powder += (powder.empty() ? "" : ", ") + m.bodies[static_cast<std::size_t>(bi)].name;
    fmt::print(
        "Compaction\n  punch {}, bottom {}; die walls {}\n  die cross-section {:g} m^2, "
        "perimeter {:g} m; powder: {}\n\n",
        m.walls[static_cast<std::size_t>(c.punch)].name,
        m.walls[static_cast<std::size_t>(c.bottom)].name, die, c.area, c.perimeter,
        powder.empty() ? "every body that is not fixed" : powder);
  }
  if (!m.constraints.empty()) {
    fmt::print("Constraints ({})\n", m.constraints.size());
    for (const auto& c : m.constraints) {
      std::string region;
      switch (c.region.kind) {
        case femdem::RegionSpec::Kind::All:
          region = "all nodes";
          break;
        case femdem::RegionSpec::Kind::Box:
          region = "nodes in the box " + vec(c.region.box_min) + " to " + vec(c.region.box_max);
          break;
        case femdem::RegionSpec::Kind::Plane:
          region = "nodes on the plane through " + vec(c.region.plane_point) + " with normal " +
                   vec(c.region.plane_normal);
          break;
      }
      std::string action;
      if (c.velocity) {
        action = "velocity " + vec(*c.velocity) + " m/s";
      } else {
        action = "fix";
        for (int i = 0; i < 3; ++i)
          if (c.fix[static_cast<std::size_t>(i)]) action += std::string(" ") + "xyz"[i];
      }
      fmt::print("  {}: {}, {}\n", m.bodies[static_cast<std::size_t>(c.body)].name, region, action);
    }
    fmt::print("\n");
  }
  fmt::print("Contact\n  penalty factor {:g}, friction {:g}", m.contact.penalty_factor,
             m.contact.friction);
  if (m.contact.impact_damping > 0.0)
    fmt::print(", impact damping {:g} (restitution about {:.2f} for a linear contact)",
               m.contact.impact_damping,
               std::exp(-M_PI * m.contact.impact_damping /
                        std::sqrt(1.0 - m.contact.impact_damping * m.contact.impact_damping)));
  fmt::print("\n\n");
  fmt::print("Scene OK.\n");
}

// A plot script the program calls (plot_sweep.py after `femdem sweep`, plot_compaction.py after
// a run with [compaction]): next to the program's source tree (baked in at build time), else in
// ../tools/ of the program's folder.
std::string plot_script(const std::string& exe, const char* name) {
  namespace fs = std::filesystem;
  std::error_code ec;
#ifdef FEMDEM_TOOLS_DIR
  if (fs::exists(fs::path(FEMDEM_TOOLS_DIR) / name, ec))
    return (fs::path(FEMDEM_TOOLS_DIR) / name).string();
#endif
  const fs::path near = fs::path(exe).parent_path() / ".." / "tools" / name;
  if (fs::exists(near, ec)) return near.string();
  return {};
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

// `femdem pack OUT ...`: generates a packing, writes it and prints what it got.
int pack(const femdem::PackingParams& params, const std::string& out, bool quiet) {
  if (auto e = femdem::check_packing_params(params)) {
    std::string option = e->key;
    std::replace(option.begin(), option.end(), '_', '-');
    throw femdem::InputError(e->message, {}, 0, 0, "--" + option);
  }
  const auto start = std::chrono::steady_clock::now();
  femdem::Packing packing;
  try {
    packing = femdem::generate_packing(params);
  } catch (femdem::InputError& e) {
    std::replace(e.key.begin(), e.key.end(), '_', '-');
    if (!e.key.empty()) e.key = "--" + e.key;
    throw;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  femdem::write_packing(out, packing);
  if (quiet) return kExitOk;
  const femdem::PackingStats& s = packing.stats;
  fmt::print("{}: {} particles, {}\n", out, packing.particles.size(), params.arrangement);
  fmt::print("  packing fraction  {:.4f} (bed of height {:g} m); {:.4f} of the container\n",
             s.packing_fraction, s.bed_height, s.container_fraction);
  if (std::isfinite(s.core_packing_fraction))
    fmt::print("  core fraction     {:.4f} (two largest diameters from walls, floor and top)\n",
               s.core_packing_fraction);
  if (std::isfinite(s.min_gap))
    fmt::print("  smallest gap      {:.3g} of the radii sum\n", s.min_gap);
  if (s.settle_steps > 0)
    fmt::print(
        "  settling          {} steps, {:.4g} sqrt(d/g), {}, last max speed {:.3g} sqrt(g d)\n",
        s.settle_steps, s.settle_time, s.at_rest ? "at rest" : "NOT at rest", s.max_speed);
  fmt::print("  time              {:.3f} s\n", seconds);
  return kExitOk;
}

// `femdem check SCENE --material NAME --strain-path FILE`: the stress path of one material point
// under a prescribed deformation history, as CSV on standard output.
int material_point(const femdem::SceneFile& scene, const std::string& name,
                   const std::string& path_file, int substeps) {
  const femdem::MaterialParams* mat = nullptr;
  std::vector<std::string> names;
  for (const auto& m : scene.model.materials) {
    names.push_back(m.name);
    if (m.name == name) mat = &m;
  }
  if (!mat) {
    std::string all;
    for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
    throw femdem::InputError("no material '" + name + "' in the scene (materials: " + all + ")",
                             scene.path, 0, 0, "--material");
  }
  const std::vector<femdem::F3> targets = femdem::read_strain_path(path_file);
  const auto steps = femdem::drive_deformation(*mat, targets, substeps);
  fmt::print(
      "step,target,F11,F12,F13,F21,F22,F23,F31,F32,F33,sigma_xx,sigma_yy,sigma_zz,sigma_xy,"
      "sigma_yz,sigma_xz,von_mises,pressure,eq_plastic_strain,elastic_energy,dissipation\n");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto& s = steps[i];
    const double* q = s.sigma;
    const double p = -(q[0] + q[1] + q[2]) / 3.0;
    const double vm = std::sqrt(1.5 * ((q[0] + p) * (q[0] + p) + (q[1] + p) * (q[1] + p) +
                                       (q[2] + p) * (q[2] + p) +
                                       2.0 * (q[3] * q[3] + q[4] * q[4] + q[5] * q[5])));
    fmt::print("{},{}", i + 1, s.segment + 1);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fmt::print(",{:.17g}", s.F[r][c]);
    for (int k = 0; k < 6; ++k) fmt::print(",{:.17g}", q[k]);
    fmt::print(",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", vm, p, s.eps_p, s.elastic_energy,
               s.dissipation);
  }
  return kExitOk;
}

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
      return pack(pp, pack_out, pack_quiet);
    }
    if (mesh->parsed()) {
      mesh_options.perturb = !no_perturb;
      mesh_options.exude = !no_exude;
      mesh_options.repair = !no_repair;
      if (mesh_output.empty())
        mesh_output = std::filesystem::path(mesh_input).replace_extension(".msh").string();
      if (std::filesystem::path(mesh_output).extension() != ".msh")
        throw femdem::InputError("the output must be a .msh file", mesh_output, 0, 0, "-o");
      if (std::filesystem::weakly_canonical(mesh_output) ==
          std::filesystem::weakly_canonical(mesh_input))
        throw femdem::InputError("the output would overwrite the input", mesh_output, 0, 0, "-o");
      femdem::CadMeshReport report;
      const femdem::Tet10Mesh m = femdem::mesh_cad_file(mesh_input, mesh_options, &report);
      femdem::write_gmsh(m, mesh_output);
      fmt::print("{}\n", femdem::format_cad_report(report));
      fmt::print("{}", indent(femdem::format_mesh_quality(femdem::mesh_quality(m)), ""));
      fmt::print("wrote {}\n", mesh_output);
      return kExitOk;
    }
    if (check->parsed()) {
      const femdem::SceneFile scene = femdem::load_scene(scene_path, overrides);
      if (material_name.empty() != strain_path.empty())
        throw femdem::InputError("--material and --strain-path go together");
      if (!material_name.empty())
        return material_point(scene, material_name, strain_path, substeps);
      for (const auto& note : scene.notes) fmt::print("{}\n", note);
      if (!scene.notes.empty()) fmt::print("\n");
      print_summary(scene);
      return kExitOk;
    }
    if (sweep->parsed()) {
      sweep_options.plot = !no_plot;
      sweep_options.femdem_exe = self_exe(argv[0]);
      sweep_options.plot_script = plot_script(sweep_options.femdem_exe, "plot_sweep.py");
      return femdem::run_sweep(sweep_options);
    }
    if (run->parsed()) {
      femdem::SceneFile scene = femdem::load_scene(scene_path, overrides);
      femdem::RunOptions options;
      options.out_dir = out_dir.empty() ? default_out_dir(scene) : out_dir;
      options.threads = threads;
      options.quiet = quiet;
      if (!run_no_plot && scene.model.compaction)
        options.plot_script = plot_script(self_exe(argv[0]), "plot_compaction.py");
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
