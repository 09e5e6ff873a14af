// SPDX-License-Identifier: GPL-3.0-or-later
// The run driver: model, time loop, outputs, progress, restitution, and what a user sees when a
// run fails or is interrupted.
#include "io/runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "engine/compaction.hpp"
#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "femdem_version.hpp"
#include "io/history_writer.hpp"
#include "io/results_writer.hpp"
#include "io/summary_writer.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace femdem {
namespace {

std::atomic<int> g_stop_signal{0};
extern "C" void on_stop_signal(int sig) {
  g_stop_signal = sig;
}

// Everything printed also goes to run.log.
class RunLog {
 public:
  RunLog(const std::filesystem::path& path, bool quiet) : file_(path), quiet_(quiet) {
    if (!file_) throw std::runtime_error("cannot create " + path.string());
  }
  void say(const std::string& line) {
    if (!quiet_) std::printf("%s\n", line.c_str()), std::fflush(stdout);
    file_ << line << '\n';
    file_.flush();
  }
  void file_only(const std::string& text) {
    file_ << text;
    file_.flush();
  }
  // A message that must reach the user even with --quiet (errors).
  void error(const std::string& line) {
    file_ << line << '\n';
    file_.flush();
  }

 private:
  std::ofstream file_;
  bool quiet_;
};

std::string format_duration(double s) {
  char buf[64];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else
    std::snprintf(buf, sizeof buf, "%.0f h %02.0f min", std::floor(s / 3600),
                  std::fmod(s / 60, 60));
  return buf;
}

// Coefficient of restitution of one body (SCENE_FORMAT.md): the centre-of-mass speed after the
// last contact over the speed before the first, and sqrt(KE_after / KE_before).
struct RestitutionTracker {
  bool touched = false, in_contact = false;
  double speed_before = 0.0, ke_before = 0.0;
  double speed_after = 0.0, ke_after = 0.0;
  double last_speed = 0.0, last_ke = 0.0;
  void update(const BodyState& s) {
    const bool contact = s.contact_force.squaredNorm() > 0.0;
    if (contact && !touched) {
      touched = true;
      speed_before = last_speed;
      ke_before = last_ke;
    }
    if (!contact && in_contact) {
      speed_after = s.vcom.norm();
      ke_after = s.kinetic_energy;
    }
    in_contact = contact;
    last_speed = s.vcom.norm();
    last_ke = s.kinetic_energy;
  }
  std::optional<Restitution> result() const {
    if (!touched || in_contact || speed_before <= 0.0 || ke_before <= 0.0) return std::nullopt;
    return Restitution{speed_after / speed_before, std::sqrt(ke_after / ke_before)};
  }
};

// summary.json's "compaction" object: extremes of the curve and the Heckel and Kawakita fits
// over the loading part (up to the largest punch pressure), in the section's pressure range.
CompactionSummary summarise_compaction(const CompactionMonitor& mon,
                                       const std::vector<CompactionSample>& curve) {
  CompactionSummary out;
  if (curve.empty()) return out;
  std::size_t peak = 0;
  double max_force = -HUGE_VAL, max_density = -HUGE_VAL, max_radial = -HUGE_VAL, max_dv = 0.0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const CompactionSample& c = curve[i];
    if (c.punch_pressure > curve[peak].punch_pressure) peak = i;
    max_force = std::max(max_force, c.punch_force);
    max_density = std::max(max_density, c.relative_density);
    max_radial = std::max(max_radial, c.radial_pressure);
    max_dv = std::max(max_dv, std::fabs(c.volume_ratio - 1.0));
  }
  const CompactionSample &first = curve.front(), &last = curve.back();
  const double p_max = curve[peak].punch_pressure;
  const double lo = mon.spec().fit_min_pressure > 0.0 ? mon.spec().fit_min_pressure : 0.2 * p_max;
  const double hi = mon.spec().fit_max_pressure > 0.0 ? mon.spec().fit_max_pressure : p_max;
  out.values = {{"max_punch_pressure", p_max},
                {"max_punch_force", max_force},
                {"max_radial_pressure", max_radial},
                {"initial_relative_density", first.relative_density},
                {"final_relative_density", last.relative_density},
                {"max_relative_density", max_density},
                {"relative_density_at_max_pressure", curve[peak].relative_density},
                {"final_punch_displacement", last.punch_displacement},
                {"initial_solid_volume", mon.initial_solid_volume()},
                {"final_volume_change", last.volume_ratio - 1.0},
                {"max_abs_volume_change", max_dv}};
  std::vector<double> P, D, C;
  for (std::size_t i = 0; i <= peak; ++i) {
    P.push_back(curve[i].punch_pressure);
    D.push_back(curve[i].relative_density);
    C.push_back(curve[i].column_strain);
  }
  const HeckelFit h = fit_heckel(P, D, lo, hi);
  out.heckel = {{"K", h.K},
                {"A", h.A},
                {"yield_pressure", h.yield_pressure},
                {"r2", h.r2},
                {"pressure_min", lo},
                {"pressure_max", hi},
                {"points", static_cast<double>(h.points)}};
  const KawakitaFit k = fit_kawakita(P, C, lo, hi);
  out.kawakita = {{"a", k.a},           {"b", k.b},
                  {"r2", k.r2},         {"pressure_min", lo},
                  {"pressure_max", hi}, {"points", static_cast<double>(k.points)}};
  return out;
}

// tools/plot_compaction.py OUT_DIR with the system python (which has Debian's matplotlib),
// else the python3 on the PATH; its output goes to run.log only. Plots are a convenience: a
// missing python or matplotlib is a note, not a failure of the run.
void plot_compaction(const RunOptions& options, const std::filesystem::path& out, RunLog& log) {
  auto quote = [](const std::string& s) {  // for sh: '...' with each ' written as '\''
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  int code = 127;
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    if (python[0] == '/' && !std::filesystem::exists(python)) continue;
    const std::string cmd = std::string(python) + " " + quote(options.plot_script) + " " +
                            quote(out.string()) + " >> " + quote((out / "run.log").string()) +
                            " 2>&1";
    const int status = std::system(cmd.c_str());
    code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : 127;
    if (code != 127) break;
  }
  if (code == 0)
    log.say("plots: compaction_curve.png, force_displacement.png, heckel.png");
  else
    log.say("note: no compaction plots (" + options.plot_script + " exited with " +
            std::to_string(code) + "; see run.log)");
}

}  // namespace

int run_scene(const SceneFile& scene, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  ModelSpec spec = scene.model;
  int threads = options.threads >= 0 ? options.threads : spec.simulation.threads;
#ifdef _OPENMP
  if (threads <= 0) threads = omp_get_num_procs();
  omp_set_num_threads(threads);
#else
  threads = 1;
#endif
  SimulationSettings& set = spec.simulation;
  if (set.output_interval <= 0.0) set.output_interval = set.end_time / 50.0;
  if (set.history_interval <= 0.0) set.history_interval = set.output_interval / 20.0;

  // Everything that can fail on bad input happens before the first file is written.
  Model model = build_model(spec);
  Simulation sim(std::move(model));
  const Model& m = sim.model();
  const double setup_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const std::filesystem::path out = options.out_dir;
  std::filesystem::create_directories(out);
  // A summary from an earlier run must not sit next to this run's partial outputs.
  std::filesystem::remove(out / "summary.json");
  RunLog log(out / "run.log", options.quiet);
  {
    std::ostringstream head;
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
    head << "femdem " << FEMDEM_VERSION << " (" << FEMDEM_GIT_REVISION << "), " << date << "\n"
         << "command: " << options.command_line << "\n"
         << "scene: " << scene.path << "\n\n# resolved scene\n"
         << scene.resolved_toml << "\n# end of resolved scene\n\n";
    log.file_only(head.str());
  }
  log.say("femdem " + std::string(FEMDEM_VERSION) + ": " +
          (m.title.empty() ? scene.stem : m.title));
  for (const auto& note : scene.notes) log.say(note);
  {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%d bodies, %d nodes, %d TET10 elements, %d walls; %d thread%s",
                  static_cast<int>(m.bodies.size()), m.node_count, m.element_count,
                  static_cast<int>(m.walls.size()), threads, threads == 1 ? "" : "s");
    log.say(buf);
    std::snprintf(buf, sizeof buf,
                  "stable time step %.4g s, step %.4g s; end time %.4g s (about %.0f steps)",
                  sim.stable_dt(), sim.dt(), set.end_time, set.end_time / sim.dt());
    log.say(buf);
    if (set.time_step > 0.0 && set.time_step > sim.stable_dt())
      log.say(
          "warning: simulation.time_step exceeds the stable step estimate; the run may diverge");
  }

  // Outputs
  std::vector<std::string> body_names, wall_names;
  for (const auto& b : m.bodies) body_names.push_back(b.name);
  for (const auto& w : m.walls) wall_names.push_back(w.name);
  ResultsWriter results(out, ResultsMesh{m.X, m.conn, m.node_body, m.element_body, body_names});
  std::optional<CompactionMonitor> compaction;
  if (spec.compaction) compaction.emplace(sim, *spec.compaction);
  std::vector<std::string> columns = standard_history_columns(body_names, wall_names);
  const bool body_contact = sim.body_contact().active();
  if (body_contact) columns.push_back("contact.max_penetration");
  if (compaction)
    for (std::string& c : compaction_columns()) columns.push_back(std::move(c));
  HistoryWriter history(out / "history.csv", std::move(columns));
  // the compaction curve, kept for the fits and extremes of summary.json
  std::vector<CompactionSample> curve;
  double compaction_time = 0.0;  // wall time spent on the compaction columns (PERFORMANCE.md)
  if (compaction)
    curve.reserve(static_cast<std::size_t>(std::min(1e6, set.end_time / set.history_interval)) + 2);
  std::vector<double> disp(m.X.size()), s6, vm, pr, ep, row;
  auto write_frame = [&]() {
    for (std::size_t i = 0; i < disp.size(); ++i) disp[i] = m.x[i] - m.X[i];
    sim.element_stress(s6, vm, pr, ep);
    results.write_frame(sim.time(), FrameFields{disp, m.v, s6, vm, pr, ep});
  };
  std::vector<RestitutionTracker> restitution(m.bodies.size());
  // the run's largest principal stress per body, and when, sampled with the history rows
  std::vector<double> peak_principal(m.bodies.size(), -HUGE_VAL),
      peak_principal_time(m.bodies.size(), 0.0);
  // the deepest overlap between bodies over the run, sampled with the history rows
  double peak_penetration = 0.0, peak_penetration_time = 0.0;
  // stop at rest: the peak kinetic energy so far and since when it has been below the threshold
  double peak_kinetic = 0.0, peak_kinetic_time = 0.0, below_since = -1.0, rest_time = -1.0;
  const double rest_hold = set.rest_hold_time > 0.0 ? set.rest_hold_time : set.output_interval;
  auto write_history = [&]() {
    const Energies e = sim.energies();
    row.assign({sim.time(), sim.dt(), e.kinetic, e.internal, e.plastic_dissipation, e.contact,
                e.contact_dissipation, e.viscous_dissipation, e.mass_scaling_dissipation,
                e.external_work, e.balance(), sim.balance_error()});
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const BodyState s = sim.body_motion(static_cast<int>(b));
      const double principal = sim.max_principal_stress(static_cast<int>(b));
      if (principal > peak_principal[b])
        peak_principal[b] = principal, peak_principal_time[b] = sim.time();
      row.insert(row.end(), {s.com.x(), s.com.y(), s.com.z(), s.vcom.x(), s.vcom.y(), s.vcom.z(),
                             s.kinetic_energy, s.contact_force.x(), s.contact_force.y(),
                             s.contact_force.z(), principal});
    }
    for (std::size_t w = 0; w < m.walls.size(); ++w) {
      const Vec3 f = sim.wall_force(static_cast<int>(w)),
                 p = sim.wall_position(static_cast<int>(w));
      row.insert(row.end(), {f.x(), f.y(), f.z(), p.x(), p.y(), p.z()});
    }
    if (body_contact) {
      const double d = sim.body_contact().max_penetration();
      if (d > peak_penetration) peak_penetration = d, peak_penetration_time = sim.time();
      row.push_back(d);
    }
    if (set.rest_kinetic_fraction > 0.0) {
      if (e.kinetic > peak_kinetic) peak_kinetic = e.kinetic, peak_kinetic_time = sim.time();
      if (peak_kinetic > 0.0 && e.kinetic < set.rest_kinetic_fraction * peak_kinetic) {
        if (below_since < 0.0) below_since = sim.time();
        if (sim.time() - below_since >= rest_hold * (1.0 - 1e-9)) rest_time = sim.time();
      } else {
        below_since = -1.0;
      }
    }
    if (compaction) {
      const auto t0 = std::chrono::steady_clock::now();
      const CompactionSample c = compaction->sample(sim);
      compaction_time +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      curve.push_back(c);
      double v[12];
      CompactionMonitor::values(c, v);
      row.insert(row.end(), v, v + 12);
    }
    history.write_row(row);
  };

  auto loop_start = std::chrono::steady_clock::now();
  RunSummary summary;
  summary.scene = scene.path;
  summary.threads = threads;
  summary.nodes = m.node_count;
  summary.elements = m.element_count;
  auto finish_summary = [&](RunStatus status) {
    summary.status = status;
    summary.end_time = sim.time();
    summary.steps = sim.steps();
    summary.time_step = sim.dt();
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const Energies e = sim.energies();
    summary.extra["setup_time_s"] = setup_time;
    summary.extra["loop_time_s"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    summary.extra["stable_time_step"] = sim.stable_dt();
    if (set.rest_kinetic_fraction > 0.0) {
      // the threshold too, so tools reading the run need not know the scene
      summary.extra["rest_kinetic_fraction"] = set.rest_kinetic_fraction;
      summary.extra["peak_kinetic_energy"] = peak_kinetic;
      summary.extra["peak_kinetic_energy_time"] = peak_kinetic_time;
      if (rest_time >= 0.0) summary.extra["at_rest_time"] = rest_time;
    }
    if (sim.body_contact().active()) {
      summary.extra["broadphase_runs"] = static_cast<double>(sim.body_contact().broadphase_runs());
      summary.extra["contact_pair_evaluations"] =
          static_cast<double>(sim.body_contact().pair_evaluations());
      summary.extra["contact_touching_pair_evaluations"] =
          static_cast<double>(sim.body_contact().touching_evaluations());
      summary.extra["contact_max_penetration"] = peak_penetration;
      summary.extra["contact_max_penetration_time"] = peak_penetration_time;
      summary.extra["contact_final_max_penetration"] = sim.body_contact().max_penetration();
      summary.extra["contact_sub_tet_min_edge"] = m.contact_tet_min_edge;
    }
    summary.energy = {.kinetic = e.kinetic,
                      .internal = e.internal,
                      .plastic_dissipation = e.plastic_dissipation,
                      .contact = e.contact,
                      .contact_dissipation = e.contact_dissipation,
                      .viscous_dissipation = e.viscous_dissipation,
                      .mass_scaling_dissipation = e.mass_scaling_dissipation,
                      .external_work = e.external_work,
                      .balance_error = sim.balance_error()};
    if (compaction) {
      summary.compaction = summarise_compaction(*compaction, curve);
      summary.extra["compaction_time_s"] = compaction_time;
    }
    summary.bodies.clear();
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const BodyState s = sim.body_state(static_cast<int>(b));
      BodySummary bs;
      bs.name = m.bodies[b].name;
      bs.mass = s.mass;
      bs.added_mass = s.added_mass;
      bs.volume = s.volume;
      bs.com = {s.com.x(), s.com.y(), s.com.z()};
      bs.vcom = {s.vcom.x(), s.vcom.y(), s.vcom.z()};
      bs.angular_velocity = {s.angular_velocity.x(), s.angular_velocity.y(),
                             s.angular_velocity.z()};
      bs.kinetic_energy = s.kinetic_energy;
      bs.bbox_min = {s.bbox_min.x(), s.bbox_min.y(), s.bbox_min.z()};
      bs.bbox_max = {s.bbox_max.x(), s.bbox_max.y(), s.bbox_max.z()};
      // equivalent plastic strain never decreases: its value now is the run's maximum
      bs.max_equivalent_plastic_strain = s.max_equivalent_plastic_strain;
      bs.max_principal_stress = peak_principal[b];
      bs.max_principal_stress_time = peak_principal_time[b];
      bs.coefficient_of_restitution = restitution[b].result();
      summary.bodies.push_back(bs);
    }
    write_summary(out / "summary.json", summary);
  };

  g_stop_signal = 0;
  auto old_int = std::signal(SIGINT, on_stop_signal);
  auto old_term = std::signal(SIGTERM, on_stop_signal);
  struct RestoreSignals {
    void (*i)(int);
    void (*t)(int);
    ~RestoreSignals() { std::signal(SIGINT, i), std::signal(SIGTERM, t); }
  } restore{old_int, old_term};

  const bool tty = !options.quiet && isatty(STDOUT_FILENO);
  auto last_report = std::chrono::steady_clock::now();
  loop_start = last_report;
  std::int64_t steps_at_report = 0;
  double next_frame = set.output_interval, next_history = set.history_interval;
  const double end = set.end_time;
  const double eps = 1e-9 * end;
  try {
    write_frame();
    for (std::size_t b = 0; b < m.bodies.size(); ++b)
      restitution[b].update(sim.body_motion(static_cast<int>(b)));
    write_history();
    while (sim.time() < end - eps) {
      // land on end_time exactly rather than a fraction of a step past it
      const double remaining = end - sim.time();
      sim.step(remaining < 1.5 * sim.dt() ? (remaining > sim.dt() ? 0.5 * remaining : remaining)
                                          : HUGE_VAL);
      for (std::size_t b = 0; b < m.bodies.size(); ++b)
        restitution[b].update(sim.body_motion(static_cast<int>(b)));
      if (sim.time() >= next_history - eps || sim.time() >= end - eps) {
        write_history();
        while (next_history <= sim.time() + eps) next_history += set.history_interval;
      }
      if (sim.time() >= next_frame - eps || sim.time() >= end - eps || rest_time >= 0.0) {
        write_frame();
        while (next_frame <= sim.time() + eps) next_frame += set.output_interval;
      }
      if (g_stop_signal != 0 || rest_time >= 0.0) break;
      if ((sim.steps() & 15) == 0 && !options.quiet) {
        const auto now = std::chrono::steady_clock::now();
        const double since = std::chrono::duration<double>(now - last_report).count();
        if (since >= (tty ? 0.5 : 30.0)) {
          const double elapsed = std::chrono::duration<double>(now - loop_start).count();
          const double rate = (sim.steps() - steps_at_report) / since;
          const double eta = elapsed * (end - sim.time()) / std::max(sim.time(), 1e-300);
          char buf[200];
          std::snprintf(buf, sizeof buf,
                        "t = %.4g / %.4g s (%3.0f%%)  %lld steps  %.0f steps/s  ETA %s", sim.time(),
                        end, 100.0 * sim.time() / end, static_cast<long long>(sim.steps()), rate,
                        format_duration(eta).c_str());
          if (tty)
            std::printf("\r%s   ", buf), std::fflush(stdout);
          else
            std::printf("%s\n", buf), std::fflush(stdout);
          last_report = now;
          steps_at_report = sim.steps();
        }
      }
    }
  } catch (const InstabilityError& e) {
    if (tty) std::printf("\n");
    history.close();
    results.close(false);
    finish_summary(RunStatus::unstable);
    log.error(std::string("error: the simulation became unstable: ") + e.what());
    throw;
  }
  if (tty) std::printf("\r%*s\r", 100, ""), std::fflush(stdout);
  history.close();
  if (g_stop_signal != 0) {
    results.close(false);
    finish_summary(RunStatus::interrupted);
    log.say("interrupted by signal " + std::to_string(g_stop_signal.load()) +
            " at t = " + std::to_string(sim.time()) + " s; the frames written so far are readable");
    return 1;
  }
  results.close(true);
  finish_summary(RunStatus::completed);
  char buf[300];
  if (set.rest_kinetic_fraction > 0.0) {
    if (rest_time >= 0.0)
      std::snprintf(buf, sizeof buf,
                    "at rest at t = %.4g s: the kinetic energy stayed below %.3g of its peak "
                    "(%.4g J at t = %.4g s) for %.4g s",
                    rest_time, set.rest_kinetic_fraction, peak_kinetic, peak_kinetic_time,
                    rest_hold);
    else
      std::snprintf(buf, sizeof buf,
                    "warning: not at rest by the end time: kinetic energy %.4g J, %.3g of its "
                    "peak (%.4g J at t = %.4g s)",
                    sim.energies().kinetic,
                    peak_kinetic > 0.0 ? sim.energies().kinetic / peak_kinetic : 0.0, peak_kinetic,
                    peak_kinetic_time);
    log.say(buf);
  }
  std::snprintf(buf, sizeof buf,
                "done: %lld steps in %s (%.3g element updates/s); energy balance error %.3g %%",
                static_cast<long long>(sim.steps()), format_duration(summary.wall_time_s).c_str(),
                static_cast<double>(sim.steps()) * m.element_count / summary.wall_time_s,
                100.0 * sim.balance_error());
  log.say(buf);
  if (set.mass_scaling_time_step > 0.0) {
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const BodyState s = sim.body_motion(static_cast<int>(b));
      const double fraction = s.added_mass / s.mass;
      std::snprintf(buf, sizeof buf,
                    "%smass scaling added %.3g kg to body '%s' (%.3g %% of its mass)",
                    fraction > 0.01 ? "warning: " : "", s.added_mass, m.bodies[b].name.c_str(),
                    100.0 * fraction);
      log.say(buf);
    }
  }
  log.say("results in " + out.string() + ": results.xdmf (ParaView), history.csv, summary.json");
  if (compaction && !options.plot_script.empty()) plot_compaction(options, out, log);
  return 0;
}

}  // namespace femdem
