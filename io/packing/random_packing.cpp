// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_map>

#include "io/packing/packing_internal.hpp"

namespace femdem::packing_detail {

// ---------------------------------------------------------------------------------------------
// Random placement and settling, in units of the largest diameter and of g.

namespace {

// The walls of the container while settling: the floor and the sides (the top stays open).
struct Walls {
  bool cylinder;
  Vec3 lo, hi;
  double radius;
  int count() const { return cylinder ? 2 : 5; }
  // Overlap of a sphere (c, r) with wall w and the wall's normal into the container.
  double overlap(int w, const Vec3& c, double r, Vec3& n) const {
    switch (w) {
      case 0:
        n = Vec3(0, 0, 1);
        return r - (c.z() - lo.z());
      case 1:
        if (cylinder) {
          const double rho = std::hypot(c.x(), c.y());
          n = rho > 0.0 ? Vec3(-c.x() / rho, -c.y() / rho, 0.0) : Vec3(1, 0, 0);
          return r - (radius - rho);
        }
        n = Vec3(1, 0, 0);
        return r - (c.x() - lo.x());
      case 2:
        n = Vec3(-1, 0, 0);
        return r - (hi.x() - c.x());
      case 3:
        n = Vec3(0, 1, 0);
        return r - (c.y() - lo.y());
      default:
        n = Vec3(0, -1, 0);
        return r - (hi.y() - c.y());
    }
  }
};

// A candidate pair of the Verlet list, with its tangential spring carried from step to step.
struct Pair {
  int i, j;  // i < j
  Vec3 xi = Vec3::Zero();
};

struct SettleResult {
  double time = 0.0;
  std::int64_t steps = 0;
  double max_speed = 0.0;
  bool at_rest = false;
};

constexpr double kStiffness = 5e3;    // k_n in units of (mass of a d = 1 particle) g / d
constexpr double kRestitution = 0.2;  // normal restitution while settling
constexpr double kDrag = 0.05;        // background drag on velocities while pouring, per time
constexpr double kSpinDrag = 0.5;     // and on spins (stands in for rolling resistance)
// Once everything has landed, stronger drag brings the last rattlers to rest sooner; the
// structure is set by then, and friction holds it.
constexpr double kRestDrag = 1.0;
constexpr double kRestSpeed = 1e-3;       // at rest below this speed, in sqrt(g d)
constexpr double kMaxSettleTime = 400.0;  // give up after this, in sqrt(d / g)
constexpr double kSkin = 0.15;            // Verlet list skin, in d

// The pairs closer than r_i + r_j + skin, sorted by (i, j), with the springs of `old` (also
// sorted) carried over by a merge.
void build_pairs(const std::vector<Vec3>& x, const std::vector<double>& r, CellGrid& grid,
                 std::vector<Pair>& pairs, std::vector<Pair>& old, std::vector<int>& scratch) {
  std::swap(pairs, old);
  pairs.clear();
  grid.build(x);
  std::size_t o = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    scratch.clear();
    grid.around(x[i], [&](int j) {
      const std::size_t ju = static_cast<std::size_t>(j);
      if (ju <= i) return;
      const double reach = r[i] + r[ju] + kSkin;
      if ((x[ju] - x[i]).squaredNorm() < reach * reach) scratch.push_back(j);
    });
    std::sort(scratch.begin(), scratch.end());
    for (int j : scratch) {
      Pair p{static_cast<int>(i), j};
      while (o < old.size() && std::tie(old[o].i, old[o].j) < std::tie(p.i, p.j)) ++o;
      if (o < old.size() && old[o].i == p.i && old[o].j == p.j) p.xi = old[o].xi;
      pairs.push_back(p);
    }
  }
}

// Drops the particles (normalised: largest diameter 1, g = 1, density 3 / (4 pi) so m = r^3)
// from their positions `x` into the container `walls` and integrates until they are at rest.
SettleResult settle(std::vector<Vec3>& x, const std::vector<double>& r, const Walls& walls,
                    double friction) {
  const std::size_t n = x.size();
  std::vector<double> m(n), inv_m(n), inv_i(n);
  double m_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    m[i] = r[i] * r[i] * r[i];
    inv_m[i] = 1.0 / m[i];
    inv_i[i] = 1.0 / (0.4 * m[i] * r[i] * r[i]);
    m_min = std::min(m_min, m[i]);
  }
  const double kn = kStiffness * 0.125, kt = 2.0 / 7.0 * kn;
  const double ln_e = std::log(kRestitution);
  const double zeta = -ln_e / std::sqrt(kPi * kPi + ln_e * ln_e);
  // The shortest contact lasts pi sqrt(m_eff / k) (two of the lightest particles); 12 steps
  // resolve it (a damped linear spring is stable up to about 3).
  const double dt = kPi * std::sqrt(0.5 * m_min / kn) / 12.0;
  double z_top = 0.0;
  for (std::size_t i = 0; i < n; ++i) z_top = std::max(z_top, x[i].z() + r[i]);
  const double t_fall = std::sqrt(2.0 * z_top);
  const double t_landed = 1.5 * t_fall + 5.0;

  CellGrid grid;
  grid.setup(walls.lo, Vec3(walls.hi.x(), walls.hi.y(), std::max(walls.hi.z(), z_top)),
             1.0 + kSkin);
  std::vector<Vec3> v(n, Vec3::Zero()), w(n, Vec3::Zero()), f(n), tq(n), x_built = x;
  std::vector<Pair> pairs, old;
  std::vector<int> scratch;
  build_pairs(x, r, grid, pairs, old, scratch);
  std::vector<std::array<Vec3, 5>> wall_xi(n);
  for (auto& a : wall_xi) a.fill(Vec3::Zero());

  SettleResult res;
  // Tangential force of one contact from its spring (updated in place), capped by friction.
  auto tangential = [&](Vec3& xi, const Vec3& nrm, const Vec3& vt, double fn) {
    xi -= xi.dot(nrm) * nrm;  // keep the spring in the current tangent plane
    xi += vt * dt;
    Vec3 ft = -kt * xi;
    const double cap = friction * fn, mag = ft.norm();
    if (mag > cap) {  // sliding: the spring holds the friction force
      ft *= mag > 0.0 ? cap / mag : 0.0;
      xi = -ft / kt;
    }
    return ft;
  };

  for (;;) {
    for (std::size_t i = 0; i < n; ++i) {
      f[i] = Vec3(0.0, 0.0, -m[i]);
      tq[i].setZero();
    }
    for (Pair& pr : pairs) {
      const std::size_t i = static_cast<std::size_t>(pr.i), j = static_cast<std::size_t>(pr.j);
      const Vec3 d = x[j] - x[i];
      const double rs = r[i] + r[j], d2 = d.squaredNorm();
      if (d2 >= rs * rs) {
        pr.xi.setZero();  // out of contact: the spring is released
        continue;
      }
      const double dist = std::sqrt(d2);
      const Vec3 nrm = dist > 0.0 ? Vec3(d / dist) : Vec3(0, 0, 1);
      const double meff = m[i] * m[j] / (m[i] + m[j]);
      const Vec3 vr = (v[j] + w[j].cross(-r[j] * nrm)) - (v[i] + w[i].cross(r[i] * nrm));
      const double vn = vr.dot(nrm);
      const double fn = std::max(0.0, kn * (rs - dist) - 2.0 * zeta * std::sqrt(meff * kn) * vn);
      const Vec3 ft = tangential(pr.xi, nrm, vr - vn * nrm, fn);
      const Vec3 fj = fn * nrm + ft;
      f[j] += fj;
      f[i] -= fj;
      tq[j] += (-r[j] * nrm).cross(fj);
      tq[i] += (r[i] * nrm).cross(-fj);
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int wi = 0; wi < walls.count(); ++wi) {
        Vec3 nrm;
        const double delta = walls.overlap(wi, x[i], r[i], nrm);
        Vec3& xi = wall_xi[i][static_cast<std::size_t>(wi)];
        if (delta <= 0.0) {
          xi.setZero();
          continue;
        }
        const Vec3 arm = -r[i] * nrm;
        const Vec3 vc = v[i] + w[i].cross(arm);
        const double vn = vc.dot(nrm);
        const double fn = std::max(0.0, kn * delta - 2.0 * zeta * std::sqrt(m[i] * kn) * vn);
        const Vec3 ft = tangential(xi, nrm, vc - vn * nrm, fn);
        f[i] += fn * nrm + ft;
        tq[i] += arm.cross(ft);
      }
    const bool landed = res.time > t_landed;
    const double decay_v = 1.0 / (1.0 + (landed ? kRestDrag : kDrag) * dt);
    const double decay_w = 1.0 / (1.0 + (landed ? kRestDrag : kSpinDrag) * dt);
    double vmax2 = 0.0, moved2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = (v[i] + dt * inv_m[i] * f[i]) * decay_v;
      w[i] = (w[i] + dt * inv_i[i] * tq[i]) * decay_w;
      x[i] += dt * v[i];
      vmax2 = std::max({vmax2, v[i].squaredNorm(), (r[i] * w[i]).squaredNorm()});
      moved2 = std::max(moved2, (x[i] - x_built[i]).squaredNorm());
    }
    // The list stays complete while no particle has moved half the skin since it was built.
    if (moved2 > 0.25 * kSkin * kSkin) {
      build_pairs(x, r, grid, pairs, old, scratch);
      x_built = x;
    }
    res.time += dt;
    ++res.steps;
    res.max_speed = std::sqrt(vmax2);
    if (res.time > t_fall && res.max_speed < kRestSpeed) {
      res.at_rest = true;
      break;
    }
    if (res.time > t_fall + kMaxSettleTime) break;
  }
  return res;
}

// Pushes overlapping pairs (and particles through walls) apart until every pair is at least
// (1 + 1e-9) (r_i + r_j) apart: the settled springs leave overlaps of about 2e-4 d per layer
// above. Gauss-Seidel sweeps over a fixed pair list, so the result is deterministic.
void remove_overlaps(std::vector<Vec3>& x, const std::vector<double>& r, const Walls& walls) {
  const std::size_t n = x.size();
  CellGrid grid;
  double z_top = 0.0;
  for (std::size_t i = 0; i < n; ++i) z_top = std::max(z_top, x[i].z() + r[i]);
  grid.setup(walls.lo, Vec3(walls.hi.x(), walls.hi.y(), z_top), 1.0 + kSkin);
  std::vector<Pair> pairs, old;
  std::vector<int> scratch;
  build_pairs(x, r, grid, pairs, old, scratch);
  constexpr double kTarget = 2e-9, kTol = 1e-9;
  for (int sweep = 0; sweep < 100000; ++sweep) {
    double worst = 0.0;
    for (const Pair& pr : pairs) {
      Vec3& xa = x[static_cast<std::size_t>(pr.i)];
      Vec3& xb = x[static_cast<std::size_t>(pr.j)];
      const double rs = r[static_cast<std::size_t>(pr.i)] + r[static_cast<std::size_t>(pr.j)];
      const Vec3 d = xb - xa;
      const double dist = d.norm();
      const double short_by = rs * (1.0 + kTarget) - dist;
      if (short_by <= 0.0) continue;
      worst = std::max(worst, short_by / rs);
      const Vec3 nrm = dist > 0.0 ? Vec3(d / dist) : Vec3(0, 0, 1);
      xa -= 0.5 * short_by * nrm;
      xb += 0.5 * short_by * nrm;
    }
    for (std::size_t i = 0; i < n; ++i)
      for (int wi = 0; wi < walls.count(); ++wi) {
        Vec3 nrm;
        const double delta = walls.overlap(wi, x[i], r[i], nrm);
        if (delta > 0.0) {
          x[i] += delta * nrm;
          worst = std::max(worst, delta / r[i]);
        }
      }
    if (worst < kTol) return;
  }
}

}  // namespace

std::vector<PackedParticle> random_packing(const PackingParams& p, PackingStats& stats) {
  const Container box(p);
  const std::vector<double> diam = draw_diameters(p, p.count);
  const double scale = max_diameter(p);  // length unit of the settling
  const std::size_t n = diam.size();
  std::vector<double> r(n);
  double volume = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = 0.5 * diam[i] / scale;
    volume += 4.0 / 3.0 * kPi * r[i] * r[i] * r[i];
  }
  // Poured spheres do not get denser than random close packing (0.64 for equal spheres, a
  // little more for mixed sizes): more particles than that cannot fit, and settling them
  // first would take long.
  const double fill = volume * scale * scale * scale / (box.section() * (box.hi.z() - box.lo.z()));
  if (fill > 0.66)
    bad("count", "the particles' volume is " + num(fill) +
                     " of the container's, more than a poured packing reaches (about 0.6): use "
                     "fewer particles or a larger container");
  Walls walls{box.cylinder, box.lo / scale, box.hi / scale, box.radius / scale};
  // Random sequential addition without overlap in a column above the floor, at a solid
  // fraction of 0.3 (far below the jamming of random sequential addition, about 0.38, so a
  // free spot is found in a few tries), then the particles rain down together.
  const double section = box.section() / (scale * scale);
  double column = std::max(volume / (0.3 * section), 1.0) + 1.0;
  Random rng(stream_seed(p.seed, 1));
  std::vector<Vec3> x(n);
  std::unordered_map<std::int64_t, std::vector<int>> cells;  // hash grid of unit cells
  auto key = [](int i, int j, int k) {
    return (static_cast<std::int64_t>(k) << 40) + (static_cast<std::int64_t>(j + (1 << 19)) << 20) +
           (i + (1 << 19));
  };
  auto cell = [](double c) { return static_cast<int>(std::floor(c)); };
  for (std::size_t i = 0; i < n; ++i) {
    bool placed = false;
    for (int attempt = 0; !placed; ++attempt) {
      if (attempt > 0 && attempt % 2000 == 0) column *= 1.25;  // crowded: grow the column
      if (attempt > 200000) bad("count", "cannot place the particles without overlap");
      Vec3 c;
      const double ri = r[i];
      if (walls.cylinder) {
        const double reach = walls.radius - ri;
        do {
          c.x() = rng.uniform(-reach, reach);
          c.y() = rng.uniform(-reach, reach);
        } while (c.x() * c.x() + c.y() * c.y() > reach * reach);
      } else {
        c.x() = rng.uniform(walls.lo.x() + ri, walls.hi.x() - ri);
        c.y() = rng.uniform(walls.lo.y() + ri, walls.hi.y() - ri);
      }
      c.z() = rng.uniform(ri, std::max(ri, column - ri));
      bool free = true;
      const int ci = cell(c.x()), cj = cell(c.y()), ck = cell(c.z());
      for (int k = ck - 1; k <= ck + 1 && free; ++k)
        for (int j = cj - 1; j <= cj + 1 && free; ++j)
          for (int ii = ci - 1; ii <= ci + 1 && free; ++ii) {
            const auto it = cells.find(key(ii, j, k));
            if (it == cells.end()) continue;
            for (int q : it->second) {
              const double rs = ri + r[static_cast<std::size_t>(q)];
              if ((x[static_cast<std::size_t>(q)] - c).squaredNorm() < rs * rs) {
                free = false;
                break;
              }
            }
          }
      if (!free) continue;
      x[i] = c;
      cells[key(ci, cj, ck)].push_back(static_cast<int>(i));
      placed = true;
    }
  }
  const SettleResult s = settle(x, r, walls, p.friction);
  remove_overlaps(x, r, walls);
  stats.settle_time = s.time;
  stats.settle_steps = s.steps;
  stats.max_speed = s.max_speed;
  stats.at_rest = s.at_rest;

  std::vector<PackedParticle> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i].centre = x[i] * scale;
    out[i].radius = 0.5 * diam[i];
  }
  // Bottom layers first: body p0001 is at the floor.
  std::stable_sort(out.begin(), out.end(), [](const PackedParticle& a, const PackedParticle& b) {
    return std::tie(a.centre.z(), a.centre.y(), a.centre.x()) <
           std::tie(b.centre.z(), b.centre.y(), b.centre.x());
  });
  const double bed = [&] {
    double t = 0.0;
    for (const auto& q : out) t = std::max(t, q.centre.z() + q.radius);
    return t;
  }();
  if (bed > box.hi.z() * (1.0 + 1e-12))
    bad("count", "the settled bed is " + num(bed) + " m high, above the container's height " +
                     num(box.hi.z()) + " m: use fewer particles or a taller container");
  return out;
}

}  // namespace femdem::packing_detail
