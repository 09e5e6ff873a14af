// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/tet_potential_contact.hpp"

#include <algorithm>
#include <cmath>

namespace femdem::contact {
namespace {

using P3 = std::array<double, 3>;

inline double dot(const P3& a, const P3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline P3 sub(const P3& a, const P3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// lambda_i(x) = c[i] + g[i] . x: the barycentric coordinates as affine functions. They are
// also the clipping half-spaces (lambda_i >= 0 is the inner side of face i), which makes the
// clipping independent of the tetrahedron's orientation and free of length-scaled tolerances.
struct Barycentric {
  double c[4];
  P3 g[4];
  double eval(int i, const P3& x) const { return c[i] + dot(g[i], x); }
};

bool barycentric(const TetCorners& t, Barycentric& b) {
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

struct Tet {
  P3 v[4];
};

// Clipping a tetrahedron by one half-space leaves a tetrahedron or a triangular prism (3
// tetrahedra), so 4 planes give at most 3^4 pieces.
constexpr int kMaxPieces = 81;

inline P3 cut(const P3& p, double sp, const P3& q, double sq) {
  // sp >= 0 > sq, so the denominator is positive and t lies in [0, 1).
  const double t = sp / (sp - sq);
  return {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
}

// Triangular prism with ends (a0, a1, a2) and (b0, b1, b2), a_k joined to b_k by an edge: three
// tetrahedra whose diagonals meet consistently on the three (planar) side quadrilaterals.
inline int emit_prism(const P3& a0, const P3& a1, const P3& a2, const P3& b0, const P3& b1,
                      const P3& b2, Tet* out) {
  out[0] = {{a0, a1, a2, b0}};
  out[1] = {{a1, a2, b0, b1}};
  out[2] = {{a2, b0, b1, b2}};
  return 3;
}

// Keeps the part of `in` where lambda_i of `plane` is >= 0; appends pieces to out.
inline int clip_tet(const Tet& in, const Barycentric& plane, int i, Tet* out) {
  double s[4];
  int inside[4], outside[4], ni = 0, no = 0;
  for (int k = 0; k < 4; ++k) {
    s[k] = plane.eval(i, in.v[k]);
    if (s[k] >= 0.0)
      inside[ni++] = k;
    else
      outside[no++] = k;
  }
  const P3* v = in.v;
  switch (ni) {
    case 4:
      out[0] = in;
      return 1;
    case 0:
      return 0;
    case 1: {
      const int a = inside[0];
      out[0] = {{v[a], cut(v[a], s[a], v[outside[0]], s[outside[0]]),
                 cut(v[a], s[a], v[outside[1]], s[outside[1]]),
                 cut(v[a], s[a], v[outside[2]], s[outside[2]])}};
      return 1;
    }
    case 2: {
      // Ends: (a, ac, ad) and (b, bc, bd).
      const int a = inside[0], b = inside[1], c = outside[0], d = outside[1];
      return emit_prism(v[a], cut(v[a], s[a], v[c], s[c]), cut(v[a], s[a], v[d], s[d]), v[b],
                        cut(v[b], s[b], v[c], s[c]), cut(v[b], s[b], v[d], s[d]), out);
    }
    default: {
      // Ends: (a, b, c) and their cuts towards the outside corner d.
      const int a = inside[0], b = inside[1], c = inside[2], d = outside[0];
      return emit_prism(v[a], v[b], v[c], cut(v[a], s[a], v[d], s[d]), cut(v[b], s[b], v[d], s[d]),
                        cut(v[c], s[c], v[d], s[d]), out);
    }
  }
}

// Volume and first moment (volume times centroid) of `region` n `other`.
void clipped_moments(const Tet& region, const Barycentric& other, double& volume, P3& moment) {
  volume = 0.0;
  moment = {0.0, 0.0, 0.0};
  // Planes that keep the whole region need no clipping; one that keeps none of it ends the
  // work. Most regions of a shallow contact end here.
  int planes[4], np = 0;
  for (int i = 0; i < 4; ++i) {
    int in = 0;
    for (int k = 0; k < 4; ++k) in += other.eval(i, region.v[k]) >= 0.0;
    if (in == 0) return;
    if (in < 4) planes[np++] = i;
  }
  Tet buf[2][kMaxPieces];
  buf[0][0] = region;
  int n = 1, cur = 0;
  for (int j = 0; j < np && n > 0; ++j) {
    const int i = planes[j];
    int m = 0;
    for (int k = 0; k < n; ++k) m += clip_tet(buf[cur][k], other, i, buf[1 - cur] + m);
    cur = 1 - cur;
    n = m;
  }
  for (int k = 0; k < n; ++k) {
    const P3* v = buf[cur][k].v;
    const double vol =
        std::abs(dot(sub(v[1], v[0]), cross(sub(v[2], v[0]), sub(v[3], v[0])))) / 6.0;
    const double w = vol * 0.25;
    volume += vol;
    for (int d = 0; d < 3; ++d) moment[d] += w * (v[0][d] + v[1][d] + v[2][d] + v[3][d]);
  }
}

// Adds T's half of the energy, E_T = p * int_{T n O} phi_T dV, and its gradient to (gt, go).
// On region i of T (phi_T = 4 lambda_i^T), with V_i, M_i the volume and moment of region i n O
// and <f> = f(centroid) V_i for an affine f:
//   E_T       += 4p <lambda_i^T>
//   dE/dx_m^T += -4p <lambda_m^T> grad lambda_i^T          (the field phi_T moves with T;
//                                                           phi_T = 0 on dT, no boundary term)
//   dE/dx_k^O += 4p (<lambda_k^O> grad lambda_i^T + <lambda_i^T> grad lambda_k^O)
// The last line is the flux of phi_T through the moving faces of O, turned into a volume
// integral with the divergence theorem (lambda_k^O is the faces' velocity field, phi_T = 0 on
// the rest of the overlap's boundary).
double add_half(const TetCorners& t, const Barycentric& bt, const Barycentric& bo, double p4,
                double grad_t[4][3], double grad_o[4][3], double& overlap, P3& overlap_moment) {
  const P3 centroid = {0.25 * (t[0][0] + t[1][0] + t[2][0] + t[3][0]),
                       0.25 * (t[0][1] + t[1][1] + t[2][1] + t[3][1]),
                       0.25 * (t[0][2] + t[1][2] + t[2][2] + t[3][2])};
  double energy = 0.0;
  for (int i = 0; i < 4; ++i) {
    // Region i: where lambda_i is the smallest coordinate = centroid + the face opposite i.
    Tet region;
    region.v[0] = centroid;
    for (int k = 0, r = 1; k < 4; ++k)
      if (k != i) region.v[r++] = t[k];
    double vol;
    P3 mom;
    clipped_moments(region, bo, vol, mom);
    if (vol == 0.0) continue;
    overlap += vol;
    for (int d = 0; d < 3; ++d) overlap_moment[d] += mom[d];
    const double li = bt.c[i] * vol + dot(bt.g[i], mom);  // <lambda_i^T>
    energy += p4 * li;
    for (int m = 0; m < 4; ++m) {
      const double lm = bt.c[m] * vol + dot(bt.g[m], mom);  // <lambda_m^T>
      const double lk = bo.c[m] * vol + dot(bo.g[m], mom);  // <lambda_m^O>
      for (int d = 0; d < 3; ++d) {
        grad_t[m][d] -= p4 * lm * bt.g[i][d];
        grad_o[m][d] += p4 * (lk * bt.g[i][d] + li * bo.g[m][d]);
      }
    }
  }
  return energy;
}

// True when all corners of `o` are on the outer side of one face plane of `t`.
bool face_separates(const Barycentric& bt, const TetCorners& o) {
  for (int i = 0; i < 4; ++i) {
    if (bt.eval(i, o[0]) <= 0.0 && bt.eval(i, o[1]) <= 0.0 && bt.eval(i, o[2]) <= 0.0 &&
        bt.eval(i, o[3]) <= 0.0)
      return true;
  }
  return false;
}

}  // namespace

bool tet_potential_contact(const TetCorners& a_in, const TetCorners& b_in, double penalty,
                           TetPairContact& out) {
  out = TetPairContact{};
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
  // Work relative to A's first corner: the barycentric offsets c_i would otherwise carry the
  // absolute coordinates and lose digits for small tetrahedra far from the origin.
  TetCorners a, b;
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) {
      a[k][d] = a_in[k][d] - a_in[0][d];
      b[k][d] = b_in[k][d] - a_in[0][d];
    }
  Barycentric ba, bb;
  if (!barycentric(a, ba) || !barycentric(b, bb)) return false;
  if (face_separates(ba, b) || face_separates(bb, a)) return false;

  const double p4 = 4.0 * penalty;
  double grad_a[4][3] = {}, grad_b[4][3] = {};
  double overlap_a = 0.0, overlap_b = 0.0;
  P3 moment_a = {0.0, 0.0, 0.0}, moment_b = {0.0, 0.0, 0.0};
  double energy = add_half(a, ba, bb, p4, grad_a, grad_b, overlap_a, moment_a);
  energy += add_half(b, bb, ba, p4, grad_b, grad_a, overlap_b, moment_b);
  if (overlap_a == 0.0 && overlap_b == 0.0) return false;
  out.energy = energy;
  // Both halves measure the same overlap volume; their mean halves the round-off.
  out.overlap_volume = 0.5 * (overlap_a + overlap_b);
  for (int d = 0; d < 3; ++d)
    out.overlap_centroid[d] = a_in[0][d] + (moment_a[d] + moment_b[d]) / (overlap_a + overlap_b);
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) {
      out.force_a[k][d] = -grad_a[k][d];
      out.force_b[k][d] = -grad_b[k][d];
    }
  return true;
}

}  // namespace femdem::contact
