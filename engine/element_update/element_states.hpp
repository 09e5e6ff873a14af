// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Gauss-point history of one element, component by component with its 4 Gauss points
// adjacent (the layout the SIMD element update loads as one pack per component), and the
// per-point view the scalar kernel and the outputs use.
#include "materials/finite_strain_update.hpp"

namespace femdem {

struct ElementStates {
  double Cp_inv[6][4] = {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1},
                         {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  double eps_p[4] = {0, 0, 0, 0};
  double kappa[4] = {0, 0, 0, 0};

  GaussPointState at(int g) const {
    GaussPointState s;
    for (int c = 0; c < 6; ++c) s.Cp_inv[c] = Cp_inv[c][g];
    s.eps_p = eps_p[g];
    s.kappa = kappa[g];
    return s;
  }
  void set(int g, const GaussPointState& s) {
    for (int c = 0; c < 6; ++c) Cp_inv[c][g] = s.Cp_inv[c];
    eps_p[g] = s.eps_p;
    kappa[g] = s.kappa;
  }
};

}  // namespace femdem
