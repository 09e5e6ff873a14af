// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/sweep/sweep.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/scene/scene_reader.hpp"
#include "tools/femdem/sweep/child_process.hpp"
#include "tools/femdem/sweep/sweep_table.hpp"
#include "tools/femdem/sweep/value_list.hpp"

namespace femdem {

namespace fs = std::filesystem;

namespace {

using namespace sweep;

std::atomic<int> g_sweep_signal{0};
extern "C" void on_sweep_signal(int sig) {
  g_sweep_signal = sig;
}

// A value of a --vary key that the scene reader rejected: the reader's message, naming the
// --vary rather than the --set it was given as.
[[noreturn]] void bad_vary_value(const std::string& key, const std::string& value,
                                 const InputError& e) {
  std::string msg = e.describe();
  const std::string as_set = "--set " + key + "=" + value;
  for (std::size_t p; (p = msg.find(as_set)) != std::string::npos;) msg.replace(p, 5, "--vary");
  throw InputError("value '" + value + "': " + msg, {}, 0, 0, "--vary " + key);
}

// The --vary axes: each KEY=V1,V2,... once, none also given to --set.
std::vector<Axis> read_axes(const SweepOptions& opt) {
  if (opt.vary.empty())
    throw InputError("give at least one --vary KEY=V1,V2,...", {}, 0, 0, "--vary");
  std::vector<Axis> axes;
  std::set<std::string> set_keys;
  for (const auto& s : opt.overrides)
    if (const auto eq = s.find('='); eq != std::string::npos)
      set_keys.insert(trim(s.substr(0, eq)));
  for (const auto& v : opt.vary) {
    const auto eq = v.find('=');
    if (eq == std::string::npos || trim(v.substr(0, eq)).empty())
      throw InputError(
          "expected --vary KEY=V1,V2,..., e.g. simulation.end_time=1e-3,2e-3 (got '" + v + "')", {},
          0, 0, "--vary");
    Axis a;
    a.key = trim(v.substr(0, eq));
    for (const auto& b : axes)
      if (b.key == a.key)
        throw InputError("varied twice; give all its values in one --vary", {}, 0, 0, a.key);
    if (set_keys.count(a.key))
      throw InputError("given both to --set and to --vary", {}, 0, 0, a.key);
    a.values = split_value_list(v.substr(eq + 1), a.key);
    axes.push_back(std::move(a));
  }
  assign_short_names(axes);
  return axes;
}

// With several axes, every value on its own first, so that a bad value is named as such
// rather than as a bad combination.
void check_axis_values(const SweepOptions& opt, const std::vector<Axis>& axes) {
  if (axes.size() > 1) {
    for (const auto& a : axes)
      for (const auto& v : a.values) {
        auto sets = opt.overrides;
        sets.push_back(a.key + "=" + v);
        try {
          load_scene(opt.scene_path, sets);
        } catch (const InputError& e) {
          bad_vary_value(a.key, v, e);
        }
      }
  }
}

// The runs in sweep order (the last axis varies fastest), each with its folder name and its
// resolved scene; a combination the scene reader rejects is an InputError.
std::vector<Run> plan_runs(const SweepOptions& opt, const std::vector<Axis>& axes,
                           std::size_t total) {
  std::vector<Run> runs(total);
  std::map<std::string, int> name_count;
  for (std::size_t i = 0; i < total; ++i) {
    Run& r = runs[i];
    // The last axis varies fastest.
    std::size_t rest = i;
    r.values.resize(axes.size());
    for (std::size_t a = axes.size(); a-- > 0;) {
      r.values[a] = axes[a].values[rest % axes[a].values.size()];
      rest /= axes[a].values.size();
    }
    auto sets = opt.overrides;
    std::string name;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      sets.push_back(axes[a].key + "=" + r.values[a]);
      name += (a ? "__" : "") + folder_text(axes[a].short_name) + "=" + folder_text(r.values[a]);
    }
    if (const int n = ++name_count[name]; n > 1) name += "~" + std::to_string(n);
    r.name = name;
    try {
      r.resolved = load_scene(opt.scene_path, sets).resolved_toml;
    } catch (const InputError& e) {
      if (axes.size() == 1) bad_vary_value(axes[0].key, r.values[0], e);
      throw InputError("the combination " + run_label(axes, r) + " is not valid: " + e.describe(),
                       {}, 0, 0, "--vary");
    }
  }

  return runs;
}

// Marks the runs already completed in `dir` with the same resolved scene as skipped (their
// summaries are kept); returns how many.
std::size_t keep_completed(const fs::path& dir, std::vector<Run>& runs) {
  std::size_t skipped = 0;
  for (auto& r : runs) {
    const fs::path rd = dir / r.name;
    const auto summary = read_summary(rd / "summary.json");
    if (!summary || !summary->is_object() || summary->value("status", "") != "completed") continue;
    const auto logged = logged_resolved_scene(rd / "run.log");
    if (!logged || *logged != r.resolved) continue;
    r.outcome = Outcome::skipped;
    flatten(*summary, "", r.fields);
    ++skipped;
  }
  return skipped;
}

// Marks the runs that were interrupted in `dir` (a checkpoint, no completed summary) with the
// same resolved scene as to be resumed from their checkpoints; returns how many.
std::size_t mark_resumable(const fs::path& dir, std::vector<Run>& runs) {
  std::size_t resumable = 0;
  for (auto& r : runs) {
    if (r.outcome != Outcome::pending) continue;
    const fs::path rd = dir / r.name;
    if (!fs::exists(rd / "checkpoint.h5")) continue;
    // killed (no summary) or stopped by a signal; a diverged run is run again from the start
    const auto summary = read_summary(rd / "summary.json");
    if (summary && summary->is_object() && summary->value("status", "") != "interrupted") continue;
    const auto logged = logged_resolved_scene(rd / "run.log");
    if (!logged || *logged != r.resolved) continue;
    r.resume = true;
    ++resumable;
  }
  return resumable;
}

// tools/plot_sweep.py DIR, with the system python first (tools/setup installs matplotlib there,
// as the script's #! line expects), then whatever python3 is on the PATH.
template <class Say>
void plot_sweep(const SweepOptions& opt, const fs::path& dir, const Say& say) {
  if (!opt.plot) {
    // --no-plot
  } else if (opt.plot_script.empty() || !fs::exists(opt.plot_script)) {
    say("note: tools/plot_sweep.py not found; no plots");
  } else {
    // The system python first (tools/setup installs matplotlib there, as the script's #! line
    // expects), then whatever python3 is on the PATH.
    int code = 127;
    for (const char* python : {"/usr/bin/python3", "python3"}) {
      if (python[0] == '/' && !fs::exists(python)) continue;
      std::vector<std::string> args = {python, opt.plot_script, dir.string()};
      if (opt.quiet) args.push_back("--quiet");
      const pid_t pid = spawn(args, opt.quiet ? "/dev/null" : "", true);
      int status = 0;
      if (pid > 0) {
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
      }
      const int c = pid > 0 ? exit_code_of(status) : 127;
      if (c == 127 && code == 4) continue;  // keep "matplotlib missing" over "no python"
      code = c;
      if (code != 127 && code != 4) break;
    }
    if (code == 127)
      say("note: python3 not found; no plots (run tools/setup, then tools/plot_sweep.py " +
          dir.string() + ")");
    else if (code == 4)
      say("note: matplotlib missing; no plots (run tools/setup, then tools/plot_sweep.py " +
          dir.string() + ")");
    else if (code != 0)
      say("note: the plot script failed (exit code " + std::to_string(code) + ")");
  }
}

// A run's process ended with `exit_code`: its summary flattened and its outcome.
void finish_run(Run& r, int exit_code, const fs::path& dir) {
  r.exit_code = exit_code;
  r.fields.clear();
  const auto summary = read_summary(dir / r.name / "summary.json");
  std::string st = "failed";
  if (summary && summary->is_object()) {
    flatten(*summary, "", r.fields);
    st = summary->value("status", "failed");
  } else {
    r.fields = {{"status", "failed"}};
  }
  if (r.exit_code == 0 && st == "completed")
    r.outcome = Outcome::completed;
  else if (g_sweep_signal != 0 && st == "interrupted")
    r.outcome = Outcome::interrupted;  // stopped by us: not counted as a failure
  else if (st == "unstable" || (r.exit_code == 3 && !summary))
    r.outcome = Outcome::diverged;
  else
    r.outcome = Outcome::failed;
}

// What the progress line says of a finished run.
std::string outcome_text(const Run& r, double seconds, const fs::path& dir) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  if (r.outcome == Outcome::completed) return std::string("completed in ") + buf;
  if (r.outcome == Outcome::interrupted) return "interrupted";
  if (r.outcome == Outcome::diverged)
    return "DIVERGED (see " + (dir / r.name / "run.log").string() + ")";
  return "FAILED with exit code " + std::to_string(r.exit_code) + " (see " +
         (dir / r.name / "console.txt").string() + ")";
}

}  // namespace

int run_sweep(const SweepOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto now = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto say = [&](const std::string& s) {
    if (!opt.quiet) std::printf("sweep: %s\n", s.c_str());
    std::fflush(stdout);
  };

  const std::vector<Axis> axes = read_axes(opt);

  // --- validate: the scene with --set, every value of every axis, then every combination
  const SceneFile base = load_scene(opt.scene_path, opt.overrides);
  std::size_t total = 1;
  for (const auto& a : axes) total *= a.values.size();
  if (total > 100000) throw InputError("more than 100000 runs", {}, 0, 0, "--vary");
  say("checking " + std::to_string(total) + " run" + (total == 1 ? "" : "s") + " of " +
      opt.scene_path);
  check_axis_values(opt, axes);
  std::vector<Run> runs = plan_runs(opt, axes, total);

  // --- the sweep folder; runs already completed with the same resolved scene are kept
  const fs::path dir =
      opt.out_dir.empty() ? fs::path("out") / (base.stem + "_sweep") : fs::path(opt.out_dir);
  fs::create_directories(dir);
  const std::size_t skipped = keep_completed(dir, runs);
  const std::size_t resumable = mark_resumable(dir, runs);
  const fs::path csv = dir / "sweep.csv";
  auto write_csv = [&] { write_file_atomically(csv, csv_text(axes, runs), /*durable=*/false); };
  write_csv();

  const int cores = available_cores();
  const int tpj = std::max(1, opt.threads_per_job);
  int jobs = opt.jobs > 0 ? opt.jobs : std::max(1, cores / tpj);
  const std::size_t to_run = total - skipped;
  jobs = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(jobs), std::max<std::size_t>(to_run, 1)));
  {
    std::string s =
        std::to_string(total) + " run" + (total == 1 ? "" : "s") + " in " + dir.string() + "/";
    if (skipped)
      s += "; " + std::to_string(skipped) +
           " already completed with the same resolved scene, not rerun";
    if (to_run)
      s += "; running " + std::to_string(to_run) + ", " + std::to_string(jobs) + " at a time, " +
           std::to_string(tpj) + " thread" + (tpj == 1 ? "" : "s") + " each";
    if (resumable)
      s += " (" + std::to_string(resumable) + " of them resumed from their checkpoints)";
    say(s);
    if (skipped && !opt.quiet)
      for (const auto& r : runs)
        if (r.outcome == Outcome::skipped) say("  skipped (already completed): " + r.name);
  }

  // --- run
  struct sigaction sa {
  }, old_int{}, old_term{};
  sa.sa_handler = on_sweep_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: waitpid returns on a signal
  g_sweep_signal = 0;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);

  std::map<pid_t, std::size_t> running;
  std::size_t next = 0, done = skipped, failed = 0, diverged = 0;
  bool forwarded = false;
  while (true) {
    while (g_sweep_signal == 0 && running.size() < static_cast<std::size_t>(jobs) && next < total) {
      Run& r = runs[next];
      if (r.outcome != Outcome::pending) {
        ++next;
        continue;
      }
      const fs::path rd = dir / r.name;
      fs::create_directories(rd);
      std::vector<std::string> args;
      if (r.resume) {
        // the run's own scene and overrides are in its checkpoint
        args = {opt.femdem_exe, "resume", rd.string(), "--threads", std::to_string(tpj), "--quiet"};
      } else {
        // (the sweep has decided that this run is to be made again: --force)
        args = {opt.femdem_exe,      "run",     opt.scene_path, "--out", rd.string(), "--threads",
                std::to_string(tpj), "--quiet", "--force"};
        for (const auto& s : opt.overrides) args.insert(args.end(), {"--set", s});
        for (std::size_t a = 0; a < axes.size(); ++a)
          args.insert(args.end(), {"--set", axes[a].key + "=" + r.values[a]});
      }
      // a run of a compaction scene draws its own plots unless the sweep is told not to plot
      if (!opt.plot) args.push_back("--no-plot");
      args.insert(args.begin(), opt.launcher.begin(), opt.launcher.end());
      const pid_t pid = spawn(args, (rd / "console.txt").string(), !opt.launcher.empty());
      if (pid < 0) {
        r.outcome = Outcome::failed;
        r.exit_code = 1;
        r.fields = {{"status", "failed"}};
        ++failed;
        ++done;
        say("[" + std::to_string(done) + "/" + std::to_string(total) +
            "] cannot start a process: " + std::strerror(errno));
        write_csv();
      } else {
        r.outcome = Outcome::running;
        r.started = now();
        running[pid] = next;
      }
      ++next;
    }
    if (running.empty()) break;
    if (g_sweep_signal != 0 && !forwarded) {
      for (const auto& [pid, i] : running) kill(pid, SIGTERM);
      forwarded = true;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;  // ECHILD: nothing left to wait for
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    Run& r = runs[it->second];
    running.erase(it);
    finish_run(r, exit_code_of(status), dir);
    diverged += r.outcome == Outcome::diverged;
    failed += r.outcome == Outcome::failed;
    ++done;
    write_csv();
    std::string line = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " +
                       run_label(axes, r) + ": " + outcome_text(r, now() - r.started, dir);
    if (failed || diverged)
      line += "; so far " + std::to_string(failed) + " failed, " + std::to_string(diverged) +
              " diverged";
    say(line);
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  write_csv();

  if (g_sweep_signal != 0) {
    std::size_t finished = 0;
    for (const auto& r : runs)
      finished += r.outcome == Outcome::completed || r.outcome == Outcome::skipped;
    std::fprintf(stderr,
                 "sweep: interrupted by signal %d; %zu of %zu runs completed, in %s (rerun the "
                 "same command to resume)\n",
                 g_sweep_signal.load(), finished, total, csv.string().c_str());
    return 1;
  }
  say("results: " + csv.string() + " (" + std::to_string(total - failed - diverged) +
      " completed, " + std::to_string(diverged) + " diverged, " + std::to_string(failed) +
      " failed)");

  plot_sweep(opt, dir, say);

  if (failed) return 1;
  if (diverged) return 3;
  return 0;
}

}  // namespace femdem
