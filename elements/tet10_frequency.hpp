// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Highest natural frequency of one linear-elastic TET10 element with HRZ lumped mass.
//
// Why: for lumped mass, max_e omega_e bounds the assembled mesh's highest frequency from above
// (u'Ku = sum u_e'K_e u_e <= max_e omega_e^2 u'Mu), so dt = 2 / max_e omega_e is a guaranteed
// stable central-difference step, without guessing an "effective length" for quadratic elements.
namespace femdem {

// dNdX: 4 x 10 x 3 reference gradients; w: 4 Gauss weights x det J0; mass: element mass.
double tet10_max_frequency(const double* dNdX, const double* w, double element_mass,
                           double lambda, double G);

}  // namespace femdem
