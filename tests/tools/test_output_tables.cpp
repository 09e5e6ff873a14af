// SPDX-License-Identifier: GPL-3.0-or-later
// The output table (tools/femdem/run/output_tables.hpp): history.csv's column names are the
// contract of docs/OUTPUTS.md, each row value sits under its own column, and the doc's tables
// are the ones the table generates.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "tools/femdem/run/output_tables.hpp"

namespace femdem {
namespace {

TEST(OutputTables, HistoryColumnNamesAndOrder) {
  HistoryLayout layout;
  layout.bodies = {"ball", "plate"};
  layout.walls = {"floor"};
  const auto c = history_columns(layout);
  ASSERT_EQ(c.size(), 12u + 2u * 11u + 8u);
  const std::vector<std::string> head = {"time",
                                         "dt",
                                         "kinetic_energy",
                                         "internal_energy",
                                         "plastic_dissipation",
                                         "contact_energy",
                                         "contact_dissipation",
                                         "viscous_dissipation",
                                         "mass_scaling_dissipation",
                                         "external_work",
                                         "total_energy",
                                         "energy_balance_error"};
  EXPECT_EQ(std::vector<std::string>(c.begin(), c.begin() + 12), head);
  const std::vector<std::string> ball = {"ball.com_x",
                                         "ball.com_y",
                                         "ball.com_z",
                                         "ball.vcom_x",
                                         "ball.vcom_y",
                                         "ball.vcom_z",
                                         "ball.kinetic_energy",
                                         "ball.contact_force_x",
                                         "ball.contact_force_y",
                                         "ball.contact_force_z",
                                         "ball.max_principal_stress"};
  EXPECT_EQ(std::vector<std::string>(c.begin() + 12, c.begin() + 23), ball);
  EXPECT_EQ(c[23], "plate.com_x");
  const std::vector<std::string> floor = {
      "floor.force_x",         "floor.force_y",
      "floor.force_z",         "floor.position_x",
      "floor.position_y",      "floor.position_z",
      "floor.max_penetration", "floor.max_penetration_per_size"};
  EXPECT_EQ(std::vector<std::string>(c.end() - 8, c.end()), floor);

  layout.body_contact = layout.compaction = true;
  const auto all = history_columns(layout);
  ASSERT_EQ(all.size(), c.size() + 2 + 12);
  EXPECT_EQ(all[c.size()], "contact.max_penetration");
  EXPECT_EQ(all[c.size() + 1], "contact.max_penetration_per_size");
  EXPECT_EQ(all[c.size() + 2], "compaction.punch_displacement");
  EXPECT_EQ(all.back(), "compaction.column_strain");
}

// Every value of a row lands under the column that names it.
TEST(OutputTables, RowValuesSitUnderTheirColumns) {
  HistorySample s;
  s.time = 1.5, s.dt = 2e-7;
  s.energies.kinetic = 3.0, s.energies.internal = 4.0, s.energies.external_work = 1.0;
  s.balance_error = 1e-4;
  s.bodies.resize(2);
  s.bodies[1].motion.com = Vec3(10, 11, 12);
  s.bodies[1].motion.vcom = Vec3(-1, -2, -3);
  s.bodies[1].motion.contact_force = Vec3(7, 8, 9);
  s.bodies[1].max_principal_stress = 5e6;
  s.walls.resize(1);
  s.walls[0].force = Vec3(100, 200, 300);
  s.walls[0].position = Vec3(0, 0, -0.5);
  s.max_penetration = 2.5e-5;
  CompactionSample cs;
  cs.relative_density = 0.75;
  cs.column_strain = 0.125;
  s.compaction = cs;

  HistoryLayout layout{{"ball", "plate"}, {"floor"}, true, true};
  const auto names = history_columns(layout);
  std::vector<double> row;
  history_row(s, row);
  ASSERT_EQ(row.size(), names.size());
  std::map<std::string, double> v;
  for (std::size_t i = 0; i < names.size(); ++i) v[names[i]] = row[i];
  EXPECT_EQ(v["time"], 1.5);
  EXPECT_EQ(v["dt"], 2e-7);
  EXPECT_EQ(v["total_energy"], 3.0 + 4.0 - 1.0);
  EXPECT_EQ(v["energy_balance_error"], 1e-4);
  EXPECT_EQ(v["plate.com_y"], 11.0);
  EXPECT_EQ(v["plate.vcom_z"], -3.0);
  EXPECT_EQ(v["plate.contact_force_x"], 7.0);
  EXPECT_EQ(v["plate.max_principal_stress"], 5e6);
  EXPECT_EQ(v["ball.com_x"], 0.0);
  EXPECT_EQ(v["floor.force_y"], 200.0);
  EXPECT_EQ(v["floor.position_z"], -0.5);
  EXPECT_EQ(v["contact.max_penetration"], 2.5e-5);
  EXPECT_EQ(v["compaction.relative_density"], 0.75);
  EXPECT_EQ(v["compaction.column_strain"], 0.125);
}

// docs/OUTPUTS.md holds the generated tables between its two markers. To refresh the doc after
// changing the table: FEMDEM_UPDATE_DOCS=1 build/test_output_tables.
TEST(OutputTables, DocsShowTheTable) {
  const std::string path = std::string(FEMDEM_SOURCE_DIR) + "/docs/OUTPUTS.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream buf;
  buf << in.rdbuf();
  std::string doc = buf.str();
  const std::string begin =
                        "<!-- output-tables:begin (generated from "
                        "tools/femdem/run/output_tables.cpp) -->\n",
                    end = "<!-- output-tables:end -->";
  const auto b = doc.find(begin), e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << "marker missing in " << path << ": " << begin;
  ASSERT_NE(e, std::string::npos) << "marker missing in " << path << ": " << end;
  const std::string generated = output_tables_markdown();
  const std::string shown = doc.substr(b + begin.size(), e - b - begin.size());
  if (shown != generated && std::getenv("FEMDEM_UPDATE_DOCS")) {
    doc.replace(b + begin.size(), e - b - begin.size(), generated);
    std::ofstream(path) << doc;
    GTEST_SKIP() << "rewrote the tables of " << path;
  }
  EXPECT_EQ(shown, generated) << "docs/OUTPUTS.md is out of date: run FEMDEM_UPDATE_DOCS=1 "
                                 "build/test_output_tables";
}

}  // namespace
}  // namespace femdem
