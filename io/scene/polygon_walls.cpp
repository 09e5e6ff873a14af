// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/scene/polygon_walls.hpp"

#include <cmath>

namespace femdem::scene {

std::vector<WallSpec> polygon_walls(const std::string& prefix, const PolygonPrism& prism) {
  const Vec3& axis = prism.axis;
  Vec3 e1 = std::fabs(axis.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  e1 = (e1 - e1.dot(axis) * axis).normalized();
  const Vec3 e2 = axis.cross(e1);
  const double pi = std::acos(-1.0);
  const double s0 = prism.centre.dot(axis);
  std::vector<WallSpec> walls;
  for (int k = 0; k < prism.sides; ++k) {
    const double th = prism.angle * pi / 180.0 + 2.0 * pi * k / prism.sides;
    const Vec3 u = std::cos(th) * e1 + std::sin(th) * e2;
    WallSpec w;
    w.name = prefix + "_" + std::to_string(k + 1);
    w.point = prism.centre + prism.radius * u;
    w.normal = -u;
    if (prism.from || prism.to) {
      w.bounded = true;
      w.bound_axis = axis;
      if (prism.from) w.bound_min = s0 + *prism.from;
      if (prism.to) w.bound_max = s0 + *prism.to;
    }
    walls.push_back(w);
  }
  return walls;
}

double polygon_side(double r, int sides) {
  return 2.0 * r * std::tan(std::acos(-1.0) / static_cast<double>(sides));
}

double polygon_area(double r, int sides) {
  return 0.5 * r * polygon_side(r, sides) * static_cast<double>(sides);
}

}  // namespace femdem::scene
