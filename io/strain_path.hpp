// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A prescribed homogeneous deformation history for the material-point driver
// (`femdem check SCENE --material NAME --strain-path FILE`).
//
// File format: one target deformation gradient per line, 9 numbers F11 F12 F13 F21 ... F33
// (row-major), separated by spaces or commas; '#' starts a comment; blank lines are skipped.
// The driver goes from each target to the next in equal increments, starting from F = I.
#include <string>
#include <vector>

#include "materials/material_point.hpp"

namespace femdem {

// Throws InputError naming the file and line for unreadable files, wrong counts, non-numbers
// and det F <= 0.
std::vector<F3> read_strain_path(const std::string& path);

}  // namespace femdem
