// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/check_command.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>

#include "elements/tet_geometry.hpp"
#include "engine/contact_stiffness.hpp"
#include "engine/errors.hpp"
#include "engine/initial_overlap.hpp"
#include "engine/simulation.hpp"
#include "io/strain_path.hpp"
#include "materials/material_point.hpp"
#include "tools/femdem/exit_codes.hpp"
#include "tools/femdem/run/memory_check.hpp"
#include "tools/femdem/run/run_log.hpp"
#include "tools/femdem/run/thread_count.hpp"
#include "tools/femdem/text_format.hpp"

namespace femdem {
namespace {

// A penalty factor as the check prints it (0: the automatic stiffness).
std::string penalty_text(double factor, bool wall) {
  if (factor > 0.0)
    return fmt::format("factor {:g} (x E of the {})", factor, wall ? "body" : "stiffer side");
  return fmt::format("automatic ({:g} x the P-wave modulus of the {})",
                     wall ? kAutoWallFactor : kAutoPairFactor, wall ? "body" : "softer side");
}

// The timed sample of `femdem check`: at least this many steps, then more until this much wall
// time or this many steps.
constexpr std::int64_t kSampleMinSteps = 3;
constexpr std::int64_t kSampleMaxSteps = 1000;
constexpr double kSampleSeconds = 1.0;

}  // namespace

// `femdem check`: what the scene builds, without running anything.
void print_scene_summary(const SceneFile& scene) {
  const ModelSpec& m = scene.model;
  const auto& s = m.simulation;
  fmt::print("Scene     {}\n", scene.path);
  fmt::print("Title     {}\n\n", m.title);

  fmt::print("Simulation\n");
  fmt::print("  end time          {:g} s\n", s.end_time);
  if (s.time_step > 0.0)
    fmt::print("  time step         {:g} s (fixed)\n", s.time_step);
  else
    fmt::print("  time step         automatic, {:g} x the stable step ({} estimate){}\n",
               s.safety(),
               s.stable_step == SimulationSettings::StableStep::assembled ? "assembled" : "element",
               s.contact_stiffness_margin() > 1.0
                   ? fmt::format(", contact springs at {:g}", s.contact_safety())
                   : std::string());
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
    fmt::print("  {}: {}, density {:g} kg/m^3, E = {:g} Pa, nu = {:g}\n", mat.name,
               material_model_name(mat), mat.density, mat.youngs_modulus, mat.poisson_ratio);
    fmt::print("{}", with_material_model(mat.model.index(), [&](auto model) {
                 using M = decltype(model);
                 return M::describe(mat, mat.template params<typename M::Params>());
               }));
    fmt::print("    K = {:g} Pa, G = {:g} Pa, wave speed {:g} m/s (P), {:g} m/s (S)\n",
               mat.bulk_modulus(), mat.shear_modulus(), cp, cs);
  }
  fmt::print("\n");

  long long total_nodes = 0, total_elements = 0;
  double total_mass = 0.0;
  fmt::print("Bodies ({})\n", m.bodies.size());
  for (const auto& b : m.bodies) {
    const auto& mat = m.materials[static_cast<std::size_t>(b.material)];
    const MeshQuality q = mesh_quality(b.mesh);
    const double volume = q.total_volume;
    const double mass = mat.density * volume;
    Vec3 lo = b.mesh.nodes.front(), hi = b.mesh.nodes.front();
    for (const auto& p : b.mesh.nodes) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    total_nodes += static_cast<long long>(b.mesh.nodes.size());
    total_elements += static_cast<long long>(b.mesh.elements.size());
    total_mass += mass;
    const FbarMode fbar = b.fbar.value_or(default_fbar_mode(mat));
    fmt::print("  {}: material {}, {} nodes, {} elements, F-bar {}{}\n", b.name, mat.name,
               b.mesh.nodes.size(), b.mesh.elements.size(), to_string(fbar),
               b.fixed ? ", fixed" : "");
    fmt::print("    volume {:g} m^3, mass {:g} kg\n", volume, mass);
    fmt::print("    bounding box {} to {} m\n", vec(lo), vec(hi));
    fmt::print("    velocity {} m/s, angular velocity {} rad/s\n", vec(b.velocity),
               vec(b.angular_velocity));
    fmt::print("{}", indent(format_mesh_quality(q), "    "));
  }
  fmt::print("  total: {} nodes, {} elements, mass {:g} kg\n\n", total_nodes, total_elements,
             total_mass);

  if (!m.walls.empty()) {
    fmt::print("Walls ({})\n", m.walls.size());
    for (const auto& w : m.walls) {
      fmt::print(
          "  {}: point {}, normal {}, {}, friction {:g}, penalty {}, "
          "damping {:g}\n",
          w.name, vec(w.point), vec(w.normal),
          w.velocity_history.empty()
              ? "velocity " + vec(w.velocity) + " m/s"
              : fmt::format("velocity history of {} points, from {} m/s at t = 0 to {} m/s "
                            "from t = {:g} s on",
                            w.velocity_history.size(), vec(w.velocity_history.front().velocity),
                            vec(w.velocity_history.back().velocity),
                            w.velocity_history.back().time),
          w.friction,
          penalty_text(w.penalty_factor > 0.0   ? w.penalty_factor
                       : w.penalty_factor < 0.0 ? 0.0
                                                : m.contact.penalty_factor,
                       true),
          w.damping);
      if (w.rolling_resistance >= 0.0)
        fmt::print("    rolling resistance {:g} on this wall (the contact's: {:g})\n",
                   w.rolling_resistance, m.contact.rolling_resistance);
      if (!w.force_history.empty())
        fmt::print(
            "    force-driven: mass {:g} kg, force history of {} points, {:g} N at t = 0, "
            "{:g} N from t = {:g} s on\n",
            w.mass, w.force_history.size(), w.force_history.front().force,
            w.force_history.back().force, w.force_history.back().time);
      if (w.bounded) {
        if (std::isfinite(w.bound_min))
          fmt::print("    acts from {:g} to {:g} m along {} (the extent moves with the wall)\n",
                     w.bound_min, w.bound_max, vec(w.bound_axis));
        else
          fmt::print("    acts only up to {:g} m along {}\n", w.bound_max, vec(w.bound_axis));
      }
      if (w.bump_diameter > 0.0)
        fmt::print(
            "    studded: hemispheres of diameter {:g} m centred on the plane, on a hexagonal "
            "lattice of spacing {:g} m; they reach {:g} m in front of it\n",
            w.bump_diameter, w.bump_spacing, 0.5 * w.bump_diameter);
      if (std::isfinite(w.thickness))
        fmt::print(
            "    a plate {:g} m thick: a node further behind than half of it is pushed "
            "out through its back\n",
            w.thickness);
    }
    fmt::print("\n");
  }
  if (m.compaction) {
    const CompactionSpec& c = *m.compaction;
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
        case RegionSpec::Kind::All:
          region = "all nodes";
          break;
        case RegionSpec::Kind::Box:
          region = "nodes in the box " + vec(c.region.box_min) + " to " + vec(c.region.box_max);
          break;
        case RegionSpec::Kind::Plane:
          region = "nodes on the plane through " + vec(c.region.plane_point) + " with normal " +
                   vec(c.region.plane_normal);
          break;
        case RegionSpec::Kind::Nodes:
          region = fmt::format("the {} nodes of its mesh's physical group '{}'",
                               c.region.nodes.size(), c.region.node_set);
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
  fmt::print("Contact\n  penalty {}, friction {:g}", penalty_text(m.contact.penalty_factor, false),
             m.contact.friction);
  if (m.contact.impact_damping > 0.0)
    fmt::print(", impact damping {:g} (restitution about {:.2f} for a linear contact)",
               m.contact.impact_damping,
               std::exp(-M_PI * m.contact.impact_damping /
                        std::sqrt(1.0 - m.contact.impact_damping * m.contact.impact_damping)));
  if (m.contact.rolling_resistance > 0.0)
    fmt::print(", rolling resistance {:g} (a moment {:g} R N against rolling)",
               m.contact.rolling_resistance, m.contact.rolling_resistance);
  fmt::print("\n\n");
  // the model as a run builds it, with its first force evaluation: the overlaps at the start
  // (InputError) and the step
  fmt::print("Memory\n  {}\n\n", memory_line(m));
  check_memory(m);
  Simulation sim(build_model(m));
  check_initial_overlap(sim);
  const double steps = s.end_time / sim.dt();
  fmt::print(
      "Model\n  {} nodes, {} TET10 elements; stable step {:.4g} s, step {:.4g} s: about {:.0f} "
      "steps to the end time\n",
      sim.model().node_count, sim.model().element_count, sim.stable_dt(), sim.dt(), steps);
  // A timed sample of the run's own first steps (nothing is written): the rate the run starts
  // at. Contact, yielding and the outputs change it as the run goes.
  const int threads = use_threads(-1, s.threads);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  std::int64_t sampled = 0;
  while (sim.time() < s.end_time &&
         (sampled < kSampleMinSteps || (sampled < kSampleMaxSteps && seconds() < kSampleSeconds))) {
    sim.step();
    ++sampled;
  }
  const double per_step = seconds() / static_cast<double>(std::max<std::int64_t>(sampled, 1));
  fmt::print(
      "  timed sample: {} steps in {:.2g} s on {} thread{} ({:.0f} steps/s): about {} for "
      "the run at that rate\n\n",
      sampled, seconds(), threads, threads == 1 ? "" : "s", 1.0 / per_step,
      format_duration(per_step * steps));
  fmt::print("Scene OK.\n");
}

// `femdem check SCENE --material NAME --strain-path FILE`: the stress path of one material point
// under a prescribed deformation history, as CSV on standard output.
int material_point(const SceneFile& scene, const std::string& name, const std::string& path_file,
                   int substeps) {
  const MaterialParams* mat = nullptr;
  std::vector<std::string> names;
  for (const auto& m : scene.model.materials) {
    names.push_back(m.name);
    if (m.name == name) mat = &m;
  }
  if (!mat) {
    std::string all;
    for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
    throw InputError("no material '" + name + "' in the scene (materials: " + all + ")", scene.path,
                     0, 0, "--material");
  }
  const std::vector<F3> targets = read_strain_path(path_file);
  const auto steps = drive_deformation(*mat, targets, substeps);
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

}  // namespace femdem
