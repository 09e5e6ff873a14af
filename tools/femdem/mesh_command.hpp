// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem mesh SURFACE --size H`: a closed CAD surface meshed into TET10 (io/mesh/cad_mesh) and
// written as a gmsh .msh file, with the repair report and the mesh quality printed.
#include <string>

#include "io/mesh/cad_mesh.hpp"

namespace femdem {

// mesh_output empty: the input's name with .msh. Returns the exit code; throws InputError.
int mesh_command(const std::string& mesh_input, std::string mesh_output,
                 const CadMeshOptions& mesh_options);

}  // namespace femdem
