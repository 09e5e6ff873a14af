// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The exact penalty-potential integral of a tetrahedron pair (contact/tet_potential_contact.hpp)
// for a given clipper: the arithmetic the kernel shares with its test references. Clip is a
// class with set_tetrahedron(corners), clip(c, g) (keeps c + g . x >= 0), empty() and
// moments(volume, first_moment), as contact/tetrahedron_set_clip.hpp (what runs use) and the
// polyhedron clipper of the tests (tests/support/convex_polyhedron.hpp).
#include <algorithm>
#include <array>

#include <cmath>
#include "contact/centroid_line.hpp"
#include "contact/point3.hpp"

#include "contact/tet_potential_contact.hpp"

namespace femdem::contact {
namespace potential_integral {

// lambda_i(x) = c[i] + g[i] . x: the barycentric coordinates as affine functions. They are
// also the clipping half-spaces (lambda_i >= 0 is the inner side of face i), which makes the
// clipping independent of the tetrahedron's orientation and free of length-scaled tolerances.
struct Barycentric {
  double c[4];
  P3 g[4];
  double eval(int i, const P3& x) const { return c[i] + dot(g[i], x); }
};

inline bool barycentric(const TetCorners& t, Barycentric& b) {
  const P3 e1 = sub(t[1], t[0]), e2 = sub(t[2], t[0]), e3 = sub(t[3], t[0]);
  const P3 n1 = cross(e2, e3), n2 = cross(e3, e1), n3 = cross(e1, e2);
  const double det = dot(e1, n1);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const double inv = 1.0 / det;
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
    separated |= at[i][0] <= 0.0 && at[i][1] <= 0.0 && at[i][2] <= 0.0 && at[i][3] <= 0.0;
  }
  return separated;
}

// The steps before the clipping: the box test, coordinates relative to A's first corner (the
// barycentric offsets c_i would otherwise carry the absolute coordinates and lose digits for
// small tetrahedra far from the origin), the centroid-line test, the barycentric planes and
// the face-plane test.
// Returns false when the pair is rejected; else b_at_a[j][k] is lambda_j^B at A's corner k and
// a_at_b the other way round.
inline bool prepare(const TetCorners& a_in, const TetCorners& b_in, TetCorners& a, TetCorners& b,
                    Barycentric& ba, Barycentric& bb, double b_at_a[4][4], double a_at_b[4][4]) {
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
  if (!barycentric(a, ba) || !barycentric(b, bb)) return false;
  return !face_separates(ba, b, a_at_b) && !face_separates(bb, a, b_at_a);
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

}  // namespace potential_integral

// The pair's energy and forces (contact/tet_potential_contact.hpp) with the regions clipped by
// Clip.
template <class Clip>
bool tet_potential_contact_with(const TetCorners& a_in, const TetCorners& b_in, double penalty,
                                TetPairContact& out) {
  using namespace potential_integral;
  TetCorners a, b;
  Barycentric ba, bb;
  double b_at_a[4][4], a_at_b[4][4];
  if (!prepare(a_in, b_in, a, b, ba, bb, b_at_a, a_at_b)) return false;
  const double p4 = 4.0 * penalty;
  double grad_a[4][3] = {}, grad_b[4][3] = {};
  double overlap_a = 0.0, overlap_b = 0.0;
  P3 moment_a = {0.0, 0.0, 0.0}, moment_b = {0.0, 0.0, 0.0};
  double energy =
      add_half_by_regions<Clip>(a, ba, bb, b_at_a, p4, grad_a, grad_b, overlap_a, moment_a);
  energy += add_half_by_regions<Clip>(b, bb, ba, a_at_b, p4, grad_b, grad_a, overlap_b, moment_b);
  if (overlap_a == 0.0 && overlap_b == 0.0) return false;
  // Both halves measure the same overlap volume; their mean halves the round-off.
  P3 moment;
  for (int d = 0; d < 3; ++d) moment[d] = 0.5 * (moment_a[d] + moment_b[d]);
  finish(a_in, energy, grad_a, grad_b, 0.5 * (overlap_a + overlap_b), moment, out);
  return true;
}

}  // namespace femdem::contact
