// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Small text helpers of the program's printed summaries.
#include <fmt/core.h>

#include <string>

#include "elements/tet10_mesh.hpp"

namespace femdem {

// "[x, y, z]" with %g numbers.
inline std::string vec(const Vec3& v) {
  return fmt::format("[{:g}, {:g}, {:g}]", v.x(), v.y(), v.z());
}

// `text` with `prefix` before each line, ending with a line break.
inline std::string indent(const std::string& text, const std::string& prefix) {
  std::string out = prefix;
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '\n' && i + 1 < text.size()) out += prefix;
  }
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}

}  // namespace femdem
