// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The four regions of a tetrahedron T (region i: the centroid and the face opposite corner i)
// clipped together by the face planes of another tetrahedron O, and each clipped region's volume
// and integrals of lambda^O: the clipper of the pair kernel (contact/tet_potential_integral.hpp).
//
// Contract: set_tetrahedron(l) takes l[j][k] = lambda_j^O at T's corner k (T's corners in
// order 0-3); clip_first(j), then clip(j) for each later plane, keep lambda_j^O >= 0 (a point on
// the plane is kept; each plane at most once, so at most 4 planes); moments(fraction, lmom)
// gives, per region i, its clipped volume over O's volume (fraction[i]) and the integrals of
// lambda_j^O over it, over O's volume (lmom[i][j]). No allocation: fixed buffers sized from
// the largest counts 4 planes can make (about 26 kB, on the stack where the kernel puts it).
//
// The work is done in O's barycentric coordinates, where each clipping plane is a coordinate
// plane: a vertex's side of a plane is the sign of a stored number, and a cut vertex's
// coordinates are its edge ends' interpolated (no dot products, no positions). The moments come
// out as integrals of lambda^O, which is what the potential integral needs: <lambda_m^O>
// directly, and <lambda_m^T> and the first moment as linear combinations of them.
//
// The regions are kept as sets of tetrahedra, as in tests/support/tetrahedron_set_clip.hpp: a plane
// keeps a piece, drops it, or cuts it into one tetrahedron or a prism of three. Here
//  - a piece is 4 indices into a vertex pool, so a vertex shared by pieces (and by regions: the
//    centroid and the corners) is stored once and a kept piece costs 8 bytes to copy;
//  - the four regions share one pass per plane, each piece tagged with its region;
//  - the first plane is read from a table of the 32 ways it can split the 5 vertices
//    (clip_first), so an edge shared by regions is cut once;
//  - no branch depends on a piece's case (keep, drop, cut: they were mispredicted often): one
//    loop keeps the whole pieces and lists the cut ones, a second cuts those, each with the same
//    straight-line code whatever its case.
// On the pair benchmark (tools/bench/bench_tet_contact.cpp) this made the kernel about twice as
// fast on overlapping pairs as with tests/support/tetrahedron_set_clip.hpp (each region by itself,
// in positions, the planes in their own order).
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

namespace femdem::contact {
namespace tet_regions_clip {

// What a plane does to a piece whose corners inside it are the set bits of `mask` (1 to 14):
// the edges it cuts (from the inside corner to the outside one; their cut vertices get local ids
// 4, 5, 6, 7) and the pieces it leaves, as local ids (corners 0-3, cuts 4-7). A cut of 3 edges
// repeats its first edge as the fourth and a single piece repeats itself twice, so that every
// cut piece runs the same straight-line code.
struct CutCase {
  int ncut, nout;
  std::uint8_t from[4], to[4];
  std::uint8_t tet[3][4];
};

constexpr CutCase make_cut_case(int mask) {
  CutCase c{};
  std::uint8_t in[4] = {}, out[4] = {};
  int ni = 0, no = 0;
  for (int k = 0; k < 4; ++k) {
    if (mask >> k & 1)
      in[ni++] = static_cast<std::uint8_t>(k);
    else
      out[no++] = static_cast<std::uint8_t>(k);
  }
  const auto set_tets = [&c](std::uint8_t a0, std::uint8_t a1, std::uint8_t a2, std::uint8_t b0,
                             std::uint8_t b1, std::uint8_t b2) {
    // The prism with ends (a0, a1, a2), (b0, b1, b2), a_k joined to b_k: three tetrahedra
    // whose diagonals meet consistently on the three side quadrilaterals.
    const std::uint8_t t[3][4] = {{a0, a1, a2, b0}, {a1, a2, b0, b1}, {a2, b0, b1, b2}};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 4; ++k) c.tet[i][k] = t[i][k];
  };
  if (ni == 1) {  // the tetrahedron at the inside corner
    c.ncut = 3;
    c.nout = 1;
    for (int e = 0; e < 4; ++e) {
      c.from[e] = in[0];
      c.to[e] = out[e % 3];
    }
    for (int i = 0; i < 3; ++i) {
      c.tet[i][0] = in[0];
      c.tet[i][1] = 4;
      c.tet[i][2] = 5;
      c.tet[i][3] = 6;
    }
  } else if (ni == 2) {  // cuts 4 = (in0, out0), 5 = (in0, out1), 6 = (in1, out0), 7 = (in1, out1)
    c.ncut = 4;
    c.nout = 3;
    const std::uint8_t f[4] = {in[0], in[0], in[1], in[1]};
    const std::uint8_t t[4] = {out[0], out[1], out[0], out[1]};
    for (int e = 0; e < 4; ++e) {
      c.from[e] = f[e];
      c.to[e] = t[e];
    }
    set_tets(in[0], 4, 5, in[1], 6, 7);
  } else if (ni == 3) {
    c.ncut = 3;
    c.nout = 3;
    for (int e = 0; e < 4; ++e) {
      c.from[e] = in[e % 3];
      c.to[e] = out[0];
    }
    set_tets(in[0], in[1], in[2], 4, 5, 6);
  }
  return c;
}

inline constexpr CutCase kCutCases[16] = {
    make_cut_case(0),  make_cut_case(1),  make_cut_case(2),  make_cut_case(3),
    make_cut_case(4),  make_cut_case(5),  make_cut_case(6),  make_cut_case(7),
    make_cut_case(8),  make_cut_case(9),  make_cut_case(10), make_cut_case(11),
    make_cut_case(12), make_cut_case(13), make_cut_case(14), make_cut_case(15)};

// The first plane on the four regions as set: pieces (4, corners but i) over the 5 vertices
// (corners 0-3, centroid 4). For each pattern of those vertices inside the plane (bit v), the
// edges it cuts, once each (from inside to outside; cut e becomes vertex 5 + e), and the pieces
// left with their regions, as vertex ids. A tetrahedron has 6 edges and the 4 regions together
// 10 (the centroid to each corner, and the corners' 6), of which a split of 5 vertices cuts at
// most 2 * 3 = 6; each region leaves at most 3 pieces.
struct FirstCut {
  int ncut, npiece;
  std::uint8_t from[6], to[6];
  std::uint16_t piece[12][4];
  std::uint8_t region[12];
};

constexpr FirstCut make_first_cut(int pattern) {
  FirstCut f{};
  for (int r = 0; r < 4; ++r) {
    std::uint16_t v[4] = {4, 0, 0, 0};
    for (int k = 0, n = 1; k < 4; ++k)
      if (k != r) v[n++] = static_cast<std::uint16_t>(k);
    int mask = 0;
    for (int k = 0; k < 4; ++k) mask |= (pattern >> v[k] & 1) << k;
    if (mask == 0) continue;
    const auto add = [&f, r](std::uint16_t a, std::uint16_t b, std::uint16_t c, std::uint16_t d) {
      f.piece[f.npiece][0] = a;
      f.piece[f.npiece][1] = b;
      f.piece[f.npiece][2] = c;
      f.piece[f.npiece][3] = d;
      f.region[f.npiece++] = static_cast<std::uint8_t>(r);
    };
    if (mask == 15) {
      add(v[0], v[1], v[2], v[3]);
      continue;
    }
    const CutCase c = make_cut_case(mask);
    std::uint16_t id[8] = {v[0], v[1], v[2], v[3]};
    for (int e = 0; e < c.ncut; ++e) {
      const int p = v[c.from[e]], q = v[c.to[e]];
      int found = -1;
      for (int i = 0; i < f.ncut; ++i)
        if (f.from[i] == p && f.to[i] == q) found = i;
      if (found < 0) {
        found = f.ncut++;
        f.from[found] = static_cast<std::uint8_t>(p);
        f.to[found] = static_cast<std::uint8_t>(q);
      }
      id[4 + e] = static_cast<std::uint16_t>(5 + found);
    }
    for (int t = 0; t < c.nout; ++t)
      add(id[c.tet[t][0]], id[c.tet[t][1]], id[c.tet[t][2]], id[c.tet[t][3]]);
  }
  return f;
}

template <int... P>
constexpr std::array<FirstCut, sizeof...(P)> make_first_cuts(std::integer_sequence<int, P...>) {
  return {make_first_cut(P)...};
}
inline constexpr std::array<FirstCut, 32> kFirstCuts =
    make_first_cuts(std::make_integer_sequence<int, 32>{});

}  // namespace tet_regions_clip

class TetRegionsClip {
 public:
  void set_tetrahedron(const double l[4][4]) {
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j) pool_[k].l[j] = l[j][k];
    // The centroid (vertex 4); lambda^O is affine, so its lambdas are the corners' mean.
    for (int j = 0; j < 4; ++j) pool_[4].l[j] = 0.25 * (l[j][0] + l[j][1] + l[j][2] + l[j][3]);
    nv_ = 5;
    for (int i = 0; i < 4; ++i) {
      Piece& p = piece_[0][i];
      p.v[0] = 4;
      for (int k = 0, r = 1; k < 4; ++k)
        if (k != i) p.v[r++] = static_cast<std::uint16_t>(k);
      region_[0][i] = static_cast<std::uint8_t>(i);
    }
    n_ = 4;
    cur_ = 0;
  }
  bool empty() const { return n_ == 0; }

  // The first plane after set_tetrahedron, from kFirstCuts: each edge it cuts is cut once.
  void clip_first(int j) {
    const int pattern = (pool_[0].l[j] >= 0.0) | (pool_[1].l[j] >= 0.0) << 1 |
                        (pool_[2].l[j] >= 0.0) << 2 | (pool_[3].l[j] >= 0.0) << 3 |
                        (pool_[4].l[j] >= 0.0) << 4;
    const tet_regions_clip::FirstCut& f = tet_regions_clip::kFirstCuts[pattern];
    for (int e = 0; e < f.ncut; ++e) cut(pool_[f.from[e]], pool_[f.to[e]], j, pool_[5 + e]);
    nv_ = 5 + f.ncut;
    static_assert(sizeof(Piece) == sizeof(f.piece[0]));
    std::memcpy(piece_[1 - cur_], f.piece, sizeof(f.piece));
    std::memcpy(region_[1 - cur_], f.region, sizeof(f.region));
    n_ = f.npiece;
    cur_ = 1 - cur_;
  }

  // A later plane: the pieces' vertices are classified one piece at a time.
  void clip(int j) {
    using tet_regions_clip::kCutCases;
    const Piece* in = piece_[cur_];
    Piece* out = piece_[1 - cur_];
    const std::uint8_t* in_region = region_[cur_];
    std::uint8_t* out_region = region_[1 - cur_];
    // First loop: keep the whole pieces, list the cut ones (written for every piece, counted
    // for the cut ones).
    std::uint16_t cut_list[kMaxPieces];
    std::uint8_t cut_mask[kMaxPieces];
    int m = 0, nc = 0;
    for (int k = 0; k < n_; ++k) {
      const Piece p = in[k];
      const int mask = (pool_[p.v[0]].l[j] >= 0.0) | (pool_[p.v[1]].l[j] >= 0.0) << 1 |
                       (pool_[p.v[2]].l[j] >= 0.0) << 2 | (pool_[p.v[3]].l[j] >= 0.0) << 3;
      out[m] = p;
      out_region[m] = in_region[k];
      m += mask == 15;
      cut_list[nc] = static_cast<std::uint16_t>(k);
      cut_mask[nc] = static_cast<std::uint8_t>(mask);
      nc += static_cast<unsigned>(mask - 1) < 14u;  // 1 to 14: cut
    }
    // Second loop: every cut piece makes 4 cut vertices and writes 3 pieces, and keeps those
    // of its case (kCutCases).
    for (int n = 0; n < nc; ++n) {
      const Piece p = in[cut_list[n]];
      const std::uint8_t r = in_region[cut_list[n]];
      const tet_regions_clip::CutCase& c = kCutCases[cut_mask[n]];
      std::uint16_t id[8] = {p.v[0], p.v[1], p.v[2], p.v[3]};
      const int v = nv_;
      for (int e = 0; e < 4; ++e) {
        id[4 + e] = static_cast<std::uint16_t>(v + e);
        cut(pool_[p.v[c.from[e]]], pool_[p.v[c.to[e]]], j, pool_[v + e]);
      }
      nv_ = v + c.ncut;
      for (int t = 0; t < 3; ++t) {
        for (int q = 0; q < 4; ++q) out[m + t].v[q] = id[c.tet[t][q]];
        out_region[m + t] = r;
      }
      m += c.nout;
    }
    n_ = m;
    cur_ = 1 - cur_;
  }

  // O's reference simplex (lambda_1..3 as coordinates) has volume 1/6, and |det| of a piece's
  // edge vectors in those coordinates is 6 times its volume there: the fraction of O.
  void moments(double fraction[4], double lmom[4][4]) const {
    double f[4] = {}, m[4][4] = {};
    const Piece* pc = piece_[cur_];
    const std::uint8_t* region = region_[cur_];
    for (int k = 0; k < n_; ++k) {
      const double* a = pool_[pc[k].v[0]].l;
      const double* b = pool_[pc[k].v[1]].l;
      const double* c = pool_[pc[k].v[2]].l;
      const double* d = pool_[pc[k].v[3]].l;
      const double u1 = b[1] - a[1], u2 = b[2] - a[2], u3 = b[3] - a[3];
      const double v1 = c[1] - a[1], v2 = c[2] - a[2], v3 = c[3] - a[3];
      const double w1 = d[1] - a[1], w2 = d[2] - a[2], w3 = d[3] - a[3];
      const double w =
          std::abs(u1 * (v2 * w3 - v3 * w2) + u2 * (v3 * w1 - v1 * w3) + u3 * (v1 * w2 - v2 * w1));
      const int r = region[k];
      f[r] += w;
      for (int i = 0; i < 4; ++i) m[r][i] += w * (a[i] + b[i] + c[i] + d[i]);
    }
    for (int r = 0; r < 4; ++r) {
      fraction[r] = f[r];
      for (int i = 0; i < 4; ++i) lmom[r][i] = 0.25 * m[r][i];
    }
  }

 private:
  // The first plane (clip_first) leaves at most 3 pieces per region (12) and adds at most 6
  // vertices (the edges a split of the 5 vertices cuts). Each later plane turns a piece into at
  // most 3 and adds at most 4 vertices per piece (one per cut edge): before planes 2, 3, 4 at most
  // 12, 36, 108 pieces, after them at most 324, and 5 + 6 + 4 (12 + 36 + 108) = 635 vertices. One
  // more vertex and two more pieces of room take a cut piece's unused fourth cut and pieces.
  static constexpr int kMaxPieces = 324 + 2;
  static constexpr int kMaxVertices = 635 + 1;

  struct Vertex {
    double l[4];  // lambda_j^O
  };
  struct Piece {
    std::uint16_t v[4];
  };

  // The point where lambda_j = 0 on the edge from p (lambda_j >= 0) to q (lambda_j < 0). Its
  // lambda_j is left as interpolated (0 to round-off, and no later plane reads it): writing an
  // exact 0 over the vector store costs a store-forwarding stall at the vertex's next read.
  static void cut(const Vertex& p, const Vertex& q, int j, Vertex& out) {
    const double t = p.l[j] / (p.l[j] - q.l[j]);
    for (int i = 0; i < 4; ++i) out.l[i] = p.l[i] + t * (q.l[i] - p.l[i]);
  }
  Vertex pool_[kMaxVertices];
  Piece piece_[2][kMaxPieces];
  std::uint8_t region_[2][kMaxPieces];  // the region (0-3) of each piece
  int nv_ = 0, n_ = 0, cur_ = 0;
};

}  // namespace femdem::contact
