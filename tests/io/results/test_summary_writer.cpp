// SPDX-License-Identifier: GPL-3.0-or-later
// summary.json: key names of docs/OUTPUTS.md, null restitution, exact doubles, atomic write.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "io/results/summary_writer.hpp"

namespace fs = std::filesystem;
using namespace femdem;
using nlohmann::json;

namespace {

RunSummary example() {
  RunSummary s;
  s.scene = "scenes/taylor_bar.toml";
  s.status = RunStatus::completed;
  s.end_time = 8e-5;
  s.steps = 2345;
  s.time_step = 1.0 / 3.0 * 1e-7;
  s.wall_time_s = 12.3;
  s.threads = 2;
  s.nodes = 35000;
  s.elements = 23000;
  s.energy = {.kinetic = 1.0,
              .internal = 2.0,
              .plastic_dissipation = 3.0,
              .contact = 4.0,
              .contact_dissipation = 0.5,
              .viscous_dissipation = 0.25,
              .mass_scaling_dissipation = 0.125,
              .external_work = 5.0,
              .balance_error = 1e-4};
  BodySummary rod;
  rod.name = "rod";
  rod.mass = 2.3;
  rod.volume = 1.1e-6;
  rod.com = {0.0, 0.1, 0.2};
  rod.vcom = {0.0, 0.0, -227.0};
  rod.kinetic_energy = 5.0e4;
  rod.bbox_min = {-1, -2, -3};
  rod.bbox_max = {1, 2, 3};
  rod.max_equivalent_plastic_strain = 1.7;
  BodySummary ball = rod;
  ball.name = "ball";
  ball.coefficient_of_restitution = Restitution{0.8, 0.75};
  s.bodies = {rod, ball};
  s.extra["final_length"] = 0.0216;
  return s;
}

}  // namespace

TEST(SummaryWriter, RoundTripKeysAndNull) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "summary_writer";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const RunSummary s = example();
  write_summary(dir / "summary.json", s);

  std::ifstream in(dir / "summary.json");
  const json j = json::parse(in);
  for (const char* key : {"scene", "status", "end_time", "steps", "time_step", "wall_time_s",
                          "threads", "nodes", "elements", "energy", "bodies", "extra"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["scene"], "scenes/taylor_bar.toml");
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["end_time"].get<double>(), 8e-5);
  EXPECT_EQ(j["steps"].get<long>(), 2345);
  EXPECT_EQ(j["time_step"].get<double>(), s.time_step);  // exact
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["nodes"], 35000);
  EXPECT_EQ(j["elements"], 23000);
  const json& e = j["energy"];
  EXPECT_EQ(e.size(), 9u);  // with viscous_dissipation and mass_scaling_dissipation
  EXPECT_EQ(e["kinetic"], 1.0);
  EXPECT_EQ(e["internal"], 2.0);
  EXPECT_EQ(e["plastic_dissipation"], 3.0);
  EXPECT_EQ(e["contact"], 4.0);
  EXPECT_EQ(e["contact_dissipation"], 0.5);
  EXPECT_EQ(e["mass_scaling_dissipation"], 0.125);
  EXPECT_EQ(e["external_work"], 5.0);
  EXPECT_EQ(e["balance_error"], 1e-4);

  ASSERT_EQ(j["bodies"].size(), 2u);
  const json& rod = j["bodies"]["rod"];
  for (const char* key :
       {"mass", "added_mass", "volume", "com", "vcom", "angular_velocity", "kinetic_energy",
        "bbox_min", "bbox_max", "max_equivalent_plastic_strain", "max_principal_stress",
        "max_principal_stress_time", "coefficient_of_restitution"}) {
    EXPECT_TRUE(rod.contains(key)) << key;
  }
  EXPECT_EQ(rod.size(), 13u);
  EXPECT_TRUE(rod["coefficient_of_restitution"].is_null());
  EXPECT_EQ(rod["vcom"], json::array({0.0, 0.0, -227.0}));
  EXPECT_EQ(rod["bbox_max"], json::array({1.0, 2.0, 3.0}));
  EXPECT_EQ(rod["max_equivalent_plastic_strain"], 1.7);
  const json& cor = j["bodies"]["ball"]["coefficient_of_restitution"];
  ASSERT_TRUE(cor.is_object());
  EXPECT_EQ(cor["com"], 0.8);
  EXPECT_EQ(cor["kinetic_energy"], 0.75);
  EXPECT_EQ(j["extra"]["final_length"], 0.0216);

  // Bodies keep the scene's order; no temporary file is left behind.
  const std::string text = summary_to_json(s);
  EXPECT_LT(text.find("\"rod\""), text.find("\"ball\""));
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename(), "summary.json");
  }
}

TEST(SummaryWriter, StatusAndNonFinite) {
  RunSummary s = example();
  s.status = RunStatus::unstable;
  s.energy.kinetic = std::numeric_limits<double>::quiet_NaN();
  json j = json::parse(summary_to_json(s));
  EXPECT_EQ(j["status"], "unstable");
  EXPECT_TRUE(j["energy"]["kinetic"].is_null());
  s.status = RunStatus::interrupted;
  EXPECT_EQ(json::parse(summary_to_json(s))["status"], "interrupted");
}

TEST(SummaryWriter, ReplacesExistingFileAtomically) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "summary_writer_replace";
  fs::remove_all(dir);
  fs::create_directories(dir);
  RunSummary s = example();
  write_summary(dir / "summary.json", s);
  s.steps = 7;
  write_summary(dir / "summary.json", s);
  std::ifstream in(dir / "summary.json");
  EXPECT_EQ(json::parse(in)["steps"], 7);
  EXPECT_THROW(write_summary(dir / "missing_folder" / "summary.json", s), std::runtime_error);
}
