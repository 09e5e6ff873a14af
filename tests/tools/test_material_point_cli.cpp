// SPDX-License-Identifier: GPL-3.0-or-later
// `femdem check SCENE --material NAME --strain-path FILE`: a von Mises point under an isochoric
// uniaxial stretch F = diag(l, l^-1/2, l^-1/2) follows the closed form of Hencky + J2 with linear
// hardening: q = (sigma_y + H e) / (1 + H / 3G), e = ln l (J = 1, so Cauchy = Kirchhoff).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <vector>
#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

std::string run(const std::string& cmd, int& code) {
  const femdem::test::CommandResult r = femdem::test::run_command(cmd);
  code = r.code;
  return r.output;
}

}  // namespace

TEST(MaterialPointCli, IsochoricStretchFollowsClosedForm) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "material_point";
  fs::create_directories(d);
  std::ofstream(d / "scene.toml") << R"(title = "material point"
[simulation]
end_time = 1e-3
[[materials]]
name = "steel"
model = "von_mises"
density = 7800
youngs_modulus = 200e9
poisson_ratio = 0.3
yield_stress = 250e6
hardening_modulus = 1e9
[[bodies]]
name = "b"
material = "steel"
mesh = { generator = "box", size = [1, 1, 1], element_size = 1 }
)";
  const double l = std::exp(0.05), t = 1.0 / std::sqrt(l);
  std::ofstream path_file(d / "path.txt");
  path_file.precision(17);
  path_file << "# isochoric uniaxial stretch to e = 0.05\n"
            << l << " 0 0\t0 " << t << " 0, 0 0 " << t << "\n";
  path_file.close();
  int code = 0;
  const std::string out =
      run(std::string("'") + FEMDEM_EXE + "' check '" + (d / "scene.toml").string() +
              "' --material steel --strain-path '" + (d / "path.txt").string() + "' --substeps 50",
          code);
  ASSERT_EQ(code, 0) << out;
  std::istringstream in(out);
  std::string header, line, last;
  std::getline(in, header);
  int rows = 0;
  while (std::getline(in, line))
    if (!line.empty()) last = line, ++rows;
  EXPECT_EQ(rows, 50);
  std::vector<double> v;
  std::stringstream ls(last);
  for (std::string c; std::getline(ls, c, ',');) v.push_back(std::stod(c));
  ASSERT_EQ(v.size(), 22u);
  const double G = 200e9 / 2.6, q = (250e6 + 1e9 * 0.05) / (1.0 + 1e9 / (3.0 * G));
  EXPECT_NEAR(v[17], q, 1e-9 * q);                 // von Mises stress
  EXPECT_NEAR(v[19], 0.05 - q / (3.0 * G), 1e-9);  // equivalent plastic strain
  EXPECT_NEAR(v[11] - v[12], q, 1e-9 * q);         // sigma_xx - sigma_yy
  // a bad path file: exit 2 naming file and line
  std::ofstream(d / "bad.txt") << "1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0\n";
  const std::string bad =
      run(std::string("'") + FEMDEM_EXE + "' check '" + (d / "scene.toml").string() +
              "' --material steel --strain-path '" + (d / "bad.txt").string() + "'",
          code);
  EXPECT_EQ(code, 2) << bad;
  EXPECT_NE(bad.find("bad.txt:2"), std::string::npos) << bad;
}
