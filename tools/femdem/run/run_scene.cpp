// SPDX-License-Identifier: GPL-3.0-or-later
// The run loop: step, observe, write on schedule, stop at the end, at rest, on a signal or when
// the simulation diverges. What it observes and writes lives beside it: output_schedule.hpp,
// history_sample.hpp and output_tables.hpp (the rows), the monitors (restitution, rest, peaks,
// compaction curve), run_summary.hpp, progress_line.hpp and run_log.hpp.
#include "tools/femdem/run/run_scene.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <sstream>
#include <vector>

#include "engine/compaction.hpp"
#include "engine/distributed/communicator.hpp"
#include "engine/errors.hpp"
#include "engine/initial_overlap.hpp"
#include "engine/output_fields.hpp"
#include "engine/simulation.hpp"
#include "femdem_version.hpp"
#include "io/checkpoint/checkpoint_file.hpp"
#include "io/results/history_writer.hpp"
#include "io/results/results_writer.hpp"
#include "io/results/summary_writer.hpp"
#include "io/results/wall_patch.hpp"
#include "io/scene/scene_digest.hpp"
#include "tools/femdem/run/compaction_curve.hpp"
#include "tools/femdem/run/memory_check.hpp"
#include "tools/femdem/run/output_folder.hpp"
#include "tools/femdem/run/output_schedule.hpp"
#include "tools/femdem/run/output_tables.hpp"
#include "tools/femdem/run/peak_monitor.hpp"
#include "tools/femdem/run/plot_script.hpp"
#include "tools/femdem/run/progress_line.hpp"
#include "tools/femdem/run/rank_group.hpp"
#include "tools/femdem/run/rest_monitor.hpp"
#include "tools/femdem/run/restitution_monitor.hpp"
#include "tools/femdem/run/run_checkpoint.hpp"
#include "tools/femdem/run/run_log.hpp"
#include "tools/femdem/run/run_summary.hpp"
#include "tools/femdem/run/thread_count.hpp"

namespace femdem {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::atomic<int> g_stop_signal{0};
extern "C" void on_stop_signal(int sig) {
  g_stop_signal = sig;
}

// SIGINT and SIGTERM end the run after the current step (the handlers are restored on leaving).
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal = 0;
    old_int_ = std::signal(SIGINT, on_stop_signal);
    old_term_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~StopSignals() { std::signal(SIGINT, old_int_), std::signal(SIGTERM, old_term_); }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return g_stop_signal.load(); }

 private:
  void (*old_int_)(int);
  void (*old_term_)(int);
};

void write_log_header(RunLog& log, const SceneFile& scene, const RunOptions& options) {
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

void say_model(RunLog& log, const SceneFile& scene, const Simulation& sim, int threads,
               const RankGroup* ranks) {
  const Model& m = sim.model();
  const SimulationSettings& set = m.settings;
  log.say("femdem " + std::string(FEMDEM_VERSION) + ": " +
          (m.title.empty() ? scene.stem : m.title));
  for (const auto& note : scene.notes) log.say(note);
  char buf[256];
  std::snprintf(buf, sizeof buf, "%d bodies, %d nodes, %d TET10 elements, %d walls; %d thread%s",
                static_cast<int>(m.bodies.size()), m.node_count, m.element_count,
                static_cast<int>(m.walls.size()), threads, threads == 1 ? "" : "s");
  if (!ranks) {
    log.say(buf);
  } else {
    log.say(std::string(buf) + " in each of " + std::to_string(ranks->ranks()) + " ranks (MPI)");
    // what the ranks exchange every step: the ghost nodes' positions and velocities
    std::int64_t sent = 0, most = 0;
    for (const std::int64_t n : ranks->ghosts_sent()) sent += n, most = std::max(most, n);
    std::snprintf(buf, sizeof buf,
                  "ghost nodes sent a step: %lld in all (%.4g kB), at most %lld by one rank",
                  static_cast<long long>(sent), 48e-3 * static_cast<double>(sent),
                  static_cast<long long>(most));
    log.say(buf);
  }
  // which element kernel: what a user needs to read the run's element-update rate
  const std::int64_t simd = sim.element_pass().simd_elements();
  std::snprintf(
      buf, sizeof buf, "element update: SIMD (%s) for %lld of %d elements%s",
      element_update_target().c_str(), static_cast<long long>(simd), m.element_count,
      simd < m.element_count ? ", the scalar kernel for the rest (nodal or sub_tet F-bar)" : "");
  log.say(buf);
  std::snprintf(buf, sizeof buf,
                "stable time step %.4g s, step %.4g s; end time %.4g s (about %.0f steps)",
                sim.stable_dt(), sim.dt(), set.end_time, set.end_time / sim.dt());
  log.say(buf);
  if (set.time_step > 0.0 && set.time_step > sim.stable_dt())
    log.say("warning: simulation.time_step exceeds the stable step estimate; the run may diverge");
}

// The closing lines of a completed run: rest, rate and balance, mass scaling, where to look.
void say_outcome(RunLog& log, const Simulation& sim, const RestMonitor& rest, double wall_time_s,
                 const std::filesystem::path& out) {
  const Model& m = sim.model();
  char buf[300];
  if (rest.enabled()) {
    if (rest.at_rest())
      std::snprintf(buf, sizeof buf,
                    "at rest at t = %.4g s: the kinetic energy stayed below %.3g of its peak "
                    "(%.4g J at t = %.4g s) for %.4g s",
                    rest.rest_time(), rest.fraction(), rest.peak(), rest.peak_time(), rest.hold());
    else
      std::snprintf(buf, sizeof buf,
                    "warning: not at rest by the end time: kinetic energy %.4g J, %.3g of its "
                    "peak (%.4g J at t = %.4g s)",
                    sim.energies().kinetic,
                    rest.peak() > 0.0 ? sim.energies().kinetic / rest.peak() : 0.0, rest.peak(),
                    rest.peak_time());
    log.say(buf);
  }
  std::snprintf(buf, sizeof buf,
                "done: %lld steps in %s (%.3g element updates/s); energy balance error %.3g %%",
                static_cast<long long>(sim.steps()), format_duration(wall_time_s).c_str(),
                static_cast<double>(sim.steps()) * m.element_count / wall_time_s,
                100.0 * sim.balance_error());
  log.say(buf);
  if (m.settings.mass_scaling_time_step > 0.0) {
    // One line in all, then the bodies that gained mass, most first (a packing has hundreds of
    // bodies, most of which gain none).
    double added = 0.0, mass = 0.0;
    struct Gain {
      double fraction, kg;
      std::size_t body;
    };
    std::vector<Gain> gained;
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      const BodyState s = sim.body_motion(static_cast<int>(b));
      added += s.added_mass;
      mass += s.mass;
      if (s.added_mass > 0.0) gained.push_back({s.added_mass / s.mass, s.added_mass, b});
    }
    std::snprintf(buf, sizeof buf,
                  "mass scaling added %.3g kg (%.3g %% of the mass) to %zu of %zu bodies", added,
                  mass > 0.0 ? 100.0 * added / mass : 0.0, gained.size(), m.bodies.size());
    log.say(buf);
    std::stable_sort(gained.begin(), gained.end(),
                     [](const Gain& a, const Gain& b) { return a.fraction > b.fraction; });
    constexpr std::size_t kListed = 10;
    for (std::size_t i = 0; i < std::min(gained.size(), kListed); ++i) {
      const Gain& g = gained[i];
      std::snprintf(buf, sizeof buf, "  body '%s': %.3g kg (%.3g %% of its mass)%s",
                    m.bodies[g.body].name.c_str(), g.kg, 100.0 * g.fraction,
                    g.fraction > 0.01 ? " - warning: more than 1 %" : "");
      log.say(buf);
    }
    if (gained.size() > kListed) {
      std::snprintf(buf, sizeof buf, "  and %zu more bodies (summary.json: bodies.*.added_mass)",
                    gained.size() - kListed);
      log.say(buf);
    }
  }
  log.say("results in " + out.string() + ": results.xdmf (ParaView), history.csv, summary.json");
}

void warn_overlap(RunLog& log, const Model& m, const PeakMonitor& peaks) {
  char buf[400];
  const bool wall = peaks.wall_penetration_per_size() > peaks.penetration_per_size();
  const std::string where =
      wall ? "behind wall '" + m.walls[peaks.wall_penetration_per_size_wall()].name + "'"
           : std::string("between bodies");
  std::snprintf(buf, sizeof buf,
                "warning: an overlap %s reached %.3g of the element size at t = %.4g s (more than "
                "%.3g): the contact is soft for this load. Set a stiffer penalty_factor (%s), "
                "refine the contact surfaces, or check the loading.",
                where.c_str(),
                wall ? peaks.wall_penetration_per_size() : peaks.penetration_per_size(),
                wall ? peaks.wall_penetration_per_size_time() : peaks.penetration_per_size_time(),
                kOverlapWarning, wall ? "walls.<name> or [contact]" : "[contact]");
  log.say(buf);
}

void plot_compaction(const std::string& script, const std::filesystem::path& out, RunLog& log) {
  const int code = run_plot_script(script, out, out / "run.log");
  if (code == 0)
    log.say("plots: compaction_curve.png, force_displacement.png, heckel.png");
  else
    log.say("note: no compaction plots (" + script + " exited with " + std::to_string(code) +
            "; see run.log)");
}

// How a run starts: afresh, or from the checkpoint in its folder (femdem resume).
struct ResumePoint {
  CheckpointInfo info;
  bool rearm_rest = false;  // the resume changed the rest criteria: look for rest anew
};

std::string version_text() {
  return std::string(FEMDEM_VERSION) + " (" + FEMDEM_GIT_REVISION + ")";
}

void say_resumed(RunLog& log, const RunOptions& options, const ResumePoint& r, double read_s) {
  std::ostringstream head;
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  head << "\n# resumed\nfemdem " << version_text() << ", " << date << "\n"
       << "command: " << options.command_line << "\n";
  log.file_only(head.str());
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "resumed from %s at t = %.6g s, step %lld (written by femdem %s, read in %.3g s); "
                "the history rows and frames after it are replaced",
                kCheckpointFile, r.info.time, static_cast<long long>(r.info.step),
                r.info.femdem_version.c_str(), read_s);
  log.say(buf);
  if (r.info.femdem_version != version_text())
    log.say("warning: the checkpoint was written by another femdem (" + r.info.femdem_version +
            "); the steps after it may differ in the last bits from an uninterrupted run");
}

int execute(const SceneFile& scene, RunOrigin origin, const RunOptions& options,
            const ResumePoint* resume) {
  const auto wall_start = Clock::now();
  ModelSpec spec = scene.model;
  const int threads =
      use_threads(options.threads, spec.simulation.threads, Communicator::world().size_here());
  SimulationSettings& set = spec.simulation;
  if (set.output_interval <= 0.0) set.output_interval = set.end_time / 50.0;
  if (set.history_interval <= 0.0) set.history_interval = set.output_interval / 20.0;

  // Everything that can fail on bad input happens before the first file is written.
  check_memory(spec);
  Model whole_model = build_model(spec);
  // On several ranks (mpirun), every rank steps a part; rank 0 goes on below with the whole
  // model's Simulation as the view that is written, the others follow its commands.
  std::optional<RankGroup> ranks;
  if (const Communicator& world = Communicator::world(); world.size() > 1) {
    ranks.emplace(whole_model, world);
    // (the compaction columns' solid volume: summed by all ranks at each history row)
    if (spec.compaction)
      ranks->measure_volume_of(CompactionMonitor::powder_of(whole_model, *spec.compaction));
    if (world.rank() != 0) {
      whole_model = Model{};      // (only rank 0 keeps the whole model)
      const StopSignals signals;  // (rank 0 decides when to stop)
      ranks->follow();
      return 0;
    }
  }
  Simulation sim(std::move(whole_model));
  if (!resume) check_initial_overlap(sim);  // (a resumed run passed it when it started)
  const Model& m = sim.model();
  const std::filesystem::path out = options.out_dir;
  const std::filesystem::path checkpoint_path = out / kCheckpointFile;
  const std::string digest = scene_digest(scene.resolved_toml);
  origin.resolved_toml = scene.resolved_toml;

  HistoryLayout layout;
  for (const auto& b : m.bodies) layout.bodies.push_back(b.name);
  for (const auto& w : m.walls) layout.walls.push_back(w.name);
  layout.body_contact = sim.body_contact().active();
  layout.compaction = spec.compaction.has_value();
  OutputSchedule schedule(set.end_time, set.output_interval, set.history_interval);

  // monitors
  std::vector<RestitutionMonitor> restitution(m.bodies.size());
  PeakMonitor peaks(m.bodies.size());
  RestMonitor rest(set.rest_kinetic_fraction,
                   set.rest_hold_time > 0.0 ? set.rest_hold_time : set.output_interval);
  std::optional<CompactionMonitor> compaction;
  std::optional<CompactionCurve> curve;
  if (spec.compaction) {
    compaction.emplace(sim, *spec.compaction);
    curve.emplace(*compaction, set.end_time / set.history_interval);
  }

  // What a checkpoint holds, saved and loaded by the same function: the engine, the monitors,
  // the outputs' counts and the run's origin.
  OutputCounts counts;
  double earlier_wall_s = 0.0, earlier_loop_s = 0.0;  // of the run before this resume
  auto loop_start = Clock::now();
  auto exchange_run = [&](StateArchive& a) {
    sim.exchange_state(a);
    const StateArchive::Scope scope(a, "run");
    RunOrigin stored = origin;
    exchange_origin(a, stored);
    schedule.exchange_state(a);
    peaks.exchange_state(a);
    rest.exchange_state(a);
    for (std::size_t b = 0; b < restitution.size(); ++b) {
      const StateArchive::Scope body(a, "restitution/" + std::to_string(b));
      restitution[b].exchange_state(a);
    }
    if (compaction) {
      compaction->exchange_state(a);
      curve->exchange_state(a);
    }
    counts.exchange_state(a);
    double wall_s = earlier_wall_s + seconds_since(wall_start);
    double loop_s = earlier_loop_s + seconds_since(loop_start);
    a.value("wall_time_s", wall_s);
    a.value("loop_time_s", loop_s);
    if (!a.saving()) earlier_wall_s = wall_s, earlier_loop_s = loop_s;
  };
  double read_time_s = 0.0;
  if (resume) {
    try {
      const auto t0 = Clock::now();
      read_checkpoint(checkpoint_path, exchange_run);
      if (ranks) ranks->scatter(sim);
      read_time_s = seconds_since(t0);
    } catch (const CheckpointError& e) {
      throw InputError(e.what(), checkpoint_path.string());
    }
    if (resume->rearm_rest) rest.rearm();
  }
  const double setup_time = seconds_since(wall_start);

  // outputs: a new run replaces what an earlier run left in the folder; a resumed run cuts its
  // outputs back to the checkpoint (checking all of them before changing any)
  std::vector<ResultsWall> result_walls;
  {
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
    for (std::size_t i = 0; i + 2 < m.X.size(); i += 3) {
      const Vec3 p(m.X[i], m.X[i + 1], m.X[i + 2]);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    for (const Wall& w : m.walls) result_walls.push_back({w.name, w.normal, wall_patch(w, lo, hi)});
  }
  const ResultsMesh mesh{m.X, m.conn, m.node_body, m.element_body, layout.bodies, result_walls};
  std::optional<ResultsWriter> results;
  std::optional<HistoryWriter> history;
  std::optional<RunLog> log_file;
  std::optional<OutputFolderLock> lock;
  if (!resume) {
    lock.emplace(out, options.command_line);
    if (!options.force) check_new_run_folder(out.string(), false);  // (another run since?)
    // A summary or checkpoint from an earlier run must not sit next to this run's outputs.
    std::filesystem::remove(out / "summary.json");
    std::filesystem::remove(checkpoint_path);
    log_file.emplace(out / "run.log", options.quiet);
    write_log_header(*log_file, scene, options);
    say_model(*log_file, scene, sim, threads, ranks ? &*ranks : nullptr);
    results.emplace(out, mesh,
                    ResultsOptions{.scene_digest = digest,
                                   .expected_frames = 1 + schedule.frames_after(sim.time()),
                                   .optional_fields = set.output_fields});
    history.emplace(out / "history.csv", history_columns(layout));
  } else {
    const HistoryWriter::ContinueAt at{counts.history_bytes, counts.history_rows};
    lock.emplace(out, options.command_line);
    try {
      HistoryWriter::check_continuable(out / "history.csv", history_columns(layout), at);
      results.emplace(
          out, mesh, ResultsWriter::ContinueFrom{counts.frames},
          ResultsOptions{.scene_digest = digest,
                         .expected_frames = counts.frames + schedule.frames_after(sim.time()),
                         .optional_fields = set.output_fields});
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("cannot resume: ") + e.what(), out.string());
    }
    history.emplace(out / "history.csv", history_columns(layout), at);
    std::filesystem::remove(out / "summary.json");
    log_file.emplace(out / "run.log", options.quiet, /*append=*/true);
    say_resumed(*log_file, options, *resume, read_time_s);
    say_model(*log_file, scene, sim, threads, ranks ? &*ranks : nullptr);
  }
  RunLog& log = *log_file;

  std::vector<double> disp(m.X.size()), row;
  ElementStressFigures stress;  // each frame's
  std::vector<double> wall_disp(3 * m.walls.size()), wall_force(3 * m.walls.size());
  // the optional fields (engine/output_fields.hpp), computed only when the scene asks
  const auto wants = [&](const char* name) {
    return std::find(set.output_fields.begin(), set.output_fields.end(), name) !=
           set.output_fields.end();
  };
  std::optional<OutputFields> optional_fields;
  if (!set.output_fields.empty()) optional_fields.emplace(m);
  std::vector<double> log_strain, nodal_stress, contact_pressure, body_velocity;
  auto write_frame = [&] {
    // the rows up to this frame reach the file first: a killed run loses no row a frame has
    history->flush();
    if (ranks)  // (each element's figures computed by its rank: 9 numbers an element gathered)
      ranks->gather(sim, GatheredState::frame, &stress);
    else
      sim.element_stress(stress.stress6, stress.von_mises, stress.pressure, stress.plastic_strain);
    for (std::size_t i = 0; i < disp.size(); ++i) disp[i] = m.x[i] - m.X[i];
    for (std::size_t w = 0; w < m.walls.size(); ++w)
      for (int k = 0; k < 3; ++k) {
        wall_disp[3 * w + k] = m.walls[w].point[k] - m.walls[w].point0[k];
        wall_force[3 * w + k] = m.walls[w].force[k];
      }
    FrameFields fields{disp,
                       m.v,
                       stress.stress6,
                       stress.von_mises,
                       stress.pressure,
                       stress.plastic_strain,
                       wall_disp,
                       wall_force};
    if (optional_fields) {
      if (wants("log_strain")) optional_fields->log_strain(m, log_strain);
      if (wants("nodal_stress")) optional_fields->nodal_stress(m, stress.stress6, nodal_stress);
      if (wants("contact_pressure")) optional_fields->contact_pressure(m, contact_pressure);
      if (wants("body_velocity")) optional_fields->body_velocity(m, body_velocity);
      fields.log_strain = log_strain;
      fields.nodal_stress = nodal_stress;
      fields.contact_force = m.f_contact;
      fields.contact_pressure = contact_pressure;
      fields.body_velocity = body_velocity;
    }
    results->write_frame(sim.time(), fields);
    schedule.frame_written(sim.time());
  };
  HistorySample sample;
  auto write_history = [&] {
    if (ranks)
      ranks->sample(sample);
    else
      take_sample(sim, sample);
    if (compaction) {
      const auto t0 = Clock::now();
      // (on ranks: the walls as every part has them, the volume the ranks summed)
      sample.compaction = ranks ? compaction->sample(ranks->part(), ranks->powder_volume())
                                : compaction->sample(sim, sim.bodies_volume(compaction->powder()));
      curve->sample_time_s += seconds_since(t0);
      curve->observe(*sample.compaction);
    }
    peaks.observe(sample);
    if (peaks.overlap_warning_due()) warn_overlap(log, m, peaks);
    rest.observe(sample.time, sample.energies.kinetic);
    history_row(sample, row);
    history->write_row(row);
    schedule.history_written(sim.time());
  };
  std::vector<BodyState> motions;
  double most_imbalance = 0.0;  // (distributed runs: rebalancing's checks)
  int redealings = 0;
  auto observe_step = [&] {
    if (ranks)
      ranks->body_motions(motions);
    else
      sim.body_motions(motions);
    for (std::size_t b = 0; b < m.bodies.size(); ++b) restitution[b].observe(motions[b]);
  };

  // checkpoints: periodically, before the last steps (the point a later end time extends the
  // run from), at rest and on a signal
  CheckpointClock clock(set.checkpoint_interval, set.checkpoint_wall_interval, sim.time());
  std::optional<CheckpointSummary> last_checkpoint;
  double checkpoint_time_s = 0.0;
  std::int64_t checkpoints = 0;
  auto write_checkpoint_now = [&] {
    const auto t0 = Clock::now();
    history->flush();
    if (ranks) ranks->gather(sim, GatheredState::everything);
    counts = {history->bytes_written(), history->rows(), results->frame_count()};
    const CheckpointInfo info{kCheckpointFormat, version_text(), digest, sim.time(), sim.steps()};
    write_checkpoint(checkpoint_path, info, exchange_run);
    clock.written(sim.time());
    last_checkpoint = CheckpointSummary{checkpoint_path.string(), sim.time(), sim.steps(),
                                        "femdem resume " + out.string()};
    checkpoint_time_s += seconds_since(t0);
    ++checkpoints;
  };

  auto finish_summary = [&](RunStatus status) {
    // (the summary reads the whole model's state now)
    if (ranks) ranks->gather(sim, GatheredState::outputs);
    const RunRecord record{.sim = sim,
                           .setup_time_s = setup_time,
                           .loop_time_s = earlier_loop_s + seconds_since(loop_start),
                           .rest = rest,
                           .peaks = peaks,
                           .compaction = curve ? &*curve : nullptr};
    const RunIdentity id{scene.path, threads, earlier_wall_s + seconds_since(wall_start)};
    RunSummary summary = make_run_summary(record, id, restitution, status);
    summary.checkpoint = last_checkpoint;
    write_summary(out / "summary.json", summary);
    return summary;
  };

  const StopSignals signals;
  ProgressLine progress(options.quiet, set.end_time, sim);
  loop_start = Clock::now();
  bool before_last_steps = false;
  try {
    if (!resume) {
      // the initial state is frame 0 and history row 0 (the schedule's first due times are one
      // interval on)
      write_frame();
      observe_step();
      write_history();
    }
    // (a run resumed from its checkpoint at rest, with the same criteria, is done)
    while (!schedule.finished(sim.time()) && !rest.at_rest()) {
      const double limit = schedule.step_limit(sim.time(), sim.dt());
      if (limit < sim.dt() && !before_last_steps) {
        // the state a resume with a later end time continues from, as the longer run has it
        write_checkpoint_now();
        before_last_steps = true;
      }
      if (ranks)
        ranks->step(limit, sim);
      else
        sim.step(limit);
      observe_step();
      if (schedule.history_due(sim.time())) write_history();
      if (schedule.frame_due(sim.time()) || rest.at_rest()) {
        write_frame();
        // (the view has the current positions now: the bisection reads them; none at the end)
        if (ranks && !rest.at_rest() && !schedule.finished(sim.time())) {
          const RankGroup::Rebalance r = ranks->rebalance(sim, set.rebalance_threshold);
          most_imbalance = std::max(most_imbalance, r.imbalance);
          redealings += r.dealt;
          if (r.dealt) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "rebalanced at t = %.6g s: the busiest rank's work was %.1f %% above "
                          "the mean; %lld elements changed rank",
                          sim.time(), 100.0 * r.imbalance, static_cast<long long>(r.moved));
            log.file_only(std::string(buf) + "\n");
          }
        }
      }
      // (none after the one before the last steps: a later end time extends the run from it)
      if (signals.received() != 0 || rest.at_rest()) {
        if (!before_last_steps) write_checkpoint_now();
        break;
      }
      if (!before_last_steps && clock.due(sim.time())) write_checkpoint_now();
      progress.update(sim);
    }
  } catch (const InstabilityError& e) {
    progress.break_line();
    history->close();
    results->close(false);
    finish_summary(RunStatus::unstable);
    log.error(std::string("error: the simulation became unstable: ") + e.what());
    throw;
  }
  progress.clear();
  history->close();
  if (checkpoints > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%lld checkpoint%s written in %.3g s in all",
                  static_cast<long long>(checkpoints), checkpoints == 1 ? "" : "s",
                  checkpoint_time_s);
    log.file_only(std::string(buf) + "\n");
  }
  if (signals.received() != 0) {
    results->close(false);
    finish_summary(RunStatus::interrupted);
    if (ranks) ranks->stop();
    log.say("interrupted by signal " + std::to_string(signals.received()) +
            " at t = " + std::to_string(sim.time()) +
            " s; the frames written so far are readable. Continue with: femdem resume " +
            out.string());
    return 1;
  }
  results->close(true);
  const RunSummary summary = finish_summary(RunStatus::completed);
  if (ranks) ranks->stop();
  say_outcome(log, sim, rest, summary.wall_time_s, out);
  if (ranks) {
    const RankGroup::Times& t = ranks->times();
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "rank 0's loop: %.3g s stepping, %.3g s body motions, %.3g s history rows, "
                  "%.3g s gathering frames and checkpoints, %.3g s rebalancing",
                  t.step_s, t.body_motions_s, t.sample_s, t.gather_s, t.rebalance_s);
    log.file_only(std::string(buf) + "\n");
    if (set.rebalance_threshold >= 0.0) {
      std::snprintf(buf, sizeof buf,
                    "rebalancing: the bodies re-dealt %d time%s; the busiest rank's work at most "
                    "%.1f %% above the mean at the frames (threshold %.3g %%)",
                    redealings, redealings == 1 ? "" : "s", 100.0 * most_imbalance,
                    100.0 * set.rebalance_threshold);
      log.file_only(std::string(buf) + "\n");
    }
    if (const BodyContact& contact = ranks->part().body_contact(); contact.active()) {
      const double n = contact.foreign_nodes_per_step();
      std::snprintf(buf, sizeof buf,
                    "contact nodes of other ranks' bodies received a step: %.1f in all (%.4g kB), "
                    "on average",
                    n, 48e-3 * n);
      log.file_only(std::string(buf) + "\n");
      std::snprintf(buf, sizeof buf,
                    "contact pairs evaluated: %lld on all ranks for %lld listed (each by one "
                    "rank); %.1f pair outcomes sent to other ranks a step (%.4g kB), on average",
                    static_cast<long long>(contact.evaluations_on_ranks()),
                    static_cast<long long>(contact.listed_since_start()),
                    contact.shared_pairs_per_step(), 1e-3 * contact.shared_bytes_per_step());
      log.file_only(std::string(buf) + "\n");
    }
  }
  if (compaction && !options.plot_script.empty()) plot_compaction(options.plot_script, out, log);
  return 0;
}

}  // namespace

int run_scene(const SceneFile& scene, const RunOptions& options) {
  check_new_run_folder(options.out_dir, options.force);
  std::error_code ec;
  RunOrigin origin{std::filesystem::absolute(scene.path, ec).string(), options.overrides, {}};
  return execute(scene, std::move(origin), options, nullptr);
}

int resume_run(const ResumeOptions& options) {
  const std::filesystem::path out = options.run.out_dir;
  const std::filesystem::path checkpoint = out / kCheckpointFile;
  ResumePoint point;
  RunOrigin origin;
  try {
    point.info = read_checkpoint_info(checkpoint);
    origin = read_run_origin(checkpoint);
  } catch (const CheckpointError& e) {
    throw InputError(e.what(), checkpoint.string());
  }
  // the checkpoint must be this folder's (a copied one would splice two runs)
  const std::string results_digest = results_scene_digest(out);
  if (results_digest != point.info.scene_digest)
    throw InputError("the checkpoint does not belong to this folder's run: it holds scene " +
                         point.info.scene_digest + ", results.h5 " +
                         (results_digest.empty() ? std::string("no scene digest (missing?)")
                                                 : "scene " + results_digest),
                     checkpoint.string());
  // only what does not alter the past may change
  const std::vector<std::string>& allowed = resumable_keys();
  bool rest_off = false;
  std::vector<std::string> given;
  for (const std::string& o : options.overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const std::string& k : allowed) list += (list.empty() ? "" : ", ") + k;
      throw InputError("--set " + key +
                           ": a resumed run may change only what does not alter the past (" + list +
                           ")",
                       "", 0, 0, key);
    }
    given.push_back(key);
    if (key == "simulation.rest_kinetic_fraction" || key == "simulation.rest_hold_time")
      point.rearm_rest = true;
    if (key == "simulation.rest_kinetic_fraction") {
      const std::string v = o.substr(o.find('=') + 1);
      rest_off = v == "0" || v == "0.0";
    }
  }
  // the run's own overrides, then the resumable settings as the run had them, then the new ones
  std::vector<std::string> overrides = origin.overrides;
  for (const std::string& s : resumable_settings(origin.resolved_toml)) {
    const std::string key = s.substr(0, s.find('='));
    if (std::find(given.begin(), given.end(), key) != given.end()) continue;
    if (rest_off && key == "simulation.rest_hold_time") continue;
    overrides.push_back(s);
  }
  overrides.insert(overrides.end(), options.overrides.begin(), options.overrides.end());
  const SceneFile scene = load_scene(origin.scene_path, overrides);
  if (scene_digest(scene.resolved_toml) != point.info.scene_digest) {
    const std::string was = scene_identity_text(origin.resolved_toml);
    const std::string now = scene_identity_text(scene.resolved_toml);
    throw InputError(
        "the scene has changed since the run started, so the checkpoint does not "
        "belong to it: the run had `" +
            first_differing_line(was, now) + "` where the scene now gives `" +
            first_differing_line(now, was) + "`",
        origin.scene_path);
  }
  return execute(scene, std::move(origin), options.run, &point);
}

}  // namespace femdem
