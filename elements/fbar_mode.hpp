// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which F-bar variant an element uses against volumetric locking (see engine/element_kernel.hpp).
#include <optional>
#include <string>

namespace femdem {

enum class FbarMode : unsigned char { Off, VolumeAverage, Centroid };

inline const char* to_string(FbarMode m) {
  switch (m) {
    case FbarMode::Off: return "off";
    case FbarMode::VolumeAverage: return "volume_average";
    case FbarMode::Centroid: return "centroid";
  }
  return "?";
}

inline std::optional<FbarMode> parse_fbar_mode(const std::string& s) {
  if (s == "off") return FbarMode::Off;
  if (s == "volume_average") return FbarMode::VolumeAverage;
  if (s == "centroid") return FbarMode::Centroid;
  return std::nullopt;
}

}  // namespace femdem
