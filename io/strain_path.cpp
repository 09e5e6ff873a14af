// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/strain_path.hpp"

#include <charconv>
#include <fstream>

#include "engine/errors.hpp"

namespace femdem {

std::vector<F3> read_strain_path(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the strain path file", path);
  std::vector<F3> out;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::vector<double> v;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && line[i] == ' ') ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ') ++j;
      double x = 0.0;
      const auto [p, ec] = std::from_chars(line.data() + i, line.data() + j, x);
      if (ec != std::errc() || p != line.data() + j)
        throw InputError("'" + line.substr(i, j - i) + "' is not a number", path, line_no,
                         static_cast<int>(i) + 1);
      v.push_back(x);
      i = j;
    }
    if (v.empty()) continue;
    if (v.size() != 9)
      throw InputError("expected 9 numbers (F11 F12 F13 F21 F22 F23 F31 F32 F33), got " +
                           std::to_string(v.size()),
                       path, line_no);
    F3 F;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) F.m[r][c] = v[3 * r + c];
    const double det = F.m[0][0] * (F.m[1][1] * F.m[2][2] - F.m[1][2] * F.m[2][1]) -
                       F.m[0][1] * (F.m[1][0] * F.m[2][2] - F.m[1][2] * F.m[2][0]) +
                       F.m[0][2] * (F.m[1][0] * F.m[2][1] - F.m[1][1] * F.m[2][0]);
    if (!(det > 0.0))
      throw InputError("det F = " + std::to_string(det) + " must be positive", path, line_no);
    out.push_back(F);
  }
  if (out.empty()) throw InputError("the strain path has no deformation gradients", path);
  return out;
}

}  // namespace femdem
