// SPDX-License-Identifier: GPL-3.0-or-later
// `femdem pack` (tools/femdem/pack_command.cpp): writes the packing file and reports it, the
// same seed gives the same file, and bad options exit with code 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/packing/packing.hpp"
#include "support/packing_checks.hpp"
#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::test::read_text;
using femdem::test::tmp_dir;

TEST(PackingCli, PackWritesTheFileAndReportsIt) {
  const fs::path dir = tmp_dir("cli");
  const std::string exe = std::string("'") + FEMDEM_EXE + "'";
  auto r = femdem::test::run_command(
      exe + " pack '" + (dir / "sc.csv").string() +
      "' --size 0.01,0.01,0.01 --arrangement simple_cubic --diameter 2.5e-3");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("64 particles"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.5236"), std::string::npos) << r.output;
  EXPECT_EQ(femdem::read_packing((dir / "sc.csv").string()).particles.size(), 64u);

  const std::string random = " --size 0.005,0.005,0.01 --count 40 --diameter 1e-3 --seed 5";
  r = femdem::test::run_command(exe + " pack '" + (dir / "a.csv").string() + "'" + random);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("at rest"), std::string::npos) << r.output;
  r = femdem::test::run_command(exe + " pack '" + (dir / "b.csv").string() + "'" + random);
  EXPECT_EQ(read_text(dir / "a.csv"), read_text(dir / "b.csv"));

  r = femdem::test::run_command(exe + " pack '" + (dir / "c.csv").string() +
                                "' --size 0.005,0.005,0.01 --count 40 --diameter -1");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--diameter"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "c.csv"));
  r = femdem::test::run_command(exe + " pack '" + (dir / "c.csv").string() +
                                "' --size 0.005,0.005 --count 40 --diameter 1e-3");
  EXPECT_EQ(r.code, 2) << r.output;
}

}  // namespace
