// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/packing/packing.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "engine/errors.hpp"
#include "femdem_version.hpp"
#include "io/atomic_file.hpp"

namespace femdem {

namespace {

constexpr double kPi = std::numbers::pi;

[[noreturn]] void bad(const std::string& key, const std::string& message) {
  throw InputError(message, {}, 0, 0, key);
}

std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // a TOML float
  return s;
}

bool is_lattice(const std::string& a) {
  return a == "simple_cubic" || a == "body_centred_cubic" || a == "face_centred_cubic";
}

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

// Separate streams for sizes, positions and orientations: changing the container does not
// change the sizes, and turning orientations on does not move the particles.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);  // SplitMix64
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double lognormal_mu(const PackingParams& p) {
  // mean of exp(N(mu, s^2)) is exp(mu + s^2 / 2)
  return std::log(p.diameter_mean) - 0.5 * p.sigma * p.sigma;
}

// Largest and smallest diameters the distribution can produce.
double max_diameter(const PackingParams& p) {
  return p.distribution == "monodisperse" ? p.diameter : p.diameter_max;
}
double min_diameter(const PackingParams& p) {
  return p.distribution == "monodisperse" ? p.diameter : p.diameter_min;
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
  const int nz = static_cast<int>(std::floor(extent.z() / a)) + 2;
  const int nxy = static_cast<int>(std::floor(std::max(extent.x(), extent.y()) / a)) + 2;
  const int xy_from = box.cylinder ? -nxy : 0;
  std::vector<Vec3> sites;
  for (int k = 0; k < nz; ++k)
    for (int j = xy_from; j < nxy; ++j)
      for (int i = xy_from; i < nxy; ++i)
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

// ---------------------------------------------------------------------------------------------
// Random placement and settling, in units of the largest diameter and of g.

// A uniform grid of cubic-ish cells over a fixed box; positions outside are clamped into the
// border cells, which keeps neighbours within one cell of each other (clamping is monotone).
struct CellGrid {
  Vec3 origin = Vec3::Zero();
  std::array<int, 3> n = {1, 1, 1};
  Vec3 inv_cell = Vec3::Ones();
  std::vector<int> start, order, cell_of;

  void setup(const Vec3& lo, const Vec3& hi, double min_cell) {
    origin = lo;
    for (int a = 0; a < 3; ++a) {
      const double ext = std::max(hi[a] - lo[a], min_cell);
      n[static_cast<std::size_t>(a)] = std::max(1, static_cast<int>(std::floor(ext / min_cell)));
      n[static_cast<std::size_t>(a)] = std::min(n[static_cast<std::size_t>(a)], 1 << 10);
      inv_cell[a] = n[static_cast<std::size_t>(a)] / ext;
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// Parameters

std::optional<PackingParamError> check_packing_params(const PackingParams& p) {
  auto err = [](std::string key, std::string msg) {
    return std::optional<PackingParamError>(PackingParamError{std::move(key), std::move(msg)});
  };
  auto finite_positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (p.container != "box" && p.container != "cylinder")
    return err("container", "unknown container '" + p.container + "': use \"box\" or \"cylinder\"");
  if (p.container == "box") {
    if (!(finite_positive(p.size.x()) && finite_positive(p.size.y()) &&
          finite_positive(p.size.z())))
      return err("size", "the box needs three positive lengths [lx, ly, lz]");
  } else {
    if (!finite_positive(p.radius)) return err("radius", "the cylinder needs a positive radius");
    if (!finite_positive(p.height)) return err("height", "the cylinder needs a positive height");
  }
  const bool lattice = is_lattice(p.arrangement);
  if (!lattice && p.arrangement != "random")
    return err("arrangement", "unknown arrangement '" + p.arrangement +
                                  "': use \"random\", \"simple_cubic\", \"body_centred_cubic\" or "
                                  "\"face_centred_cubic\"");
  if (p.count < 0 || p.count > 1000000)
    return err("count",
               "must lie in [0, 1000000] (0: every lattice site), got " + std::to_string(p.count));
  if (!lattice && p.count < 1)
    return err("count", "a random packing needs the number of particles (count >= 1)");
  if (p.distribution == "monodisperse") {
    if (!finite_positive(p.diameter)) return err("diameter", "must be positive");
  } else if (p.distribution == "uniform") {
    if (lattice) return err("distribution", "a lattice needs monodisperse particles");
    if (!finite_positive(p.diameter_min)) return err("diameter_min", "must be positive");
    if (!(std::isfinite(p.diameter_max) && p.diameter_max > p.diameter_min))
      return err("diameter_max", "must be larger than diameter_min");
  } else if (p.distribution == "lognormal") {
    if (lattice) return err("distribution", "a lattice needs monodisperse particles");
    if (!finite_positive(p.diameter_mean)) return err("diameter_mean", "must be positive");
    if (!(finite_positive(p.sigma) && p.sigma <= 2.0))
      return err("sigma", "the standard deviation of ln d must lie in (0, 2]");
    if (p.diameter_min < 0.0 || !std::isfinite(p.diameter_min))
      return err("diameter_min", "must be positive (or 0 for the default mean * exp(-3 sigma))");
    if (p.diameter_max < 0.0 || !std::isfinite(p.diameter_max))
      return err("diameter_max", "must be positive (or 0 for the default mean * exp(3 sigma))");
    const PackingParams q = resolve_packing_params(p);
    if (!(q.diameter_max > q.diameter_min))
      return err("diameter_max", "must be larger than diameter_min");
    // The clip window must hold at least 1 % of the distribution, or redrawing takes forever.
    const double mu = lognormal_mu(q);
    auto cdf = [&](double d) {
      return 0.5 * std::erfc(-(std::log(d) - mu) / (q.sigma * std::sqrt(2.0)));
    };
    if (cdf(q.diameter_max) - cdf(q.diameter_min) < 0.01)
      return err("diameter_min",
                 "the clip window [diameter_min, diameter_max] holds less than 1 % of the "
                 "distribution");
  } else {
    return err("distribution", "unknown distribution '" + p.distribution +
                                   "': use \"monodisperse\", \"uniform\" or \"lognormal\"");
  }
  const PackingParams q = resolve_packing_params(p);
  const double dmax = max_diameter(q), dmin = min_diameter(q);
  if (dmax / dmin > 20.0)
    return err("diameter_max", "the largest diameter may be at most 20 times the smallest");
  const Container box(q);
  const double width = box.cylinder ? 2.0 * box.radius : std::min(box.hi.x(), box.hi.y());
  if (dmax > width * (1.0 + 1e-12) || dmax > box.hi.z() * (1.0 + 1e-12))
    return err(p.distribution == "monodisperse" ? "diameter" : "diameter_max",
               "the largest particle (" + num(dmax) + " m) does not fit in the container");
  if (p.shape.empty()) return err("shape", "must not be empty");
  for (char c : p.shape)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return err("shape",
                 "'" + p.shape + "': a shape name has only letters, digits, '_', '-', '.'");
  if (!p.orientation.empty() && p.orientation != "identity" && p.orientation != "random")
    return err("orientation",
               "unknown orientation '" + p.orientation + "': use \"identity\" or \"random\"");
  if (!(std::isfinite(p.friction) && p.friction >= 0.0 && p.friction <= 10.0))
    return err("friction", "must lie in [0, 10]");
  return std::nullopt;
}

PackingParams resolve_packing_params(PackingParams p) {
  if (p.orientation.empty()) p.orientation = p.shape == "sphere" ? "identity" : "random";
  if (p.distribution == "lognormal") {
    if (p.diameter_min == 0.0) p.diameter_min = p.diameter_mean * std::exp(-3.0 * p.sigma);
    if (p.diameter_max == 0.0) p.diameter_max = p.diameter_mean * std::exp(3.0 * p.sigma);
  }
  return p;
}

std::string packing_params_text(const PackingParams& in) {
  const PackingParams p = resolve_packing_params(in);
  std::ostringstream os;
  os << "container = \"" << p.container << "\"\n";
  if (p.container == "box")
    os << "size = [" << num(p.size.x()) << ", " << num(p.size.y()) << ", " << num(p.size.z())
       << "]\n";
  else
    os << "radius = " << num(p.radius) << "\nheight = " << num(p.height) << "\n";
  os << "arrangement = \"" << p.arrangement << "\"\n";
  os << "count = " << p.count << "\n";
  os << "distribution = \"" << p.distribution << "\"\n";
  if (p.distribution == "monodisperse") os << "diameter = " << num(p.diameter) << "\n";
  if (p.distribution == "lognormal")
    os << "diameter_mean = " << num(p.diameter_mean) << "\nsigma = " << num(p.sigma) << "\n";
  if (p.distribution != "monodisperse")
    os << "diameter_min = " << num(p.diameter_min) << "\ndiameter_max = " << num(p.diameter_max)
       << "\n";
  os << "seed = " << p.seed << "\n";
  os << "shape = \"" << p.shape << "\"\n";
  os << "orientation = \"" << p.orientation << "\"\n";
  if (p.arrangement == "random") os << "friction = " << num(p.friction) << "\n";
  return os.str();
}

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

// ---------------------------------------------------------------------------------------------
// Files

std::string packing_file_text(const Packing& packing) {
  std::ostringstream os;
  const PackingStats& s = packing.stats;
  os << "# femdem packing, format 1 (docs/OUTPUTS.md, \"Packing files\")\n";
  os << "# [generator]\n";
  os << "# program = \"" << (packing.generator.empty() ? "unknown" : packing.generator) << "\"\n";
  if (!packing.params_text.empty()) {
    os << "# [parameters]\n";
    std::istringstream in(packing.params_text);
    for (std::string line; std::getline(in, line);) os << "# " << line << "\n";
  }
  os << "# [result]\n";
  os << "# count = " << packing.particles.size() << "\n";
  os << "# particle_volume = " << num(s.particle_volume) << "\n";
  os << "# bed_height = " << num(s.bed_height) << "\n";
  os << "# packing_fraction = " << num(s.packing_fraction) << "\n";
  os << "# container_fraction = " << num(s.container_fraction) << "\n";
  if (std::isfinite(s.core_packing_fraction))
    os << "# core_packing_fraction = " << num(s.core_packing_fraction) << "\n";
  if (std::isfinite(s.min_gap)) os << "# min_gap = " << num(s.min_gap) << "\n";
  if (s.settle_steps > 0) {
    os << "# settle_time = " << num(s.settle_time) << "\n";
    os << "# settle_steps = " << s.settle_steps << "\n";
    os << "# max_speed = " << num(s.max_speed) << "\n";
    os << "# at_rest = " << (s.at_rest ? "true" : "false") << "\n";
  }
  os << "id,shape,x,y,z,radius,qw,qx,qy,qz\n";
  char buf[512];
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const PackedParticle& q = packing.particles[i];
    std::snprintf(buf, sizeof buf, "%zu,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  i + 1, q.shape.c_str(), q.centre.x(), q.centre.y(), q.centre.z(), q.radius,
                  q.orientation.w(), q.orientation.x(), q.orientation.y(), q.orientation.z());
    os << buf;
  }
  return os.str();
}

void write_packing(const std::string& path, const Packing& packing) {
  write_file_atomically(path, packing_file_text(packing), false);
}

Packing read_packing(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read the packing file", path);
  Packing packing;
  std::string section, line;
  bool have_columns = false;
  int lineno = 0;
  const std::string columns = "id,shape,x,y,z,radius,qw,qx,qy,qz";
  auto fail = [&](const std::string& msg, int column = 0) {
    throw InputError(msg, path, lineno, column);
  };
  auto header_value = [](const std::string& s) {
    std::string v = s.substr(s.find('=') + 1);
    v.erase(0, v.find_first_not_of(' '));
    if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);
    return v;
  };
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (have_columns) continue;
      std::string body = line.substr(1);
      if (!body.empty() && body[0] == ' ') body.erase(0, 1);
      if (!body.empty() && body[0] == '[') {
        section = body;
      } else if (section == "[parameters]") {
        packing.params_text += body + "\n";
      } else if (section == "[generator]" && body.rfind("program", 0) == 0) {
        packing.generator = header_value(body);
      }
      continue;
    }
    if (!have_columns) {
      if (line != columns)
        fail("expected the column line '" + columns + "' before the rows, got '" + line + "'", 1);
      have_columns = true;
      continue;
    }
    // id,shape,x,y,z,radius,qw,qx,qy,qz
    std::vector<std::string> fields;
    std::vector<int> starts;
    std::size_t b = 0;
    while (true) {
      const std::size_t e = line.find(',', b);
      starts.push_back(static_cast<int>(b) + 1);
      fields.push_back(line.substr(b, e == std::string::npos ? std::string::npos : e - b));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    if (fields.size() != 10)
      fail("expected 10 fields (" + columns + "), got " + std::to_string(fields.size()), 1);
    double v[8];
    for (int k = 0; k < 8; ++k) {
      const std::string& f = fields[static_cast<std::size_t>(k) + 2];
      const char* first = f.data();
      const auto r = std::from_chars(first, first + f.size(), v[k]);
      if (r.ec != std::errc() || r.ptr != first + f.size() || !std::isfinite(v[k]))
        fail("field '" + f + "' is not a finite number", starts[static_cast<std::size_t>(k) + 2]);
    }
    PackedParticle q;
    q.shape = fields[1];
    if (q.shape.empty()) fail("empty shape name", starts[1]);
    q.centre = Vec3(v[0], v[1], v[2]);
    q.radius = v[3];
    if (!(q.radius > 0.0)) fail("the radius must be positive", starts[5]);
    q.orientation = Eigen::Quaterniond(v[4], v[5], v[6], v[7]);
    const double norm = q.orientation.norm();
    if (!(std::abs(norm - 1.0) < 1e-6))
      fail("the quaternion (qw, qx, qy, qz) must have unit length, has " + num(norm), starts[6]);
    q.orientation.normalize();
    packing.particles.push_back(std::move(q));
  }
  if (!have_columns) throw InputError("no column line '" + columns + "' in the file", path);
  if (packing.particles.empty()) throw InputError("the packing has no particles", path);
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
