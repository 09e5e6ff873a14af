// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The exact penalty-potential integral of a tetrahedron pair (contact/tet_potential_contact.hpp)
// in two ways: tet_potential_contact_by_clipped_regions (what runs use; the regions clipped by
// contact/tet_regions_clip.hpp in barycentric coordinates), and tet_potential_contact_with<Clip>
// for a given clipper of positions, the tests' references. Clip is a class with
// set_tetrahedron(corners), clip(c, g) (keeps c + g . x >= 0), empty() and
// moments(volume, first_moment), as tests/support/tetrahedron_set_clip.hpp and the polyhedron
// clipper of the tests (tests/support/convex_polyhedron.hpp).
#include <algorithm>
#include <array>

#include <cmath>
#include "contact/centroid_line.hpp"
#include "contact/point3.hpp"
#include "contact/tet_regions_clip.hpp"

#include "contact/tet_potential_contact.hpp"

namespace femdem::contact {
namespace potential_integral {

// lambda_i(x) = c[i] + g[i] . x: the barycentric coordinates as affine functions. They are
// also the clipping half-spaces (lambda_i >= 0 is the inner side of face i), which makes the
// clipping independent of the tetrahedron's orientation and free of length-scaled tolerances.
struct Barycentric {
  double c[4];
  P3 g[4];
  double volume;  // of the tetrahedron
  double eval(int i, const P3& x) const { return c[i] + dot(g[i], x); }
};

inline bool barycentric(const TetCorners& t, Barycentric& b) {
  const P3 e1 = sub(t[1], t[0]), e2 = sub(t[2], t[0]), e3 = sub(t[3], t[0]);
  const P3 n1 = cross(e2, e3), n2 = cross(e3, e1), n3 = cross(e1, e2);
  const double det = dot(e1, n1);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const double inv = 1.0 / det;
  b.volume = std::abs(det) / 6.0;
  // Rows of the inverse of [e1 e2 e3] are the gradients of lambda_1..3.
  for (int k = 0; k < 3; ++k) {
    b.g[1][k] = n1[k] * inv;
    b.g[2][k] = n2[k] * inv;
    b.g[3][k] = n3[k] * inv;
    b.g[0][k] = -(b.g[1][k] + b.g[2][k] + b.g[3][k]);
  }
  b.c[1] = -dot(b.g[1], t[0]);
  b.c[2] = -dot(b.g[2], t[0]);
  b.c[3] = -dot(b.g[3], t[0]);
  b.c[0] = 1.0 - b.c[1] - b.c[2] - b.c[3];
  return true;
}

template <class Clip>
void clip_and_measure(const std::array<P3, 4>& region, const Barycentric& other, const int* planes,
                      int np, double& volume, P3& moment) {
  Clip clip;
  clip.set_tetrahedron(region);
  for (int j = 0; j < np && !clip.empty(); ++j) clip.clip(other.c[planes[j]], other.g[planes[j]]);
  clip.moments(volume, moment);
}

// `side[j][k]` is lambda_j of `other` at the region's corner k.
// Volume and first moment (volume times centroid) of `region` n `other`.
template <class Clip>
void clipped_moments(const std::array<P3, 4>& region, const double side[4][4],
                     const Barycentric& other, double& volume, P3& moment) {
  volume = 0.0;
  moment = {0.0, 0.0, 0.0};
  // Planes that keep the whole region need no clipping; one that keeps none of it ends the
  // work. Most regions of a shallow contact end here.
  int planes[4], np = 0;
  for (int j = 0; j < 4; ++j) {
    const int in =
        (side[j][0] >= 0.0) + (side[j][1] >= 0.0) + (side[j][2] >= 0.0) + (side[j][3] >= 0.0);
    if (in == 0) return;
    if (in < 4) planes[np++] = j;
  }
  clip_and_measure<Clip>(region, other, planes, np, volume, moment);
}

// One region's share of T's half of the energy, E_T = p * int_{T n O} phi_T dV, and of its
// gradient (added to grad_t, grad_o). On region i of T (phi_T = 4 lambda_i^T), with V, M the
// volume and first moment of (region i) n O and <f> = f(centroid) V for an affine f:
//   E_T       += 4p <lambda_i^T>
//   dE/dx_m^T += -4p <lambda_m^T> grad lambda_i^T          (the field phi_T moves with T;
//                                                           phi_T = 0 on dT, no boundary term)
//   dE/dx_k^O += 4p (<lambda_k^O> grad lambda_i^T + <lambda_i^T> grad lambda_k^O)
// The last line is the flux of phi_T through the moving faces of O, turned into a volume
// integral with the divergence theorem (lambda_k^O is the faces' velocity field, phi_T = 0 on
// the rest of the overlap's boundary).
inline double add_region(int i, double vol, const P3& mom, const Barycentric& bt,
                         const Barycentric& bo, double p4, double grad_t[4][3],
                         double grad_o[4][3]) {
  const double li = bt.c[i] * vol + dot(bt.g[i], mom);  // <lambda_i^T>
  for (int m = 0; m < 4; ++m) {
    const double lm = bt.c[m] * vol + dot(bt.g[m], mom);  // <lambda_m^T>
    const double lk = bo.c[m] * vol + dot(bo.g[m], mom);  // <lambda_m^O>
    for (int d = 0; d < 3; ++d) {
      grad_t[m][d] -= p4 * lm * bt.g[i][d];
      grad_o[m][d] += p4 * (lk * bt.g[i][d] + li * bo.g[m][d]);
    }
  }
  return p4 * li;
}

// T's half, region by region: region i (where lambda_i^T is the smallest: the centroid and the
// face opposite corner i) clipped by O's four faces. `at_corners[j][k]` is lambda_j^O at T's
// corner k.
template <class Clip>
double add_half_by_regions(const TetCorners& t, const Barycentric& bt, const Barycentric& bo,
                           const double at_corners[4][4], double p4, double grad_t[4][3],
                           double grad_o[4][3], double& overlap, P3& overlap_moment) {
  const P3 centroid = {0.25 * (t[0][0] + t[1][0] + t[2][0] + t[3][0]),
                       0.25 * (t[0][1] + t[1][1] + t[2][1] + t[3][1]),
                       0.25 * (t[0][2] + t[1][2] + t[2][2] + t[3][2])};
  double at_centroid[4];
  for (int j = 0; j < 4; ++j) at_centroid[j] = bo.eval(j, centroid);
  double energy = 0.0;
  for (int i = 0; i < 4; ++i) {
    std::array<P3, 4> region;
    double side[4][4];
    region[0] = centroid;
    for (int j = 0; j < 4; ++j) side[j][0] = at_centroid[j];
    for (int k = 0, r = 1; k < 4; ++k)
      if (k != i) {
        for (int j = 0; j < 4; ++j) side[j][r] = at_corners[j][k];
        region[r++] = t[k];
      }
    double vol;
    P3 mom;
    clipped_moments<Clip>(region, side, bo, vol, mom);
    if (vol == 0.0) continue;
    overlap += vol;
    for (int d = 0; d < 3; ++d) overlap_moment[d] += mom[d];
    energy += add_region(i, vol, mom, bt, bo, p4, grad_t, grad_o);
  }
  return energy;
}

// at[i][k] = lambda_i^T at O's corner k. True when all corners of O are on the outer side of
// one face plane of T.
inline bool face_separates(const Barycentric& bt, const TetCorners& o, double at[4][4]) {
  bool separated = false;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) at[i][k] = bt.eval(i, o[k]);
    // & rather than &&: no branch on each corner (a rejection test, mispredicted often).
    separated |= (at[i][0] <= 0.0) & (at[i][1] <= 0.0) & (at[i][2] <= 0.0) & (at[i][3] <= 0.0);
  }
  return separated;
}

// A pair past the tests before the clipping, and the sums both halves add to: what the kernel's
// path and the tests' reference path share.
struct PreparedPair {
  TetCorners a, b;  // the corners relative to A's first corner
  Barycentric ba, bb;
  double b_at_a[4][4], a_at_b[4][4];  // lambda_j^B at A's corner k, and the other way round
  double p4;                          // 4 x the penalty: phi = 4 lambda_i in region i
  double grad_a[4][3], grad_b[4][3];  // zeroed by prepare() once the pair passes (a rejected
                                      // pair clears nothing: most candidates are rejected)
};

// The steps before the clipping: the box test, coordinates relative to A's first corner (the
// barycentric offsets c_i would otherwise carry the absolute coordinates and lose digits for
// small tetrahedra far from the origin), the centroid-line test, the barycentric planes and
// the face-plane test. Returns false when the pair is rejected.
inline bool prepare(const TetCorners& a_in, const TetCorners& b_in, double penalty,
                    PreparedPair& pair) {
  TetCorners& a = pair.a;
  TetCorners& b = pair.b;
  pair.p4 = 4.0 * penalty;
  for (int d = 0; d < 3; ++d) {
    double amin = a_in[0][d], amax = amin, bmin = b_in[0][d], bmax = bmin;
    for (int k = 1; k < 4; ++k) {
      amin = std::min(amin, a_in[k][d]);
      amax = std::max(amax, a_in[k][d]);
      bmin = std::min(bmin, b_in[k][d]);
      bmax = std::max(bmax, b_in[k][d]);
    }
    if (amax <= bmin || bmax <= amin) return false;
  }
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) {
      a[k][d] = a_in[k][d] - a_in[0][d];
      b[k][d] = b_in[k][d] - a_in[0][d];
    }
  // The line through the centroids separates most near pairs of two bodies' surfaces, and
  // costs 8 dot products where the face planes need both inverses.
  if (centroid_line_separation(a, b) > 0.0) return false;
  if (!barycentric(a, pair.ba) || !barycentric(b, pair.bb)) return false;
  if (face_separates(pair.ba, b, pair.a_at_b) || face_separates(pair.bb, a, pair.b_at_a))
    return false;
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) pair.grad_a[k][d] = pair.grad_b[k][d] = 0.0;
  return true;
}

inline void finish(const TetCorners& a_in, double energy, const double grad_a[4][3],
                   const double grad_b[4][3], double overlap, const P3& moment,
                   TetPairContact& out) {
  out.energy = energy;
  out.overlap_volume = overlap;
  for (int d = 0; d < 3; ++d) out.overlap_centroid[d] = a_in[0][d] + moment[d] / overlap;
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) {
      out.force_a[k][d] = -grad_a[k][d];
      out.force_b[k][d] = -grad_b[k][d];
    }
}

// The kernel's path: T's half (add_half_by_regions) with T's four regions clipped together in
// O's barycentric coordinates (contact/tet_regions_clip.hpp). `at_corners[j][k]` is lambda_j^O
// at T's corner k, `t_at_o[m][j]` lambda_m^T at O's corner j; lsum[j] gathers the integrals of
// lambda_j^O over T n O.
inline double add_half_by_clipped_regions(const Barycentric& bt, const Barycentric& bo,
                                          const double at_corners[4][4], const double t_at_o[4][4],
                                          double p4, double grad_t[4][3], double grad_o[4][3],
                                          double& overlap, double lsum[4]) {
  // Planes that keep all of T need no clipping; one that keeps none of it leaves nothing.
  // The others go in the order of their key: fewer corners kept first, then the one deeper
  // into T (the smaller sum). A plane keeping one corner of a piece leaves one tetrahedron
  // where one keeping three leaves a prism of three, and every piece dropped early is one the
  // later planes need not cut: on the benchmark's pairs this leaves about 40 % fewer pieces
  // than the planes' own order. The order is each key's rank, found without branches.
  int in_count[4];
  double sum[4];
  for (int j = 0; j < 4; ++j) {
    const double* s = at_corners[j];
    in_count[j] = (s[0] >= 0.0) + (s[1] >= 0.0) + (s[2] >= 0.0) + (s[3] >= 0.0);
    sum[j] = s[0] + s[1] + s[2] + s[3];
  }
  if (in_count[0] == 0 || in_count[1] == 0 || in_count[2] == 0 || in_count[3] == 0) return 0.0;
  int planes[4] = {}, np = 0;
  for (int j = 0; j < 4; ++j) {
    int rank = 0;
    for (int k = 0; k < 4; ++k)
      rank += (in_count[k] < in_count[j]) |
              ((in_count[k] == in_count[j]) & ((sum[k] < sum[j]) | ((sum[k] == sum[j]) & (k < j))));
    planes[rank] = j;
    np += in_count[j] < 4;
  }
  TetRegionsClip clip;
  clip.set_tetrahedron(at_corners);
  for (int n = 0; n < np; ++n) {
    if (n == 0)
      clip.clip_first(planes[0]);
    else
      clip.clip(planes[n]);
    if (clip.empty()) return 0.0;
  }
  double fraction[4], lm[4][4];
  clip.moments(fraction, lm);
  // add_region for the four regions at once, with the moments as integrals of lambda^O: for
  // region i, lm[i][j] = integral of lambda_j^O over (region i) n O, so <lambda_m^O> = lm[i][m]
  // and, lambda_m^T being affine and x = sum_j lambda_j^O(x) o_j,
  // <lambda_m^T> = sum_j lambda_m^T(o_j) lm[i][j]. An empty region adds zeros.
  overlap += bo.volume * (fraction[0] + fraction[1] + fraction[2] + fraction[3]);
  double lt[4][4], e = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) lm[i][j] *= bo.volume;
    for (int m = 0; m < 4; ++m)
      lt[i][m] = t_at_o[m][0] * lm[i][0] + t_at_o[m][1] * lm[i][1] + t_at_o[m][2] * lm[i][2] +
                 t_at_o[m][3] * lm[i][3];
    e += lt[i][i];
  }
  for (int j = 0; j < 4; ++j) lsum[j] += lm[0][j] + lm[1][j] + lm[2][j] + lm[3][j];
  for (int m = 0; m < 4; ++m)
    for (int d = 0; d < 3; ++d) {
      double gt = 0.0, go = 0.0;
      for (int i = 0; i < 4; ++i) {
        gt += lt[i][m] * bt.g[i][d];
        go += lm[i][m] * bt.g[i][d];
      }
      grad_t[m][d] -= p4 * gt;
      grad_o[m][d] += p4 * (go + e * bo.g[m][d]);
    }
  return p4 * e;
}

}  // namespace potential_integral

// The pair's energy and forces (contact/tet_potential_contact.hpp): what runs use. The same
// integral as tet_potential_contact_with<Clip> below (the tests' reference path), which clips
// each region by itself in positions.
inline bool tet_potential_contact_by_clipped_regions(const TetCorners& a_in, const TetCorners& b_in,
                                                     double penalty, TetPairContact& out) {
  using namespace potential_integral;
  PreparedPair p;
  if (!prepare(a_in, b_in, penalty, p)) return false;
  double overlap_a = 0.0, overlap_b = 0.0, lsum_a[4] = {}, lsum_b[4] = {};
  double energy = add_half_by_clipped_regions(p.ba, p.bb, p.b_at_a, p.a_at_b, p.p4, p.grad_a,
                                              p.grad_b, overlap_a, lsum_a);
  energy += add_half_by_clipped_regions(p.bb, p.ba, p.a_at_b, p.b_at_a, p.p4, p.grad_b, p.grad_a,
                                        overlap_b, lsum_b);
  if (overlap_a == 0.0 && overlap_b == 0.0) return false;
  // Both halves measure the same overlap; their mean halves the round-off. A's half integrates
  // lambda^B (first moment sum_j b_j lsum_a[j]) and B's half lambda^A.
  P3 moment;
  for (int d = 0; d < 3; ++d) {
    double m = 0.0;
    for (int j = 0; j < 4; ++j) m += p.b[j][d] * lsum_a[j] + p.a[j][d] * lsum_b[j];
    moment[d] = 0.5 * m;
  }
  finish(a_in, energy, p.grad_a, p.grad_b, 0.5 * (overlap_a + overlap_b), moment, out);
  return true;
}

// The pair's energy and forces (contact/tet_potential_contact.hpp) with the regions clipped by
// Clip.
template <class Clip>
bool tet_potential_contact_with(const TetCorners& a_in, const TetCorners& b_in, double penalty,
                                TetPairContact& out) {
  using namespace potential_integral;
  PreparedPair p;
  if (!prepare(a_in, b_in, penalty, p)) return false;
  double overlap_a = 0.0, overlap_b = 0.0;
  P3 moment_a = {0.0, 0.0, 0.0}, moment_b = {0.0, 0.0, 0.0};
  double energy = add_half_by_regions<Clip>(p.a, p.ba, p.bb, p.b_at_a, p.p4, p.grad_a, p.grad_b,
                                            overlap_a, moment_a);
  energy += add_half_by_regions<Clip>(p.b, p.bb, p.ba, p.a_at_b, p.p4, p.grad_b, p.grad_a,
                                      overlap_b, moment_b);
  if (overlap_a == 0.0 && overlap_b == 0.0) return false;
  // Both halves measure the same overlap volume; their mean halves the round-off.
  P3 moment;
  for (int d = 0; d < 3; ++d) moment[d] = 0.5 * (moment_a[d] + moment_b[d]);
  finish(a_in, energy, p.grad_a, p.grad_b, 0.5 * (overlap_a + overlap_b), moment, out);
  return true;
}

}  // namespace femdem::contact
