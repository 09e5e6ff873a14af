// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The linear-elastic stiffness of one TET10 element at its current shape, applied to a vector:
// f = K_e(x) u with K_e = sum_g w_g J_g B_g' D B_g, the small-strain stiffness (Lame lambda, G)
// integrated over the deformed element. The stable-step estimate (engine/stable_step/) takes
// the highest frequency of the assembled system from it: the step of an explicit run is limited
// by the stiffness a point has when it unloads, which is elastic, on the geometry it has now.
// The stress's own (geometric) stiffness is left out: sigma / E is below 1e-2 for the metals,
// rock and concrete this engine is used for, so it moves the frequency by less than 1 %.
namespace femdem {

// x: the 10 nodes' current positions (30); dNdX: reference gradients (4 x 10 x 3); w: Gauss
// weights times det J0 (4); u: 30; f: 30, overwritten. Returns false (f zero) when a Gauss point
// is inverted or degenerate (det F <= 0), where the element has no stiffness to speak of.
bool tet10_elastic_action(const double* x, const double* dNdX, const double* w, double lambda,
                          double G, const double* u, double* f);

}  // namespace femdem
