// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What two runs of the femdem program are compared by when they must be the same run (a
// resumed run against the uninterrupted one, a run on several ranks against one process):
// summary.json but for what measures the machine, history.csv byte for byte, every frame of
// results.h5, and the XDMF files.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace femdem::test {

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// summary.json without what measures the machine rather than the run.
inline nlohmann::json comparable_summary(const std::filesystem::path& out) {
  nlohmann::json j = nlohmann::json::parse(read_text(out / "summary.json"));
  j.erase("wall_time_s");
  j.erase("threads");
  for (const char* k :
       {"setup_time_s", "loop_time_s", "element_updates_per_s", "compaction_time_s"})
    j["extra"].erase(k);
  j["checkpoint"].erase("file");
  j["checkpoint"].erase("resume");
  return j;
}

// Every dataset under /frames of results.h5, as bytes.
inline std::vector<std::vector<char>> frames(const std::filesystem::path& out) {
  std::vector<std::vector<char>> data;
  // (SWMR: a killed run leaves the writer's mark, which plain readers refuse)
  const hid_t f =
      H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
  if (f < 0) return data;
  for (const char* name : {"time", "displacement", "velocity", "stress", "von_mises", "pressure",
                           "equivalent_plastic_strain"}) {
    const hid_t d = H5Dopen2(f, (std::string("/frames/") + name).c_str(), H5P_DEFAULT);
    const hid_t s = H5Dget_space(d);
    std::vector<char> bytes(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)) * 8);
    if (!bytes.empty()) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
    data.push_back(std::move(bytes));
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return data;
}

// The same run: summary.json (but for the machine's timings), history.csv, every frame and the
// XDMF files alike to the bit. restitution_tolerance > 0: the bodies' coefficients of
// restitution in summary.json may differ by that much, relative (a body cut among the ranks of
// a distributed run has its per-step motion summed per rank: docs/ARCHITECTURE.md).
inline void expect_same_run(const std::filesystem::path& reference,
                            const std::filesystem::path& out, double restitution_tolerance = 0.0) {
  nlohmann::json a_summary = comparable_summary(reference), b_summary = comparable_summary(out);
  if (restitution_tolerance > 0.0 && a_summary.contains("bodies") && b_summary.contains("bodies"))
    for (auto& [name, body] : a_summary["bodies"].items()) {
      if (!body.contains("coefficient_of_restitution") || !b_summary["bodies"].contains(name))
        continue;
      nlohmann::json& other = b_summary["bodies"][name]["coefficient_of_restitution"];
      for (auto& [k, e] : body["coefficient_of_restitution"].items()) {
        if (!e.is_number() || !other.contains(k) || !other[k].is_number()) continue;
        const double x = e.get<double>(), y = other[k].get<double>();
        EXPECT_LE(std::fabs(x - y), restitution_tolerance * std::fabs(x)) << name << " " << k;
        other[k] = e;  // (compared: the rest must be equal)
      }
    }
  EXPECT_EQ(a_summary, b_summary);
  EXPECT_TRUE(read_text(reference / "history.csv") == read_text(out / "history.csv"))
      << "history.csv differs from the uninterrupted run's";
  const auto a = frames(reference), b = frames(out);
  ASSERT_EQ(a.size(), 7u);
  ASSERT_EQ(b.size(), 7u);
  const char* names[] = {"time",
                         "displacement",
                         "velocity",
                         "stress",
                         "von_mises",
                         "pressure",
                         "equivalent_plastic_strain"};
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_TRUE(a[i] == b[i]) << "results.h5 /frames/" << names[i] << " differs";
  // the XDMF files a resume rebuilds from results.h5 (the walls' positions and forces in
  // walls.xdmf at full precision)
  for (const char* x : {"results.xdmf", "walls.xdmf"}) {
    EXPECT_EQ(std::filesystem::exists(reference / x), std::filesystem::exists(out / x)) << x;
    EXPECT_TRUE(read_text(reference / x) == read_text(out / x)) << x << " differs";
  }
}

}  // namespace femdem::test
