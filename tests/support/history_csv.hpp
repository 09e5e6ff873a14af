// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// history.csv of a finished run, as columns by name (for the tests that drive femdem).
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace femdem::test {

inline std::map<std::string, std::vector<double>> read_history(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) names.push_back(c);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::size_t i = 0;
    for (std::string c; std::getline(ls, c, ',') && i < names.size(); ++i)
      cols[names[i]].push_back(std::stod(c));
  }
  return cols;
}

}  // namespace femdem::test
