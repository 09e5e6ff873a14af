// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/errors.hpp"
#include "femdem_version.hpp"
#include "io/packing/packing.hpp"
#include "io/packing/packing_internal.hpp"

namespace femdem {

namespace packing_detail {

// Separate streams for sizes, positions and orientations: changing the container does not
// change the sizes, and turning orientations on does not move the particles.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);  // SplitMix64
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::vector<double> draw_diameters(const PackingParams& p, std::int64_t n) {
  std::vector<double> d(static_cast<std::size_t>(n));
  Random rng(stream_seed(p.seed, 0));
  for (double& x : d) {
    if (p.distribution == "monodisperse") {
      x = p.diameter;
    } else if (p.distribution == "uniform") {
      x = rng.uniform(p.diameter_min, p.diameter_max);
    } else {
      // Truncation by redrawing; check_packing_params keeps the window wide enough that this
      // ends quickly (it holds at least 1 % of the distribution).
      const double mu = lognormal_mu(p);
      do {
        x = std::exp(mu + p.sigma * rng.normal());
      } while (x < p.diameter_min || x > p.diameter_max);
    }
  }
  return d;
}

}  // namespace packing_detail

using packing_detail::bad;
using packing_detail::CellGrid;
using packing_detail::Container;
using packing_detail::draw_diameters;
using packing_detail::is_lattice;
using packing_detail::kPi;
using packing_detail::lattice_packing;
using packing_detail::Random;
using packing_detail::random_packing;
using packing_detail::stream_seed;

// ---------------------------------------------------------------------------------------------
// Generation and statistics

std::vector<double> packing_diameters(const PackingParams& params, std::int64_t n) {
  if (auto e = check_packing_params(params)) bad(e->key, e->message);
  return draw_diameters(resolve_packing_params(params), n);
}

void measure_packing(const PackingParams& params, Packing& packing) {
  const Container box(resolve_packing_params(params));
  PackingStats& s = packing.stats;
  const auto& ps = packing.particles;
  s.particle_volume = 0.0;
  s.bed_height = 0.0;
  double rmax = 0.0;
  for (const auto& q : ps) {
    s.particle_volume += 4.0 / 3.0 * kPi * q.radius * q.radius * q.radius;
    s.bed_height = std::max(s.bed_height, q.centre.z() + q.radius - box.lo.z());
    rmax = std::max(rmax, q.radius);
  }
  s.packing_fraction = s.bed_height > 0.0 ? s.particle_volume / (box.section() * s.bed_height) : 0;
  s.container_fraction = s.particle_volume / (box.section() * (box.hi.z() - box.lo.z()));

  std::vector<Vec3> x(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) x[i] = ps[i].centre;
  CellGrid grid;
  grid.setup(box.lo, Vec3(box.hi.x(), box.hi.y(), std::max(box.hi.z(), s.bed_height)),
             std::max(2.0 * rmax, 1e-300));
  grid.build(x);
  s.min_gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ps.size(); ++i)
    grid.around(x[i], [&](int j) {
      if (static_cast<std::size_t>(j) <= i) return;
      const double rs = ps[i].radius + ps[static_cast<std::size_t>(j)].radius;
      s.min_gap = std::min(s.min_gap, ((x[static_cast<std::size_t>(j)] - x[i]).norm() - rs) / rs);
    });

  // Core fraction: a regular grid of sample points in the core, each tested against the
  // particles of its cells.
  const double margin = 4.0 * rmax;
  Vec3 lo = box.lo + Vec3(margin, margin, margin);
  Vec3 hi = Vec3(box.hi.x(), box.hi.y(), box.lo.z() + s.bed_height) - Vec3(margin, margin, margin);
  if (box.cylinder) {
    const double h = (box.radius - margin) / std::sqrt(2.0);  // the square inside the core disc
    lo.x() = lo.y() = -h;
    hi.x() = hi.y() = h;
  }
  if (!(hi.x() > lo.x() && hi.y() > lo.y() && hi.z() > lo.z())) {
    s.core_packing_fraction = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double step = std::max((hi - lo).maxCoeff() / 80.0, rmax / 10.0);
  std::int64_t inside = 0, total = 0;
  for (double z = lo.z() + 0.5 * step; z < hi.z(); z += step)
    for (double y = lo.y() + 0.5 * step; y < hi.y(); y += step)
      for (double xx = lo.x() + 0.5 * step; xx < hi.x(); xx += step) {
        const Vec3 pt(xx, y, z);
        bool in = false;
        grid.around(pt, [&](int j) {
          const auto& q = ps[static_cast<std::size_t>(j)];
          if (!in && (q.centre - pt).squaredNorm() < q.radius * q.radius) in = true;
        });
        inside += in;
        ++total;
      }
  s.core_packing_fraction = static_cast<double>(inside) / static_cast<double>(total);
}

Packing generate_packing(const PackingParams& in) {
  if (auto e = check_packing_params(in)) bad(e->key, e->message);
  const PackingParams p = resolve_packing_params(in);
  Packing packing;
  packing.generator = std::string("femdem pack ") + FEMDEM_VERSION;
  packing.params_text = packing_params_text(p);
  if (is_lattice(p.arrangement))
    packing.particles = lattice_packing(p);
  else
    packing.particles = random_packing(p, packing.stats);
  Random rng(stream_seed(p.seed, 2));
  for (auto& q : packing.particles) {
    q.shape = p.shape;
    if (p.orientation == "random") q.orientation = rng.rotation();
  }
  measure_packing(p, packing);
  return packing;
}

double bounding_radius(const Tet10Mesh& mesh, Vec3* centre) {
  Vec3 lo = mesh.nodes.front(), hi = mesh.nodes.front();
  for (const Vec3& p : mesh.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 c = 0.5 * (lo + hi);
  double r = 0.0;
  for (const Vec3& p : mesh.nodes) r = std::max(r, (p - c).norm());
  if (centre) *centre = c;
  return r;
}

}  // namespace femdem
