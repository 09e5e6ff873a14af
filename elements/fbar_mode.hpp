// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Which F-bar variant an element uses against volumetric locking (see engine/element_kernel.hpp).
#include <optional>
#include <string>

namespace femdem {

// Nodal: J0 interpolated linearly from corner-node values, each the volume ratio of the elements
// around that corner (a continuous linear volume field under quadratic displacements, as in
// the stable P2/P1 pair).
// SubTet: J0 from the volume of the 8 linear sub-tetrahedra that the mid-edge nodes cut the
// element into. Unlike the element volume (and det F at the centre), whose derivative with
// respect to a TET10 corner node vanishes, it lets the mean pressure act on the corner nodes too.
enum class FbarMode : unsigned char { Off, VolumeAverage, Centroid, Nodal, SubTet };

inline const char* to_string(FbarMode m) {
  switch (m) {
    case FbarMode::Off:
      return "off";
    case FbarMode::VolumeAverage:
      return "volume_average";
    case FbarMode::Centroid:
      return "centroid";
    case FbarMode::Nodal:
      return "nodal";
    case FbarMode::SubTet:
      return "subtet";
  }
  return "?";
}

inline std::optional<FbarMode> parse_fbar_mode(const std::string& s) {
  if (s == "off") return FbarMode::Off;
  if (s == "volume_average") return FbarMode::VolumeAverage;
  if (s == "centroid") return FbarMode::Centroid;
  if (s == "nodal") return FbarMode::Nodal;
  if (s == "subtet") return FbarMode::SubTet;
  return std::nullopt;
}

}  // namespace femdem
