// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Internals of the packing generator (io/packing/*.cpp only; the public interface is
// packing.hpp): the random numbers, the container geometry and the cell grid shared by the
// parameter checks (packing_params.cpp), the lattices (lattice_packing.cpp), the random
// placement and settling DEM (random_packing.cpp), generation and statistics
// (generate_packing.cpp) and the packing file (packing_file.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "io/packing/packing.hpp"

namespace femdem::packing_detail {

constexpr double kPi = std::numbers::pi;

// Throws InputError with the parameter's name as its key.
[[noreturn]] void bad(const std::string& key, const std::string& message);
// Shortest round-trip form, always a TOML float.
std::string num(double v);
bool is_lattice(const std::string& a);
// Most lattice sites a container may be searched for: more particles than a model can hold (each
// body has tens of elements at least, a model at most kMaxGeneratedElements = 2e7).
constexpr double kMaxLatticeSites = 1e6;
// Widest and highest container of a random packing, in largest particle diameters (its settling
// grid indexes cells in 20 bits, +-2^19, across; the column above the bed needs room too).
constexpr double kMaxRandomContainerDiameters = 1e5;

// ---------------------------------------------------------------------------------------------
// Random numbers. std::mt19937_64's sequence is fixed by the standard, but the standard
// distributions are not (each library draws differently), so the draws are done here: the same
// seed gives the same packing with any compiler.

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  double normal() {  // Box-Muller; the second value is dropped to keep the stream simple
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }
  // A uniformly distributed rotation (Shoemake's method).
  Eigen::Quaterniond rotation() {
    const double u1 = uniform(), u2 = uniform(), u3 = uniform();
    const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    Eigen::Quaterniond q(a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2),
                         b * std::sin(2 * kPi * u3), b * std::cos(2 * kPi * u3));
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // one sign for each rotation
    return q.normalized();
  }

 private:
  std::mt19937_64 engine_;
};

// A seed for stream `stream` (0: sizes, 1: positions, 2: orientations) of a packing's seed.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream);
// mu of ln d for the lognormal distribution of mean diameter_mean.
double lognormal_mu(const PackingParams& p);
// Largest and smallest diameters the distribution can produce.
double max_diameter(const PackingParams& p);
double min_diameter(const PackingParams& p);
// The first n diameters of the size distribution (resolved parameters).
std::vector<double> draw_diameters(const PackingParams& p, std::int64_t n);

// Container geometry in one place.
struct Container {
  bool cylinder = false;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // bounding box (hi.z = the container's height)
  double radius = 0.0;
  explicit Container(const PackingParams& p) {
    cylinder = p.container == "cylinder";
    if (cylinder) {
      radius = p.radius;
      lo = Vec3(-p.radius, -p.radius, 0.0);
      hi = Vec3(p.radius, p.radius, p.height);
    } else {
      hi = p.size;
    }
  }
  double section() const {
    return cylinder ? kPi * radius * radius : (hi.x() - lo.x()) * (hi.y() - lo.y());
  }
  // Whether a sphere of radius r at c lies inside (ignoring the top when `open_top`).
  bool holds(const Vec3& c, double r, bool open_top, double tol = 0.0) const {
    if (c.z() - r < lo.z() - tol) return false;
    if (!open_top && c.z() + r > hi.z() + tol) return false;
    if (cylinder) return std::hypot(c.x(), c.y()) + r <= radius + tol;
    return c.x() - r >= lo.x() - tol && c.x() + r <= hi.x() + tol && c.y() - r >= lo.y() - tol &&
           c.y() + r <= hi.y() + tol;
  }
};

// A uniform grid of cubic-ish cells over a fixed box; positions outside are clamped into the
// border cells, which keeps neighbours within one cell of each other (clamping is monotone).
struct CellGrid {
  Vec3 origin = Vec3::Zero();
  std::array<int, 3> n = {1, 1, 1};
  Vec3 inv_cell = Vec3::Ones();
  std::vector<int> start, order, cell_of;

  // At most this many cells (8 MB of counts): particles tiny against their container (found by
  // fuzzing: 1e-8 m grains in a 6 mm cylinder asked for 2^30 cells, 4 GB) get larger cells,
  // which only makes the neighbour search visit more candidates.
  static constexpr double kMaxCells = double(1 << 21);

  void setup(const Vec3& lo, const Vec3& hi, double min_cell) {
    origin = lo;
    Vec3 ext;
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
      ext[a] = std::max(hi[a] - lo[a], min_cell);
      cells *= std::max(1.0, std::floor(ext[a] / min_cell));
    }
    // the smallest cell size the cap allows, the same on every axis
    const double cell = cells > kMaxCells ? min_cell * std::cbrt(cells / kMaxCells) : min_cell;
    for (int a = 0; a < 3; ++a) {
      const double k = std::clamp(std::floor(ext[a] / cell), 1.0, double(1 << 10));
      n[static_cast<std::size_t>(a)] = static_cast<int>(k);
      inv_cell[a] = n[static_cast<std::size_t>(a)] / ext[a];
    }
    start.assign(static_cast<std::size_t>(n[0]) * n[1] * n[2] + 1, 0);
  }
  int coord(const Vec3& x, int a) const {
    const int c = static_cast<int>(std::floor((x[a] - origin[a]) * inv_cell[a]));
    return std::clamp(c, 0, n[static_cast<std::size_t>(a)] - 1);
  }
  int index(int i, int j, int k) const { return (k * n[1] + j) * n[0] + i; }
  // Counting sort of the particles by cell: a fixed order, no allocation after the first call.
  void build(const std::vector<Vec3>& x) {
    cell_of.resize(x.size());
    order.resize(x.size());
    std::fill(start.begin(), start.end(), 0);
    for (std::size_t p = 0; p < x.size(); ++p) {
      cell_of[p] = index(coord(x[p], 0), coord(x[p], 1), coord(x[p], 2));
      ++start[static_cast<std::size_t>(cell_of[p]) + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<int>& fill = scratch_;
    fill.assign(start.begin(), start.end() - 1);
    for (std::size_t p = 0; p < x.size(); ++p)
      order[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[p])]++)] =
          static_cast<int>(p);
  }
  // Calls f(q) for every particle q in the 27 cells around point x.
  template <class F>
  void around(const Vec3& x, F&& f) const {
    const int ci = coord(x, 0), cj = coord(x, 1), ck = coord(x, 2);
    for (int k = std::max(0, ck - 1); k <= std::min(n[2] - 1, ck + 1); ++k)
      for (int j = std::max(0, cj - 1); j <= std::min(n[1] - 1, cj + 1); ++j)
        for (int i = std::max(0, ci - 1); i <= std::min(n[0] - 1, ci + 1); ++i) {
          const int c = index(i, j, k);
          for (int s = start[static_cast<std::size_t>(c)];
               s < start[static_cast<std::size_t>(c) + 1]; ++s)
            f(order[static_cast<std::size_t>(s)]);
        }
  }

 private:
  std::vector<int> scratch_;
};

// The particles on the lattice of p.arrangement, bottom layers first.
std::vector<PackedParticle> lattice_packing(const PackingParams& p);
// The particles dropped and settled (the settling fields of `stats` filled), bottom first.
std::vector<PackedParticle> random_packing(const PackingParams& p, PackingStats& stats);

}  // namespace femdem::packing_detail
