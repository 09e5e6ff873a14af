// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/mesh_generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/errors.hpp"

namespace femdem {

namespace {

constexpr double kQuarterPi = 0.78539816339744830962;

std::string fmt_g(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void require_positive(const char* generator, const char* what, double v) {
  if (!(std::isfinite(v) && v > 0.0))
    throw InputError(std::string(generator) + ": " + what + " must be a positive number, got " +
                     fmt_g(v));
}

// Cells along a length: max(1, round(l / h)), checked for absurd values before converting.
double cells_along(double l, double h) {
  return std::max(1.0, std::round(l / h));
}

void check_count(const char* generator, double elements) {
  if (!(elements <= kMaxGeneratedElements))
    throw InputError(std::string(generator) + ": element_size gives " + fmt_g(elements) +
                     " elements, more than the limit of " + fmt_g(kMaxGeneratedElements) +
                     "; use a larger element_size");
}

// A structured grid of nx x ny x nz cells, each split into 6 TET10. Nodes are the points of the
// twice-refined grid, (2nx+1) x (2ny+1) x (2nz+1), numbered x fastest.
struct Grid {
  std::array<int, 3> n{1, 1, 1};
  // Along a mirrored axis the split diagonal of a cell starts at the cell's corner nearest to
  // the middle plane of the grid (n must be even there), otherwise at its low corner.
  std::array<bool, 3> mirror{false, false, false};

  std::array<std::int64_t, 3> dims() const {
    return {2 * std::int64_t{n[0]} + 1, 2 * std::int64_t{n[1]} + 1, 2 * std::int64_t{n[2]} + 1};
  }
};

// The 10 nodes of the 6 tetrahedra of a cell, as offsets into the refined-grid node array from
// the cell's low corner, for each of the 8 combinations of step directions.
using CellTable = std::array<std::array<std::array<std::int64_t, 10>, 6>, 8>;

CellTable make_cell_table(const Grid& g) {
  const auto d = g.dims();
  static constexpr std::array<std::array<int, 3>, 6> perms = {
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};
  static constexpr std::array<int, 6> perm_sign = {1, 1, 1, -1, -1, -1};
  CellTable table{};
  for (int combo = 0; combo < 8; ++combo) {
    std::array<int, 3> s{};
    for (int a = 0; a < 3; ++a) s[a] = (combo >> a) & 1 ? -1 : 1;
    for (int t = 0; t < 6; ++t) {
      // Corners in refined-grid units (0..2 per axis): walk from the start corner along the
      // permuted axes.
      std::array<std::array<int, 3>, 4> p{};
      for (int a = 0; a < 3; ++a) p[0][a] = s[a] > 0 ? 0 : 2;
      for (int k = 0; k < 3; ++k) {
        p[k + 1] = p[k];
        p[k + 1][perms[t][k]] += 2 * s[perms[t][k]];
      }
      // det(p1 - p0, p2 - p0, p3 - p0) = sign(perm) * s0 s1 s2 (times 8): make it positive.
      if (perm_sign[t] * s[0] * s[1] * s[2] < 0) std::swap(p[1], p[2]);
      auto offset = [&](const std::array<int, 3>& q) {
        return q[0] + d[0] * (q[1] + d[1] * std::int64_t{q[2]});
      };
      for (int i = 0; i < 4; ++i) table[combo][t][i] = offset(p[i]);
      for (int e = 0; e < 6; ++e) {
        const auto& a = p[kTet10Edges[e][0]];
        const auto& b = p[kTet10Edges[e][1]];
        table[combo][t][4 + e] = offset({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2});
      }
    }
  }
  return table;
}

// Builds the mesh; map(I, J, K) gives the position of refined-grid point (I, J, K).
template <class Map>
Tet10Mesh build(const Grid& g, const Map& map) {
  const auto d = g.dims();
  Tet10Mesh mesh;
  mesh.nodes.resize(static_cast<std::size_t>(d[0] * d[1] * d[2]));
#pragma omp parallel for schedule(static)
  for (std::int64_t K = 0; K < d[2]; ++K)
    for (std::int64_t J = 0; J < d[1]; ++J)
      for (std::int64_t I = 0; I < d[0]; ++I)
        mesh.nodes[static_cast<std::size_t>(I + d[0] * (J + d[1] * K))] =
            map(static_cast<int>(I), static_cast<int>(J), static_cast<int>(K));

  const CellTable table = make_cell_table(g);
  const std::int64_t cells_per_layer = std::int64_t{g.n[0]} * g.n[1];
  mesh.elements.resize(static_cast<std::size_t>(6 * cells_per_layer * g.n[2]));
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < g.n[2]; ++k) {
    for (int j = 0; j < g.n[1]; ++j) {
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<int, 3> c{i, j, static_cast<int>(k)};
        int combo = 0;
        for (int a = 0; a < 3; ++a)
          if (g.mirror[a] && 2 * c[a] < g.n[a]) combo |= 1 << a;
        const std::int64_t base = 2 * i + d[0] * (2 * j + d[1] * 2 * k);
        std::size_t out = static_cast<std::size_t>(6 * (i + g.n[0] * (j + g.n[1] * k)));
        for (int t = 0; t < 6; ++t) {
          Tet10& el = mesh.elements[out + t];
          for (int m = 0; m < 10; ++m) el[m] = static_cast<std::int32_t>(base + table[combo][t][m]);
        }
      }
    }
  }
  return mesh;
}

// The equiangular "concentric squares/cubes -> circles/spheres" map of u in [-1, 1]^D to the
// ball of radius r: m = max |u_i| selects the shell, each coordinate u_i / m in [-1, 1] becomes
// tan(pi/4 * u_i / m) (the dominant one stays +-1), and the direction is scaled to radius r m.
template <int D>
std::array<double, D> ball_map(const std::array<double, D>& u, double r) {
  double m = 0.0;
  for (double v : u) m = std::max(m, std::abs(v));
  std::array<double, D> w{};
  if (m == 0.0) return w;
  double norm2 = 0.0;
  for (int i = 0; i < D; ++i) {
    const double t = u[i] / m;
    w[i] = std::abs(t) == 1.0 ? t : std::tan(kQuarterPi * t);
    norm2 += w[i] * w[i];
  }
  const double scale = r * m / std::sqrt(norm2);
  for (int i = 0; i < D; ++i) w[i] *= scale;
  return w;
}

Grid box_grid(const Vec3& size, double h) {
  for (int a = 0; a < 3; ++a) require_positive("box", "size", size[a]);
  require_positive("box", "element_size", h);
  const double nx = cells_along(size[0], h), ny = cells_along(size[1], h),
               nz = cells_along(size[2], h);
  check_count("box", 6.0 * nx * ny * nz);
  Grid g;
  g.n = {static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz)};
  return g;
}

Grid cylinder_grid(double radius, double length, double h) {
  require_positive("cylinder", "radius", radius);
  require_positive("cylinder", "length", length);
  require_positive("cylinder", "element_size", h);
  const double n = cells_along(radius, h), nz = cells_along(length, h);
  check_count("cylinder", 6.0 * (2 * n) * (2 * n) * nz);
  Grid g;
  g.n = {2 * static_cast<int>(n), 2 * static_cast<int>(n), static_cast<int>(nz)};
  g.mirror = {true, true, false};
  return g;
}

Grid sphere_grid(double radius, double h) {
  require_positive("sphere", "radius", radius);
  require_positive("sphere", "element_size", h);
  const double n = cells_along(radius, h);
  check_count("sphere", 6.0 * 8.0 * n * n * n);
  Grid g;
  const int c = 2 * static_cast<int>(n);
  g.n = {c, c, c};
  g.mirror = {true, true, true};
  return g;
}

std::int64_t count(const Grid& g) {
  return 6 * std::int64_t{g.n[0]} * g.n[1] * g.n[2];
}

}  // namespace

std::int64_t box_element_count(Vec3 size, double h) {
  return count(box_grid(size, h));
}
std::int64_t cylinder_element_count(double radius, double length, double h) {
  return count(cylinder_grid(radius, length, h));
}
std::int64_t sphere_element_count(double radius, double h) {
  return count(sphere_grid(radius, h));
}

Tet10Mesh generate_box(Vec3 size, double h) {
  const Grid g = box_grid(size, h);
  // Refined-grid point I along an axis of n cells sits at l * I / (2n), exact at both ends.
  const double dx = 2.0 * g.n[0], dy = 2.0 * g.n[1], dz = 2.0 * g.n[2];
  return build(g, [&](int I, int J, int K) {
    return Vec3(size[0] * (I / dx), size[1] * (J / dy), size[2] * (K / dz));
  });
}

Tet10Mesh generate_cylinder(double radius, double length, double h) {
  const Grid g = cylinder_grid(radius, length, h);
  const int N = g.n[0];  // cells across the square; refined points 0..2N map to u = -1..1
  const double dz = 2.0 * g.n[2];
  return build(g, [&](int I, int J, int K) {
    const std::array<double, 2> u{double(I - N) / N, double(J - N) / N};
    const auto p = ball_map<2>(u, radius);
    return Vec3(p[0], p[1], length * (K / dz));
  });
}

Tet10Mesh generate_sphere(double radius, double h) {
  const Grid g = sphere_grid(radius, h);
  const int N = g.n[0];
  return build(g, [&](int I, int J, int K) {
    const std::array<double, 3> u{double(I - N) / N, double(J - N) / N, double(K - N) / N};
    const auto p = ball_map<3>(u, radius);
    return Vec3(p[0], p[1], p[2]);
  });
}

}  // namespace femdem
