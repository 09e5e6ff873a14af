// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "io/packing/packing_internal.hpp"

namespace femdem::packing_detail {

// ---------------------------------------------------------------------------------------------
// Lattices

std::vector<PackedParticle> lattice_packing(const PackingParams& p) {
  const Container box(p);
  const double d = p.diameter, r = 0.5 * d;
  std::vector<Vec3> basis;
  double a = d;  // cubic cell edge for touching neighbours
  if (p.arrangement == "simple_cubic") {
    basis = {Vec3(0, 0, 0)};
  } else if (p.arrangement == "body_centred_cubic") {
    a = 2.0 * d / std::sqrt(3.0);  // neighbours touch along the body diagonal
    basis = {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5)};
  } else {
    a = std::sqrt(2.0) * d;  // neighbours touch along the face diagonals
    basis = {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0, 0.5), Vec3(0, 0.5, 0.5)};
  }
  // Lattice sites from the container's low corner + r (a box) or around the axis (a cylinder),
  // kept when the sphere fits; a relative tolerance lets an exact fit (4 spheres of 2.5 mm in
  // 10 mm) count despite rounding.
  const double tol = 1e-9 * d;
  const Vec3 origin = box.cylinder ? Vec3(0.0, 0.0, r) : Vec3(r, r, r);
  const Vec3 extent = box.hi - box.lo;
  // Cells per axis: a box's own extents; a cylinder's square about its axis.
  const double cells_z = std::floor(extent.z() / a) + 2.0;
  const double cells_x =
      std::floor((box.cylinder ? std::max(extent.x(), extent.y()) : extent.x()) / a) + 2.0;
  const double cells_y =
      std::floor((box.cylinder ? std::max(extent.x(), extent.y()) : extent.y()) / a) + 2.0;
  // Refused before it is searched: a lattice this fine is more particles than a model can hold,
  // and searching it would take minutes.
  const double candidates =
      cells_z * (box.cylinder ? 4.0 : 1.0) * cells_x * cells_y * static_cast<double>(basis.size());
  if (!(candidates <= kMaxLatticeSites))
    bad("diameter", "the lattice would have up to " +
                        std::to_string(static_cast<long long>(std::min(candidates, 1e18))) +
                        " sites in the container, more than " +
                        std::to_string(static_cast<long long>(kMaxLatticeSites)) +
                        ": use a larger diameter or a smaller container");
  const int nz = static_cast<int>(cells_z);
  const int nx = static_cast<int>(cells_x), ny = static_cast<int>(cells_y);
  const int x_from = box.cylinder ? -nx : 0, y_from = box.cylinder ? -ny : 0;
  std::vector<Vec3> sites;
  for (int k = 0; k < nz; ++k)
    for (int j = y_from; j < ny; ++j)
      for (int i = x_from; i < nx; ++i)
        for (const Vec3& b : basis) {
          const Vec3 c = origin + a * (Vec3(i, j, k) + b);
          if (box.holds(c, r, false, tol)) sites.push_back(c);
        }
  if (sites.empty()) bad("diameter", "no particle fits in the container");
  // A box's lattice is centred horizontally (its block sits on the floor).
  if (!box.cylinder) {
    Vec3 lo = sites.front(), hi = sites.front();
    for (const Vec3& c : sites) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    for (int ax = 0; ax < 2; ++ax) {
      const double shift = 0.5 * ((box.hi[ax] - r - hi[ax]) - (lo[ax] - r - box.lo[ax]));
      if (std::abs(shift) > tol)  // an exact fit keeps its exact sites
        for (Vec3& c : sites) c[ax] += shift;
    }
  }
  std::sort(sites.begin(), sites.end(), [](const Vec3& u, const Vec3& v) {
    return std::tie(u.z(), u.y(), u.x()) < std::tie(v.z(), v.y(), v.x());
  });
  if (p.count > 0) {
    if (static_cast<std::size_t>(p.count) > sites.size())
      bad("count", "only " + std::to_string(sites.size()) + " particles fit on this lattice, " +
                       std::to_string(p.count) + " asked");
    sites.resize(static_cast<std::size_t>(p.count));
  }
  std::vector<PackedParticle> out(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    out[i].centre = sites[i];
    out[i].radius = r;
  }
  return out;
}

}  // namespace femdem::packing_detail
