// SPDX-License-Identifier: GPL-3.0-or-later
#include "contact/penalty_potential_law.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "contact/tet_potential_contact.hpp"

namespace femdem {
namespace {

using Vec3 = Eigen::Vector3d;

// Barycentric coordinates of p in the tetrahedron t (any orientation, non-degenerate).
std::array<double, 4> barycentric(const contact::TetCorners& t, const Vec3& p) {
  Eigen::Matrix3d A;
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) A(k, a) = t[a + 1][k] - t[0][k];
  const Vec3 rhs(p[0] - t[0][0], p[1] - t[0][1], p[2] - t[0][2]);
  const Vec3 l = A.inverse() * rhs;
  return {1.0 - l[0] - l[1] - l[2], l[0], l[1], l[2]};
}

// Sizes of a linear tetrahedron for the stiffness bound of a pair: its total surface area and
// the largest gradient of its potential, max |grad 4 lambda_i| = 4 / (smallest altitude)
// = 4 max_i S_i / (3 V). Zero area for a degenerate tetrahedron (the pair is then not touching).
struct TetSize {
  double area = 0.0, max_gradient = 0.0;
};

TetSize tet_size(const contact::TetCorners& t) {
  const Vec3 p0(t[0][0], t[0][1], t[0][2]), p1(t[1][0], t[1][1], t[1][2]),
      p2(t[2][0], t[2][1], t[2][2]), p3(t[3][0], t[3][1], t[3][2]);
  const double six_v = std::abs((p1 - p0).dot((p2 - p0).cross(p3 - p0)));
  const double s[4] = {0.5 * (p2 - p1).cross(p3 - p1).norm(), 0.5 * (p2 - p0).cross(p3 - p0).norm(),
                       0.5 * (p1 - p0).cross(p3 - p0).norm(),
                       0.5 * (p1 - p0).cross(p2 - p0).norm()};
  TetSize z;
  if (!(six_v > 0.0)) return z;
  z.area = s[0] + s[1] + s[2] + s[3];
  z.max_gradient = 8.0 * std::max(std::max(s[0], s[1]), std::max(s[2], s[3])) / six_v;
  return z;
}

// Upper bound of the stiffness of a pair against relative translation, from the penalty and
// the sizes of the two tetrahedra alone (thesis eq. 2.119 and 2.124: the contact stiffness of
// a boundary tetrahedron is set by k = a E and its size). With E = p int_{A n B} (phi_A +
// phi_B), moving B by delta moves only the faces of B through phi_A (which is continuous and
// vanishes on dA), so d2/d delta2 of p int_{A n B} phi_A is the flux p int_{dB n A}
// (grad phi_A . e)(n . e) dS, at most p max|grad phi_A| area(dB n A); likewise for phi_B. dB n A
// and dA n B are parts of the boundary of the convex A n B, whose area is at most that of
// either tetrahedron. So k <= p (max|grad phi_A| + max|grad phi_B|) min(S_A, S_B). Two
// regular tetrahedra with faces flush (the stiffest contact, 4 p S (1/h_A + 1/h_B)) reach a
// quarter of it; the 2 N^2 / 2E of the contacts in test_body_contact stays below it (the
// same numbers as without the bound), so it acts where the secant has lost its meaning.
double pair_stiffness_bound(const contact::TetCorners& a, const contact::TetCorners& b,
                            double penalty) {
  const TetSize sa = tet_size(a), sb = tet_size(b);
  return penalty * (sa.max_gradient + sb.max_gradient) * std::min(sa.area, sb.area);
}

}  // namespace

void PenaltyPotentialLaw::evaluate(const PairInput& in, PairSpring& spring, PairOutcome& out) {
  const contact::TetCorners& a = *in.corners_a;
  const contact::TetCorners& b = *in.corners_b;
  const auto& ta = in.tet_a;
  const auto& tb = in.tet_b;
  out.energy = out.dissipated = out.stiffness = out.penetration = 0.0;
  contact::TetPairContact o;
  out.touching = contact::tet_potential_contact(a, b, in.penalty, o);
  if (!out.touching || !(o.energy > 0.0)) {
    out.touching = false;
    // released: the spring's energy goes to friction
    const double u2 = spring.stick[0] * spring.stick[0] + spring.stick[1] * spring.stick[1] +
                      spring.stick[2] * spring.stick[2];
    out.dissipated = 0.5 * spring.stick_stiffness * u2;
    spring.stick[0] = spring.stick[1] = spring.stick[2] = 0.0;
    return;
  }
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 3; ++k) {
      out.force[3 * c + k] = o.force_a[c][k];
      out.force[12 + 3 * c + k] = o.force_b[c][k];
    }
  out.energy = o.energy;
  Vec3 fb = Vec3::Zero();
  for (int c = 0; c < 4; ++c) fb += Vec3(o.force_b[c][0], o.force_b[c][1], o.force_b[c][2]);
  const double N = fb.norm();
  const double k_n = N * N / (2.0 * o.energy);
  // The stable step: a pair stiffer than its secant (a corner poking in: E ~ d^4) by up to 2,
  // but never stiffer than the geometric bound. The secant alone is not a sound estimate when
  // the overlap is a sliver at round-off level (corners, edges or faces of aligned meshes
  // exactly coincident): E is then a difference of O(volume) terms that cancels to almost
  // nothing while N keeps its honest size (volume x potential gradient), and N^2 / 2E grew by
  // 12 orders of magnitude and collapsed the step. The bound depends on the geometry only.
  // The friction spring takes the same capped secant, so that the stiffness counted for the
  // step covers it too; in a regular contact the cap does not act and k_t = N^2 / 2E.
  const double k_s = std::min(k_n, 0.5 * pair_stiffness_bound(a, b, in.penalty));
  out.stiffness = 2.0 * k_s;
  if (N > 0.0) out.penetration = 2.0 * o.energy / N;
  for (int k = 0; k < 3; ++k) {
    out.normal_force_b[k] = fb[k];
    out.centroid[k] = o.overlap_centroid[k];
  }
  out.secant = k_s;
  if (in.friction <= 0.0 || !(N > 0.0)) return;

  const Vec3 n = fb / N;
  const Vec3 c(o.overlap_centroid[0], o.overlap_centroid[1], o.overlap_centroid[2]);
  const auto la = barycentric(a, c), lb = barycentric(b, c);
  Vec3 va = Vec3::Zero(), vb = Vec3::Zero();
  for (int q = 0; q < 4; ++q) {
    va += la[q] * Vec3(in.v_a[3 * ta[q]], in.v_a[3 * ta[q] + 1], in.v_a[3 * ta[q] + 2]);
    vb += lb[q] * Vec3(in.v_b[3 * tb[q]], in.v_b[3 * tb[q] + 1], in.v_b[3 * tb[q] + 2]);
  }
  const Vec3 v_rel = vb - va;
  const Vec3 du = in.step_dt * (v_rel - v_rel.dot(n) * n);
  Vec3 u_old(spring.stick[0], spring.stick[1], spring.stick[2]);
  u_old -= u_old.dot(n) * n;  // the contact plane turns with the bodies
  Vec3 u = u_old + du;
  const double k_t = k_s;
  const double limit = in.friction * N / k_t;
  const double stretch = u.norm();
  if (stretch > limit) {
    // slides: the spring force's work over the step (trapezoidal, as the integrator applies it)
    // minus the change of its stored energy
    const Vec3 u_new = u * (limit / stretch);
    out.dissipated =
        0.5 * k_t * ((u_old + u_new).dot(du) - (u_new.squaredNorm() - u_old.squaredNorm()));
    u = u_new;
  }
  spring.stick[0] = u[0], spring.stick[1] = u[1], spring.stick[2] = u[2];
  spring.stick_stiffness = k_t;
  out.energy += 0.5 * k_t * u.squaredNorm();
  const Vec3 ft = -k_t * u;  // on B at c; minus that on A
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k < 3; ++k) {
      out.force[3 * q + k] -= la[q] * ft[k];
      out.force[12 + 3 * q + k] += lb[q] * ft[k];
    }
}

}  // namespace femdem
