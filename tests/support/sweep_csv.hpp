// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// sweep.csv of `femdem sweep`: its fields may be quoted (vector values hold commas), so a line is
// split at the commas outside double quotes.
#include <string>
#include <vector>

namespace femdem::test {

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

}  // namespace femdem::test
