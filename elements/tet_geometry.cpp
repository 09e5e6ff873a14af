// SPDX-License-Identifier: GPL-3.0-or-later
#include "elements/tet_geometry.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

namespace femdem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;

// Outward (for a right-handed tet) area vectors of the faces opposite corners 0..3, times 2.
std::array<Vec3, 4> face_area_vectors2(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {(c - b).cross(d - b),   // opposite 0: face 1-2-3
          (d - a).cross(c - a),   // opposite 1: face 0-3-2
          (b - a).cross(d - a),   // opposite 2: face 0-1-3
          (c - a).cross(b - a)};  // opposite 3: face 0-2-1
}

// det J of the quadratic map of element nodes x at volume coordinates L.
double tet10_det_j(const std::array<Vec3, 10>& x, const std::array<double, 4>& L) {
  // dN/dL_j, then d/dxi_k = d/dL_{k+1} - d/dL_0.
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) {
    const double g = 4.0 * L[i] - 1.0;
    // node i depends only on L_i
    if (i == 0) {
      J.col(0) -= g * x[0];
      J.col(1) -= g * x[0];
      J.col(2) -= g * x[0];
    } else {
      J.col(i - 1) += g * x[i];
    }
  }
  for (int e = 0; e < 6; ++e) {
    const int p = kTet10Edges[e][0], q = kTet10Edges[e][1];
    const Vec3& xm = x[4 + e];
    // N = 4 L_p L_q: dN/dL_p = 4 L_q, dN/dL_q = 4 L_p
    const std::array<std::pair<int, double>, 2> terms = {{{p, 4.0 * L[q]}, {q, 4.0 * L[p]}}};
    for (const auto& [j, v] : terms) {
      if (j == 0) {
        J.col(0) -= v * xm;
        J.col(1) -= v * xm;
        J.col(2) -= v * xm;
      } else {
        J.col(j - 1) += v * xm;
      }
    }
  }
  return J.determinant();
}

std::array<Vec3, 10> element_nodes(const Tet10Mesh& mesh, std::size_t e) {
  std::array<Vec3, 10> x;
  for (int i = 0; i < 10; ++i) x[i] = mesh.nodes[mesh.elements[e][i]];
  return x;
}

}  // namespace

double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

std::array<double, 4> tet_face_areas(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto s = face_area_vectors2(a, b, c, d);
  return {0.5 * s[0].norm(), 0.5 * s[1].norm(), 0.5 * s[2].norm(), 0.5 * s[3].norm()};
}

double tet_min_altitude(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto areas = tet_face_areas(a, b, c, d);
  const double amax = *std::max_element(areas.begin(), areas.end());
  if (!(amax > 0.0)) return 0.0;
  return 3.0 * std::abs(tet_signed_volume(a, b, c, d)) / amax;
}

std::array<double, 6> tet_dihedral_angles(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d) {
  const auto s = face_area_vectors2(a, b, c, d);
  std::array<double, 6> out{};
  for (int e = 0; e < 6; ++e) {
    // The edge p-q is shared by the faces opposite the two other corners k and l.
    const int p = kTet10Edges[e][0], q = kTet10Edges[e][1];
    int other[2], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != p && k != q) other[n++] = k;
    const Vec3& sk = s[other[0]];
    const Vec3& sl = s[other[1]];
    const double denom = sk.norm() * sl.norm();
    if (!(denom > 0.0)) {
      out[e] = 0.0;
      continue;
    }
    // interior angle = pi - angle between the outward normals
    const double cosang = std::clamp(-sk.dot(sl) / denom, -1.0, 1.0);
    out[e] = std::acos(cosang) * kRadToDeg;
  }
  return out;
}

double tet_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double lmax =
      std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm(),
                          (d - a).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()}));
  const double hmin = tet_min_altitude(a, b, c, d);
  if (!(hmin > 0.0)) return std::numeric_limits<double>::infinity();
  return lmax / hmin * std::sqrt(2.0 / 3.0);
}

double tet10_min_scaled_jacobian(const Tet10Mesh& mesh, std::size_t e) {
  const auto x = element_nodes(mesh, e);
  const double det0 = 6.0 * tet_signed_volume(x[0], x[1], x[2], x[3]);
  if (det0 == 0.0 || !std::isfinite(det0)) return -std::numeric_limits<double>::infinity();
  constexpr double ga = 0.5854101966249685, gb = 0.1381966011250105;
  double m = std::numeric_limits<double>::infinity();
  for (int g = 0; g < 4; ++g) {
    std::array<double, 4> L{gb, gb, gb, gb};
    L[g] = ga;
    m = std::min(m, tet10_det_j(x, L) / det0);
    std::array<double, 4> C{0.0, 0.0, 0.0, 0.0};
    C[g] = 1.0;
    m = std::min(m, tet10_det_j(x, C) / det0);
  }
  return m;
}

double tet10_volume(const Tet10Mesh& mesh, std::size_t e) {
  const auto x = element_nodes(mesh, e);
  // Degree-3 rule on the reference tet (volume 1/6): centroid with weight -4/5, the four points
  // (1/2, 1/6, 1/6, 1/6) with weight 9/20 each.
  double v = -0.8 * tet10_det_j(x, {0.25, 0.25, 0.25, 0.25});
  for (int g = 0; g < 4; ++g) {
    std::array<double, 4> L{1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0};
    L[g] = 0.5;
    v += 0.45 * tet10_det_j(x, L);
  }
  return v / 6.0;
}

MeshQuality mesh_quality(const Tet10Mesh& mesh) {
  MeshQuality q;
  q.elements = static_cast<std::int64_t>(mesh.elements.size());
  q.nodes = static_cast<std::int64_t>(mesh.nodes.size());
  if (mesh.elements.empty()) return q;
  constexpr double inf = std::numeric_limits<double>::infinity();
  q.min_dihedral_deg = inf;
  q.max_dihedral_deg = -inf;
  q.max_aspect_ratio = 0.0;
  q.min_volume = inf;
  q.max_volume = -inf;
  q.min_scaled_jacobian = inf;
  q.min_edge = inf;
  q.max_edge = 0.0;
  double sum_abs = 0.0;
  std::vector<double> vols(mesh.elements.size()), sj(mesh.elements.size());
  std::vector<double> min_angle(mesh.elements.size()), aspect(mesh.elements.size());
  double edge_sum = 0.0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const auto& t = mesh.elements[e];
    const Vec3 &a = mesh.nodes[t[0]], &b = mesh.nodes[t[1]], &c = mesh.nodes[t[2]],
               &d = mesh.nodes[t[3]];
    const double v = tet_signed_volume(a, b, c, d);
    vols[e] = v;
    sum_abs += std::abs(v);
    q.min_volume = std::min(q.min_volume, v);
    q.max_volume = std::max(q.max_volume, v);
    for (const auto& ed : kTet10Edges) {
      const double l = (mesh.nodes[t[ed[1]]] - mesh.nodes[t[ed[0]]]).norm();
      edge_sum += l;
      q.min_edge = std::min(q.min_edge, l);
      q.max_edge = std::max(q.max_edge, l);
    }
    const auto ang = tet_dihedral_angles(a, b, c, d);
    min_angle[e] = *std::min_element(ang.begin(), ang.end());
    for (double x : ang) {
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, x);
      q.max_dihedral_deg = std::max(q.max_dihedral_deg, x);
    }
    aspect[e] = tet_aspect_ratio(a, b, c, d);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, aspect[e]);
    sj[e] = tet10_min_scaled_jacobian(mesh, e);
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, sj[e]);
    q.total_volume += tet10_volume(mesh, e);
  }
  q.mean_edge = edge_sum / (6.0 * static_cast<double>(mesh.elements.size()));
  {
    // Nearest-rank percentiles: the element at rank ceil(0.05 n) from the bad end.
    const std::size_t n = mesh.elements.size();
    const std::size_t k = (n * 5 + 99) / 100 - 1;
    std::nth_element(min_angle.begin(), min_angle.begin() + k, min_angle.end());
    q.p05_min_dihedral_deg = min_angle[k];
    std::nth_element(aspect.begin(), aspect.begin() + k, aspect.end(), std::greater<double>());
    q.p95_aspect_ratio = aspect[k];
  }
  const double tiny = 1e-12 * sum_abs / static_cast<double>(mesh.elements.size());
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    if (!(vols[e] > tiny) || !(sj[e] > 0.0)) {
      if (q.first_bad_element < 0) q.first_bad_element = static_cast<std::int64_t>(e);
      ++q.bad_elements;
    }
  }
  return q;
}

std::string format_mesh_quality(const MeshQuality& q) {
  char buf[768];
  std::snprintf(buf, sizeof buf,
                "elements %lld, nodes %lld, volume %.6g\n"
                "dihedral angles %.2f .. %.2f deg (5 %% of elements below %.2f), "
                "worst aspect ratio %.3f (1 = regular; 5 %% above %.3f)\n"
                "edge lengths %.4g .. %.4g (mean %.4g), corner-tet volumes %.4g .. %.4g\n"
                "min scaled Jacobian %.4f",
                static_cast<long long>(q.elements), static_cast<long long>(q.nodes), q.total_volume,
                q.min_dihedral_deg, q.max_dihedral_deg, q.p05_min_dihedral_deg, q.max_aspect_ratio,
                q.p95_aspect_ratio, q.min_edge, q.max_edge, q.mean_edge, q.min_volume, q.max_volume,
                q.min_scaled_jacobian);
  std::string s = buf;
  if (q.bad_elements > 0) {
    std::snprintf(buf, sizeof buf, "\n%lld inverted or degenerate element(s), first: %lld",
                  static_cast<long long>(q.bad_elements),
                  static_cast<long long>(q.first_bad_element));
    s += buf;
  } else {
    s += "\nno inverted or degenerate elements";
  }
  return s;
}

}  // namespace femdem
