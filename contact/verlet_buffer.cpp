// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/verlet_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace femdem {

VerletBuffer::VerletBuffer(double buffer) : buffer_(buffer) {
  if (!(buffer > 0.0) || !std::isfinite(buffer))
    throw std::invalid_argument("VerletBuffer: buffer must be positive and finite, got " +
                                std::to_string(buffer));
}

void VerletBuffer::record(std::span<const Vec3> positions) {
  reference_.assign(positions.begin(), positions.end());
  recorded_ = true;
}

double VerletBuffer::max_displacement(std::span<const Vec3> positions) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!recorded_ || positions.size() != reference_.size()) return kInf;
  double worst2 = 0.0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const double d2 = (positions[k] - reference_[k]).squaredNorm();
    if (!(d2 <= worst2)) {
      if (!std::isfinite(d2)) return kInf;
      worst2 = d2;
    }
  }
  return std::sqrt(worst2);
}

bool VerletBuffer::needs_rebuild(std::span<const Vec3> positions) const {
  return max_displacement(positions) > margin();
}

}  // namespace femdem
