// SPDX-License-Identifier: GPL-3.0-or-later
// The thesis' steel ball on a concrete prism (VALIDATION.md section 5; thesis ch. 5,
// scenes/ball_on_concrete.toml), a part of the restitution study chosen to span it: Mohr-Coulomb
// case 1 (c 15 MPa, phi 30: the highest restitution) and case 3 (c 70 MPa, phi 5: the lowest),
// each at the lowest and highest impact speeds, 4.3 and 6.35 m/s (4 of the 25 runs; the whole
// study is the sweep in the scene's header). Targets: the restitution within 0.03 of the thesis'
// simulated values (Table 5.5, the tolerance) and falling with the speed. The piece-wise
// Drucker-Prager model is not asserted: read as the notes reconstruct Table 5.6 it gives e 0.21
// at 4.3 m/s, far below the experiments (VALIDATION.md section 5 says why).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/sweep_csv.hpp"

namespace {

namespace fs = std::filesystem;

using femdem::test::split_csv_line;

}  // namespace

TEST(BallOnConcrete, RestitutionMatchesTheThesis) {
  const fs::path out = fs::path(FEMDEM_TEST_TMP) / "long" / "ball_on_concrete_sweep";
  fs::remove_all(out);
  const auto r = femdem::test::run_command(
      std::string("'") + FEMDEM_EXE + "' sweep '" + FEMDEM_SOURCE_DIR +
      "/scenes/ball_on_concrete.toml' --vary 'bodies.ball.velocity=[0,0,-4.3],[0,0,-6.35]' "
      "--vary bodies.prism.material=concrete_mc1,concrete_mc3 --jobs 1 "
      "--threads-per-job 2 --no-plot --quiet --out '" +
      out.string() + "'");
  ASSERT_EQ(r.code, 0) << r.output;

  std::ifstream in(out / "sweep.csv");
  std::string line;
  std::getline(in, line);
  const auto header = split_csv_line(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* c : {"bodies.ball.velocity", "bodies.prism.material", "status",
                        "bodies.ball.coefficient_of_restitution.com"})
    ASSERT_TRUE(col.count(c)) << c;
  // e[material][speed]
  std::map<std::string, std::map<double, double>> e;
  while (std::getline(in, line)) {
    const auto f = split_csv_line(line);
    ASSERT_EQ(f[col["status"]], "completed") << line;
    const std::string v = f[col["bodies.ball.velocity"]];
    const double speed = std::fabs(std::stod(v.substr(v.rfind(',') + 1)));
    const std::string cor = f[col["bodies.ball.coefficient_of_restitution.com"]];
    ASSERT_FALSE(cor.empty()) << "the ball did not leave the prism: " << line;
    e[f[col["bodies.prism.material"]]][speed] = std::stod(cor);
  }
  ASSERT_EQ(e.size(), 2u);

  // Thesis Table 5.5 (Mohr-Coulomb, simulated), from the CSV the plot script reads too
  std::map<std::string, std::map<double, double>> thesis;
  std::ifstream ref(std::string(FEMDEM_SOURCE_DIR) + "/scenes/ball_on_concrete_reference.csv");
  ASSERT_TRUE(ref.good());
  bool header_read = false;
  while (std::getline(ref, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header_read) {
      header_read = true;
      continue;
    }
    const auto f = split_csv_line(line);  // source,material,speed,e,e_lowest,e_highest
    if (f[0] == "table5.5") thesis[f[1]][std::stod(f[2])] = std::stod(f[3]);
  }
  ASSERT_EQ(thesis.size(), 4u);
  for (const auto& [material, by_speed] : e) {
    ASSERT_EQ(by_speed.size(), 2u) << material;
    for (const auto& [speed, cor] : by_speed) {
      const double ref_e = thesis.at(material).at(speed);
      std::printf("%s at %.2f m/s: e %.4f, thesis %.3f (%+.4f)\n", material.c_str(), speed, cor,
                  ref_e, cor - ref_e);
      EXPECT_NEAR(cor, ref_e, 0.03) << material << " at " << speed << " m/s";
    }
    EXPECT_LT(by_speed.at(6.35), by_speed.at(4.3)) << material;
  }
}
