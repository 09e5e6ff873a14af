// SPDX-License-Identifier: GPL-3.0-or-later
// results.xdmf opens in ParaView as a time series of quadratic tetrahedra with every field
// (docs/OUTPUTS.md). Needs ParaView's pvbatch (Debian: paraview, python3-paraview),
// which tools/setup does not install (it is large); the test is skipped without it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "support/run_command.hpp"

namespace fs = std::filesystem;

std::string run(const std::string& cmd, int& code) {
  const femdem::test::CommandResult r = femdem::test::run_command(cmd);
  code = r.code;
  return r.output;
}

TEST(ParaView, OpensResultsAsTimeSeries) {
  if (!fs::exists("/usr/bin/pvbatch")) GTEST_SKIP() << "ParaView (pvbatch) is not installed";
  const fs::path out = fs::path(FEMDEM_TEST_TMP) / "paraview";
  fs::remove_all(out);
  int code = 0;
  const std::string r =
      run(std::string("'") + FEMDEM_EXE + "' run '" + FEMDEM_SOURCE_DIR +
              "/scenes/sphere_drop.toml' --quiet --out '" + out.string() +
              "' --set bodies.ball.mesh.element_size=3.4e-3 --set simulation.end_time=10e-6",
          code);
  ASSERT_EQ(code, 0) << r;
  const std::string pv =
      run("cd '" + out.string() + "' && /usr/bin/pvbatch '" + std::string(FEMDEM_SOURCE_DIR) +
              "/tests/io/results/paraview_open.py' '" + (out / "results.xdmf").string() + "'",
          code);
  ASSERT_EQ(code, 0) << pv;
  std::map<std::string, std::string> kv;
  std::map<std::string, int> arrays;
  std::istringstream in(pv);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string key, value;
    ls >> key >> value;
    if (key == "array") {
      int comps = 0;
      ls >> comps;
      arrays[value] = comps;
    } else {
      kv[key] = value;
    }
  }
  EXPECT_EQ(kv["timesteps"], "6") << pv;  // t = 0, 2, 4, 6, 8, 10 us
  EXPECT_NEAR(std::stod(kv["last_time"]), 10e-6, 1e-12);
  EXPECT_EQ(kv["cells"], "1296");
  EXPECT_EQ(kv["cell_type"], "24");  // VTK_QUADRATIC_TETRA
  EXPECT_EQ(arrays["displacement"], 3);
  EXPECT_EQ(arrays["velocity"], 3);
  EXPECT_EQ(arrays["stress"], 9);
  EXPECT_EQ(arrays["von_mises"], 1);
  EXPECT_EQ(arrays["pressure"], 1);
  EXPECT_EQ(arrays["equivalent_plastic_strain"], 1);
}
