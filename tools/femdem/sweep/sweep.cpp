// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/sweep/sweep.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
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
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/scene/scene_reader.hpp"

namespace femdem {

namespace fs = std::filesystem;

namespace {

using Json = nlohmann::ordered_json;

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

// ---------------------------------------------------------------------------------------------
// Value lists

// Splits at the commas outside brackets, braces, parentheses and quoted strings.
std::vector<std::string> split_top_level(const std::string& s, const std::string& key,
                                         const std::string& what) {
  std::vector<std::string> items;
  std::string cur;
  int depth = 0;
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote) {
      cur += c;
      if (c == '\\' && quote == '"' && i + 1 < s.size()) {
        cur += s[++i];
      } else if (c == quote) {
        quote = 0;
      }
      continue;
    }
    if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{' || c == '(') {
      ++depth;
    } else if (c == ']' || c == '}' || c == ')') {
      if (--depth < 0)
        throw InputError("unbalanced '" + std::string(1, c) + "' in " + what, {}, 0, 0, key);
    } else if (c == ',' && depth == 0) {
      items.push_back(trim(cur));
      cur.clear();
      continue;
    }
    cur += c;
  }
  if (quote) throw InputError("unterminated quoted string in " + what, {}, 0, 0, key);
  if (depth != 0) throw InputError("unbalanced brackets in " + what, {}, 0, 0, key);
  items.push_back(trim(cur));
  return items;
}

struct Number {
  double value = 0.0;
  bool integer = false;  // written without '.', exponent, inf or nan
};

std::optional<Number> parse_number(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  for (char c : t)
    if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.' ||
          c == 'e' || c == 'E'))
      return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return Number{v, t.find_first_of(".eE") == std::string::npos};
}

// A range value as TOML text: integers as integers, floats rounded to 12 significant digits
// (so 0.1 + 2 * 0.1 is written 0.3) and always recognisable as a float.
std::string format_range_value(double v, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(std::llround(v)));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  double rounded = std::strtod(buf, nullptr);
  if (rounded == 0.0) rounded = 0.0;  // no "-0"
  std::snprintf(buf, sizeof buf, "%.15g", rounded);
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

constexpr std::size_t kMaxRangeValues = 10000;

// Expands "A:B:S", "linspace(A,B,N)" or "logspace(A,B,N)"; nullopt when the item is neither.
std::optional<std::vector<std::string>> expand_range(const std::string& item,
                                                     const std::string& key) {
  const std::string where = "the range '" + item + "'";
  std::vector<std::string> out;
  for (const char* fn : {"linspace", "logspace"}) {
    const std::string f = std::string(fn) + "(";
    if (item.rfind(f, 0) != 0) continue;
    if (item.back() != ')')
      throw InputError(where + " must end with ')': " + fn + "(START,STOP,COUNT)", {}, 0, 0, key);
    const auto args =
        split_top_level(item.substr(f.size(), item.size() - f.size() - 1), key, where);
    std::optional<Number> a, b, n;
    if (args.size() == 3)
      a = parse_number(args[0]), b = parse_number(args[1]), n = parse_number(args[2]);
    if (!a || !b || !n)
      throw InputError(where + ": expected " + std::string(fn) + "(START,STOP,COUNT) with numbers",
                       {}, 0, 0, key);
    if (!n->integer || n->value < 1 || n->value > static_cast<double>(kMaxRangeValues))
      throw InputError(
          where + ": COUNT must be an integer from 1 to " + std::to_string(kMaxRangeValues), {}, 0,
          0, key);
    const bool log = std::string(fn) == "logspace";
    if (log && (a->value <= 0.0 || b->value <= 0.0))
      throw InputError(where + ": logspace needs positive START and STOP", {}, 0, 0, key);
    const auto count = static_cast<std::size_t>(n->value);
    for (std::size_t i = 0; i < count; ++i) {
      const double t = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
      const double v =
          log ? std::exp(std::log(a->value) + t * (std::log(b->value) - std::log(a->value)))
              : a->value + t * (b->value - a->value);
      out.push_back(format_range_value(i + 1 == count && count > 1 ? b->value : v, false));
    }
    return out;
  }
  // START:STOP:STEP, three numbers.
  if (item.find(':') == std::string::npos) return std::nullopt;
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t c = item.find(':', start);
    parts.push_back(item.substr(start, c - start));
    if (c == std::string::npos) break;
    start = c + 1;
  }
  std::vector<Number> nums;
  for (const auto& p : parts)
    if (auto n = parse_number(p)) nums.push_back(*n);
  if (nums.size() != parts.size()) return std::nullopt;  // not a numeric range: a plain value
  if (nums.size() != 3)
    throw InputError(where + ": a range is START:STOP:STEP (three numbers)", {}, 0, 0, key);
  const double a = nums[0].value, b = nums[1].value, step = nums[2].value;
  if (step == 0.0 || (b - a) * step < 0.0)
    throw InputError(where + ": STEP must be nonzero and lead from START to STOP", {}, 0, 0, key);
  const bool integer = nums[0].integer && nums[1].integer && nums[2].integer;
  const double count_f = std::floor((b - a) / step + 1e-9) + 1.0;
  if (count_f > static_cast<double>(kMaxRangeValues))
    throw InputError(where + ": more than " + std::to_string(kMaxRangeValues) + " values", {}, 0, 0,
                     key);
  const auto count = static_cast<std::size_t>(count_f);
  for (std::size_t i = 0; i < count; ++i)
    out.push_back(format_range_value(a + static_cast<double>(i) * step, integer));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Run folders

struct Axis {
  std::string key;
  std::vector<std::string> values;
  std::string short_name;  // the key's last parts, enough to tell the axes apart
};

std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

void assign_short_names(std::vector<Axis>& axes) {
  std::size_t depth = 1;
  while (true) {
    std::set<std::string> seen;
    bool unique = true;
    bool more = false;
    for (auto& a : axes) {
      const auto parts = key_parts(a.key);
      const std::size_t n = std::min(depth, parts.size());
      if (n < parts.size()) more = true;
      std::string s;
      for (std::size_t i = parts.size() - n; i < parts.size(); ++i)
        s += (s.empty() ? "" : ".") + parts[i];
      a.short_name = s;
      unique = seen.insert(s).second && unique;
    }
    if (unique || !more) return;
    ++depth;
  }
}

// A folder-name-friendly rendering of a value: brackets, braces, quotes and spaces dropped,
// anything else unusual replaced by '_'.
std::string folder_text(const std::string& value) {
  std::string s;
  for (char c : value) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
        c == ',' || c == '_')
      s += c;
    else if (c == '[' || c == ']' || c == '{' || c == '}' || c == '"' || c == '\'' || c == ' ' ||
             c == '(' || c == ')')
      continue;
    else
      s += '_';
  }
  if (s.size() > 40) s = s.substr(0, 40);
  if (s.empty()) s = "_";
  return s;
}

// ---------------------------------------------------------------------------------------------
// Results

// The resolved scene a run recorded in its run.log, if any.
std::optional<std::string> logged_resolved_scene(const fs::path& run_log) {
  std::ifstream in(run_log, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::string begin = "# resolved scene\n", end = "\n# end of resolved scene";
  const std::size_t a = text.find(begin);
  if (a == std::string::npos) return std::nullopt;
  const std::size_t b = text.find(end, a + begin.size());
  if (b == std::string::npos) return std::nullopt;
  return text.substr(a + begin.size(), b - a - begin.size());
}

std::optional<Json> read_summary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    return Json::parse(in);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string number_text(const Json& v) {
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_unsigned()) return std::to_string(v.get<unsigned long long>());
  char buf[64];
  // Shortest text that reads back to the same double.
  const double d = v.get<double>();
  for (int prec = 1; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, d);
    if (std::strtod(buf, nullptr) == d) break;
  }
  return buf;
}

using Fields = std::vector<std::pair<std::string, std::string>>;

// summary.json flattened to dotted columns: vectors of three as .x/.y/.z, a null restitution as
// two empty columns (so the columns do not depend on whether a body bounced).
void flatten(const Json& j, const std::string& prefix, Fields& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (prefix.empty() && it.key() == "scene") continue;  // the same for every run
      flatten(it.value(), prefix + it.key() + ".", out);
    }
    return;
  }
  const std::string name = prefix.substr(0, prefix.size() - 1);
  if (j.is_array()) {
    static const char* xyz[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < j.size(); ++i)
      flatten(j[i], prefix + (j.size() == 3 ? xyz[i] : std::to_string(i)) + ".", out);
  } else if (j.is_null()) {
    if (name.size() >= 26 && name.ends_with("coefficient_of_restitution")) {
      out.emplace_back(name + ".com", "");
      out.emplace_back(name + ".kinetic_energy", "");
    } else {
      out.emplace_back(name, "");
    }
  } else if (j.is_number()) {
    out.emplace_back(name, number_text(j));
  } else if (j.is_boolean()) {
    out.emplace_back(name, j.get<bool>() ? "true" : "false");
  } else if (j.is_string()) {
    out.emplace_back(name, j.get<std::string>());
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

enum class Outcome { pending, running, skipped, completed, diverged, failed, interrupted };

struct Run {
  std::vector<std::string> values;  // one per axis
  std::string name;                 // sub-folder
  std::string resolved;             // resolved scene
  Outcome outcome = Outcome::pending;
  int exit_code = 0;
  Fields fields;  // flattened summary.json
  double started = 0.0;
};

// sweep.csv: the finished runs in sweep order; the columns are the union over them.
std::string csv_text(const std::vector<Axis>& axes, const std::vector<Run>& runs) {
  std::vector<std::string> columns;
  std::set<std::string> known;
  for (const auto& r : runs) {
    if (r.outcome == Outcome::pending || r.outcome == Outcome::running) continue;
    for (const auto& [k, v] : r.fields)
      if (known.insert(k).second) columns.push_back(k);
  }
  std::string out;
  for (const auto& a : axes) out += csv_field(a.key) + ",";
  out += "run,exit_code";
  for (const auto& c : columns) {
    out += ',';
    out += csv_field(c);
  }
  out += '\n';
  for (const auto& r : runs) {
    if (r.outcome == Outcome::pending || r.outcome == Outcome::running) continue;
    for (const auto& v : r.values) out += csv_field(v) + ",";
    out += csv_field(r.name) + "," + std::to_string(r.exit_code);
    std::map<std::string, std::string> m(r.fields.begin(), r.fields.end());
    for (const auto& c : columns) {
      out += ",";
      if (auto it = m.find(c); it != m.end()) out += csv_field(it->second);
    }
    out += "\n";
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Processes

std::atomic<int> g_sweep_signal{0};
extern "C" void on_sweep_signal(int sig) {
  g_sweep_signal = sig;
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

// fork + exec; stdout and stderr to `output` ("" keeps them), stdin from /dev/null.
pid_t spawn(const std::vector<std::string>& args, const std::string& output, bool search_path) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid != 0) return pid;  // parent (or -1)
  // A sweep that is killed outright takes its runs with it (they write "interrupted").
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (getppid() != parent) _exit(1);
  const int in = open("/dev/null", O_RDONLY);
  if (in >= 0) dup2(in, 0);
  if (!output.empty()) {
    const int fd = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
  }
  if (search_path)
    execvp(argv[0], argv.data());
  else
    execv(argv[0], argv.data());
  const std::string msg = "cannot start " + args[0] + ": " + std::strerror(errno) + "\n";
  if (write(2, msg.data(), msg.size()) < 0) {
  }
  _exit(127);
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

std::string run_label(const std::vector<Axis>& axes, const Run& r) {
  std::string s;
  for (std::size_t a = 0; a < axes.size(); ++a)
    s += (a ? ", " : "") + axes[a].short_name + "=" + r.values[a];
  return s;
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

}  // namespace

std::vector<std::string> split_value_list(const std::string& list, const std::string& key) {
  const auto items = split_top_level(list, key, "--vary " + key + "=" + list);
  std::vector<std::string> values;
  for (const auto& item : items) {
    if (item.empty())
      throw InputError(
          "empty value in --vary " + key + "=" + list + " (values are separated by commas)", {}, 0,
          0, key);
    if (auto range = expand_range(item, key))
      values.insert(values.end(), range->begin(), range->end());
    else
      values.push_back(item);
  }
  std::set<std::string> seen;
  for (const auto& v : values)
    if (!seen.insert(v).second)
      throw InputError("value '" + v + "' appears twice in --vary " + key + "=" + list, {}, 0, 0,
                       key);
  return values;
}

int run_sweep(const SweepOptions& opt) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto now = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto say = [&](const std::string& s) {
    if (!opt.quiet) std::printf("sweep: %s\n", s.c_str());
    std::fflush(stdout);
  };

  // --- the axes
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

  // --- validate: the scene with --set, every value of every axis, then every combination
  const SceneFile base = load_scene(opt.scene_path, opt.overrides);
  std::size_t total = 1;
  for (const auto& a : axes) total *= a.values.size();
  if (total > 100000) throw InputError("more than 100000 runs", {}, 0, 0, "--vary");
  say("checking " + std::to_string(total) + " run" + (total == 1 ? "" : "s") + " of " +
      opt.scene_path);
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

  // --- the sweep folder; runs already completed with the same resolved scene are kept
  const fs::path dir =
      opt.out_dir.empty() ? fs::path("out") / (base.stem + "_sweep") : fs::path(opt.out_dir);
  fs::create_directories(dir);
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
      std::vector<std::string> args = {opt.femdem_exe, "run",       opt.scene_path,      "--out",
                                       rd.string(),    "--threads", std::to_string(tpj), "--quiet"};
      // a run of a compaction scene draws its own plots unless the sweep is told not to plot
      if (!opt.plot) args.push_back("--no-plot");
      for (const auto& s : opt.overrides) args.insert(args.end(), {"--set", s});
      for (std::size_t a = 0; a < axes.size(); ++a)
        args.insert(args.end(), {"--set", axes[a].key + "=" + r.values[a]});
      const pid_t pid = spawn(args, (rd / "console.txt").string(), false);
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
    r.exit_code = exit_code_of(status);
    r.fields.clear();
    const auto summary = read_summary(dir / r.name / "summary.json");
    std::string st = "failed";
    if (summary && summary->is_object()) {
      flatten(*summary, "", r.fields);
      st = summary->value("status", "failed");
    } else {
      r.fields = {{"status", "failed"}};
    }
    if (r.exit_code == 0 && st == "completed") {
      r.outcome = Outcome::completed;
    } else if (g_sweep_signal != 0 && st == "interrupted") {
      r.outcome = Outcome::interrupted;  // stopped by us: not counted as a failure
    } else if (st == "unstable" || (r.exit_code == 3 && !summary)) {
      r.outcome = Outcome::diverged;
      ++diverged;
    } else {
      r.outcome = Outcome::failed;
      ++failed;
    }
    ++done;
    write_csv();
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f s", now() - r.started);
    std::string line =
        "[" + std::to_string(done) + "/" + std::to_string(total) + "] " + run_label(axes, r) + ": ";
    if (r.outcome == Outcome::completed)
      line += std::string("completed in ") + buf;
    else if (r.outcome == Outcome::interrupted)
      line += "interrupted";
    else if (r.outcome == Outcome::diverged)
      line += "DIVERGED (see " + (dir / r.name / "run.log").string() + ")";
    else
      line += "FAILED with exit code " + std::to_string(r.exit_code) + " (see " +
              (dir / r.name / "console.txt").string() + ")";
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

  // --- plots
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

  if (failed) return 1;
  if (diverged) return 3;
  return 0;
}

}  // namespace femdem
