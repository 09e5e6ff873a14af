// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/mesh/mesh_generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

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
            map(static_cast<double>(I), static_cast<double>(J), static_cast<double>(K));

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

// ---- Local refinement by newest-vertex (Maubach) bisection, see the header. ----

// Parameter-space units per grid cell: vertices of the refined mesh have integer coordinates in
// these units, so every bisection midpoint is exact. 2^24 allows 24 halvings (72 bisections)
// of a cell, far more than the element limit permits.
constexpr std::int64_t kSub = std::int64_t{1} << 24;

struct BisectTet {
  std::array<std::int32_t, 4> v;  // Maubach order: the refinement edge is v[0]-v[tag]
  int tag;                        // 1..3
};

struct RefineSpec {
  const char* generator;
  double h;
  double distance_to_body;  // of the refine point
  double body_diameter;     // an upper bound of the distance between two points of the body
};

void check_refinement(const RefineSpec& spec, const MeshRefinement& r) {
  const char* gen = spec.generator;
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(r.point[a]))
      throw InputError(std::string(gen) + ": refine_point must be three finite numbers");
  require_positive(gen, "refine_size", r.size);
  if (r.size > spec.h)
    throw InputError(std::string(gen) + ": refine_size (" + fmt_g(r.size) +
                     ") must not be larger than element_size (" + fmt_g(spec.h) + ")");
  if (spec.h > 1e6 * r.size)  // 20 halvings of a cell; the vertex coordinates allow 24
    throw InputError(std::string(gen) + ": refine_size (" + fmt_g(r.size) +
                     ") must be at least element_size / 1e6");
  if (!(std::isfinite(r.radius) && r.radius >= 0.0))
    throw InputError(std::string(gen) + ": refine_radius must be a number >= 0, got " +
                     fmt_g(r.radius));
  if (!(std::isfinite(r.growth) && r.growth > 0.0 && r.growth <= 2.0))
    throw InputError(std::string(gen) + ": refine_growth must be in (0, 2], got " +
                     fmt_g(r.growth));
  if (spec.distance_to_body > r.radius + 1e-12 * spec.body_diameter)
    throw InputError(std::string(gen) + ": refine_point is " + fmt_g(spec.distance_to_body) +
                     " m from the body, farther than refine_radius (" + fmt_g(r.radius) +
                     "); it is given in the mesh's own frame, before position and rotation");
}

// Elements of a size field with target(d) = min(h, size + growth * max(0, d - radius)) in a
// ball of diameter-of-the-body radius around the point: 6 V / target^3, an upper bound (about
// twice the count for a point on the surface), used to fail fast before refining.
double estimate_refined_elements(const RefineSpec& spec, const MeshRefinement& r) {
  const int steps = 4000;
  const double D = spec.body_diameter, dd = D / steps;
  double n = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double d = (i + 0.5) * dd;
    const double t = std::min(spec.h, r.size + r.growth * std::max(0.0, d - r.radius));
    n += 6.0 * 4.0 * 3.14159265358979323846 * d * d * dd / (t * t * t);
  }
  return n;
}

template <class Map>
Tet10Mesh build_refined(const Grid& g, const Map& map, const MeshRefinement& r,
                        const RefineSpec& spec) {
  check_refinement(spec, r);
  const double estimate = estimate_refined_elements(spec, r);
  if (!(estimate <= kMaxGeneratedElements))
    throw InputError(std::string(spec.generator) + ": refine_size gives about " + fmt_g(estimate) +
                     " elements, more than the limit of " + fmt_g(kMaxGeneratedElements) +
                     "; use a larger refine_size or refine_growth");

  // Parameter-space points in half-cell units, the argument of `map`.
  auto mapped = [&](const std::array<std::int64_t, 3>& c, double scale) {
    return map(scale * static_cast<double>(c[0]), scale * static_cast<double>(c[1]),
               scale * static_cast<double>(c[2]));
  };
  constexpr double kToHalfCells = 2.0 / static_cast<double>(kSub);

  // Grid corners.
  const std::array<std::int64_t, 3> nv{std::int64_t{g.n[0]} + 1, std::int64_t{g.n[1]} + 1,
                                       std::int64_t{g.n[2]} + 1};
  std::vector<std::array<std::int64_t, 3>> coord;
  coord.reserve(static_cast<std::size_t>(nv[0] * nv[1] * nv[2]));
  for (std::int64_t k = 0; k < nv[2]; ++k)
    for (std::int64_t j = 0; j < nv[1]; ++j)
      for (std::int64_t i = 0; i < nv[0]; ++i) coord.push_back({i * kSub, j * kSub, k * kSub});
  std::vector<Vec3> pos(coord.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(coord.size()); ++i)
    pos[static_cast<std::size_t>(i)] = mapped(coord[static_cast<std::size_t>(i)], kToHalfCells);

  // The Kuhn tetrahedra of every cell as tagged simplices: the path from the start corner
  // along the three axes in a permuted order, the refinement edge being the cell diagonal.
  static constexpr std::array<std::array<int, 3>, 6> perms = {
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};
  std::vector<BisectTet> tets;
  tets.reserve(static_cast<std::size_t>(count(g)));
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::array<int, 3> c{i, j, k};
        std::array<int, 3> start{}, step{};
        for (int a = 0; a < 3; ++a) {
          const bool flip = g.mirror[a] && 2 * c[a] < g.n[a];
          start[a] = c[a] + (flip ? 1 : 0);
          step[a] = flip ? -1 : 1;
        }
        for (const auto& perm : perms) {
          BisectTet t{};
          t.tag = 3;
          std::array<int, 3> q = start;
          for (int m = 0; m < 4; ++m) {
            if (m > 0) q[perm[m - 1]] += step[perm[m - 1]];
            t.v[m] = static_cast<std::int32_t>(q[0] + nv[0] * (q[1] + nv[1] * std::int64_t{q[2]}));
          }
          tets.push_back(t);
        }
      }

  // Bisection until every element is small enough and none holds a bisected edge.
  const double slack = std::pow(2.0, 1.0 / 6.0);  // half a bisection, in size
  auto too_big = [&](const BisectTet& t) {
    const Vec3& x0 = pos[t.v[0]];
    const Vec3& x1 = pos[t.v[1]];
    const Vec3& x2 = pos[t.v[2]];
    const Vec3& x3 = pos[t.v[3]];
    // Element size: the mean corner-to-corner edge length.
    const double size = ((x1 - x0).norm() + (x2 - x1).norm() + (x0 - x2).norm() + (x3 - x0).norm() +
                         (x3 - x1).norm() + (x3 - x2).norm()) /
                        6.0;
    const Vec3 centre = 0.25 * (x0 + x1 + x2 + x3);
    const double reach =
        std::sqrt(std::max({(x0 - centre).squaredNorm(), (x1 - centre).squaredNorm(),
                            (x2 - centre).squaredNorm(), (x3 - centre).squaredNorm()}));
    const double d = std::max(0.0, (centre - r.point).norm() - reach);
    const double target = r.size + r.growth * std::max(0.0, d - r.radius);
    return size > slack * target;
  };
  auto edge_key = [](std::int32_t a, std::int32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  std::unordered_map<std::uint64_t, std::int32_t> midpoint;  // bisected edge -> new vertex
  std::vector<BisectTet> next;
  for (int pass = 0;; ++pass) {
    if (pass > 10000) throw std::logic_error("mesh refinement does not terminate");
    next.clear();
    next.reserve(tets.size() + tets.size() / 2);
    bool changed = false;
    for (const BisectTet& t : tets) {
      bool split = too_big(t);
      for (int e = 0; e < 6 && !split && !midpoint.empty(); ++e)
        split = midpoint.count(edge_key(t.v[kTet10Edges[e][0]], t.v[kTet10Edges[e][1]])) > 0;
      if (!split) {
        next.push_back(t);
        continue;
      }
      changed = true;
      const int k = t.tag;
      const std::uint64_t key = edge_key(t.v[0], t.v[k]);
      auto it = midpoint.find(key);
      std::int32_t z;
      if (it != midpoint.end()) {
        z = it->second;
      } else {
        const auto& a = coord[t.v[0]];
        const auto& b = coord[t.v[k]];
        std::array<std::int64_t, 3> m{};
        for (int i = 0; i < 3; ++i) {
          if ((a[i] + b[i]) % 2 != 0)
            throw InputError(std::string(spec.generator) +
                             ": refine_size is too small for the refinement depth limit");
          m[i] = (a[i] + b[i]) / 2;
        }
        if (coord.size() >= static_cast<std::size_t>(INT32_MAX))
          throw InputError(std::string(spec.generator) + ": too many nodes");
        z = static_cast<std::int32_t>(coord.size());
        coord.push_back(m);
        pos.push_back(mapped(m, kToHalfCells));
        midpoint.emplace(key, z);
      }
      // Maubach: T1 = (x0, .., x_{k-1}, z, x_{k+1}, .., x3), T2 = (x1, .., x_k, z, x_{k+1}, ..
      // x3), both with tag k - 1 (or 3 after 1).
      BisectTet c1{}, c2{};
      c1.tag = c2.tag = k > 1 ? k - 1 : 3;
      for (int i = 0; i < 4; ++i) c1.v[i] = t.v[i];
      c1.v[k] = z;
      for (int i = 0; i < k; ++i) c2.v[i] = t.v[i + 1];
      c2.v[k] = z;
      for (int i = k + 1; i < 4; ++i) c2.v[i] = t.v[i];
      next.push_back(c1);
      next.push_back(c2);
    }
    tets.swap(next);
    if (!changed) break;
    if (!(static_cast<double>(tets.size()) <= kMaxGeneratedElements))
      throw InputError(std::string(spec.generator) + ": refinement gives more than " +
                       fmt_g(kMaxGeneratedElements) + " elements; use a larger refine_size");
  }

  // TET10: right-handed corners, then one mapped parameter-space midpoint per edge.
  Tet10Mesh mesh;
  const std::size_t corners = coord.size();
  mesh.nodes = std::move(pos);
  mesh.elements.resize(tets.size());
  std::unordered_map<std::uint64_t, std::int32_t> edge_node;
  edge_node.reserve(tets.size() * 2);
  constexpr double kMidToHalfCells = 1.0 / static_cast<double>(kSub);  // (a + b) / 2 * 2 / kSub
  for (std::size_t e = 0; e < tets.size(); ++e) {
    std::array<std::int32_t, 4> v = tets[e].v;
    std::array<double, 3> d1{}, d2{}, d3{};
    for (int i = 0; i < 3; ++i) {
      d1[i] = static_cast<double>(coord[v[1]][i] - coord[v[0]][i]);
      d2[i] = static_cast<double>(coord[v[2]][i] - coord[v[0]][i]);
      d3[i] = static_cast<double>(coord[v[3]][i] - coord[v[0]][i]);
    }
    const double det = d1[0] * (d2[1] * d3[2] - d2[2] * d3[1]) -
                       d1[1] * (d2[0] * d3[2] - d2[2] * d3[0]) +
                       d1[2] * (d2[0] * d3[1] - d2[1] * d3[0]);
    if (det < 0.0) std::swap(v[1], v[2]);
    Tet10& el = mesh.elements[e];
    for (int i = 0; i < 4; ++i) el[i] = v[i];
    for (int m = 0; m < 6; ++m) {
      const std::int32_t a = v[kTet10Edges[m][0]], b = v[kTet10Edges[m][1]];
      const auto [it, added] = edge_node.emplace(
          edge_key(a, b), static_cast<std::int32_t>(corners + (mesh.nodes.size() - corners)));
      if (added) {
        const std::array<std::int64_t, 3> sum{coord[a][0] + coord[b][0], coord[a][1] + coord[b][1],
                                              coord[a][2] + coord[b][2]};
        mesh.nodes.push_back(mapped(sum, kMidToHalfCells));
      }
      el[4 + m] = it->second;
    }
  }
  return mesh;
}

// The uniform grid, or the refined one.
template <class Map>
Tet10Mesh build_mesh(const Grid& g, const Map& map, const std::optional<MeshRefinement>& refine,
                     const RefineSpec& spec) {
  if (!refine) return build(g, map);
  return build_refined(g, map, *refine, spec);
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
  return generate_box(size, h, std::nullopt);
}
Tet10Mesh generate_cylinder(double radius, double length, double h) {
  return generate_cylinder(radius, length, h, std::nullopt);
}
Tet10Mesh generate_sphere(double radius, double h) {
  return generate_sphere(radius, h, std::nullopt);
}

Tet10Mesh generate_box(Vec3 size, double h, const std::optional<MeshRefinement>& refine) {
  const Grid g = box_grid(size, h);
  const RefineSpec spec{
      "box", h,
      refine ? (refine->point - refine->point.cwiseMax(Vec3::Zero()).cwiseMin(size)).norm() : 0.0,
      size.norm()};
  // Refined-grid point I along an axis of n cells sits at l * I / (2n), exact at both ends.
  const double dx = 2.0 * g.n[0], dy = 2.0 * g.n[1], dz = 2.0 * g.n[2];
  return build_mesh(
      g,
      [&](double I, double J, double K) {
        return Vec3(size[0] * (I / dx), size[1] * (J / dy), size[2] * (K / dz));
      },
      refine, spec);
}

Tet10Mesh generate_cylinder(double radius, double length, double h,
                            const std::optional<MeshRefinement>& refine) {
  const Grid g = cylinder_grid(radius, length, h);
  double dist = 0.0;
  if (refine) {
    const Vec3& q = refine->point;
    const double dr = std::max(0.0, std::hypot(q[0], q[1]) - radius);
    const double dz = std::max({0.0, -q[2], q[2] - length});
    dist = std::hypot(dr, dz);
  }
  const RefineSpec spec{"cylinder", h, dist, std::hypot(2.0 * radius, length)};
  const int N = g.n[0];  // cells across the square; refined points 0..2N map to u = -1..1
  const double dz = 2.0 * g.n[2];
  return build_mesh(
      g,
      [&](double I, double J, double K) {
        const std::array<double, 2> u{(I - N) / N, (J - N) / N};
        const auto p = ball_map<2>(u, radius);
        return Vec3(p[0], p[1], length * (K / dz));
      },
      refine, spec);
}

Tet10Mesh generate_sphere(double radius, double h, const std::optional<MeshRefinement>& refine) {
  const Grid g = sphere_grid(radius, h);
  const RefineSpec spec{"sphere", h, refine ? std::max(0.0, refine->point.norm() - radius) : 0.0,
                        2.0 * radius};
  const int N = g.n[0];
  return build_mesh(
      g,
      [&](double I, double J, double K) {
        const std::array<double, 3> u{(I - N) / N, (J - N) / N, (K - N) / N};
        const auto p = ball_map<3>(u, radius);
        return Vec3(p[0], p[1], p[2]);
      },
      refine, spec);
}

}  // namespace femdem
