// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Runs the femdem program on a scene shipped in scenes/ (or one a test writes) and reads what
// the tests look at: the exit code and output, summary.json and history.csv. Test files that
// include this get the program built first (tests/CMakeLists.txt looks for this header's name).
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/history_csv.hpp"
#include "support/run_command.hpp"

namespace femdem::test {

struct SceneRun {
  CommandResult command;
  std::filesystem::path out;
  nlohmann::json summary;                              // null when the run wrote no summary.json
  std::map<std::string, std::vector<double>> history;  // empty without history.csv
};

// `femdem run scenes/<scene> --quiet --out <FEMDEM_TEST_TMP>/<out_name> <options>`, the output
// folder emptied first. env: assignments put before the program ("FEMDEM_MESH_CACHE=...").
inline SceneRun run_shipped_scene(const std::string& scene, const std::string& out_name,
                                  const std::string& options, const std::string& env = "") {
  namespace fs = std::filesystem;
  SceneRun run;
  run.out = fs::path(FEMDEM_TEST_TMP) / out_name;
  fs::remove_all(run.out);
  run.command = run_command((env.empty() ? std::string() : env + " ") + "'" + FEMDEM_EXE +
                            "' run '" + FEMDEM_SOURCE_DIR + "/scenes/" + scene +
                            "' --quiet --out '" + run.out.string() + "' " + options);
  if (std::ifstream in(run.out / "summary.json"); in) run.summary = nlohmann::json::parse(in);
  if (fs::exists(run.out / "history.csv")) run.history = read_history(run.out / "history.csv");
  return run;
}

// A scene written by the test: `text` goes to <FEMDEM_TEST_TMP>/<out_name>/scene.toml (the
// folder emptied first), then `femdem run scene.toml --quiet --no-plot --out .../out <options>`.
inline SceneRun run_scene_text(const std::string& out_name, const std::string& text,
                               const std::string& options = "--threads 1") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / out_name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml") << text;
  SceneRun run;
  run.out = dir / "out";
  std::string command = "'";  // (appended piece by piece: GCC 12 warns, wrongly, on a + chain)
  command += FEMDEM_EXE;
  command += "' run '" + (dir / "scene.toml").string();
  command += "' --quiet --no-plot --out '" + run.out.string() + "' " + options;
  run.command = run_command(command);
  if (std::ifstream in(run.out / "summary.json"); in) run.summary = nlohmann::json::parse(in);
  if (fs::exists(run.out / "history.csv")) run.history = read_history(run.out / "history.csv");
  return run;
}

}  // namespace femdem::test
