// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/mesh_command.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/gmsh_io.hpp"
#include "tools/femdem/exit_codes.hpp"
#include "tools/femdem/text_format.hpp"

namespace femdem {

int mesh_command(const std::string& mesh_input, std::string mesh_output,
                 const CadMeshOptions& mesh_options) {
  if (mesh_output.empty())
    mesh_output = std::filesystem::path(mesh_input).replace_extension(".msh").string();
  if (std::filesystem::path(mesh_output).extension() != ".msh")
    throw InputError("the output must be a .msh file", mesh_output, 0, 0, "-o");
  if (std::filesystem::weakly_canonical(mesh_output) ==
      std::filesystem::weakly_canonical(mesh_input))
    throw InputError("the output would overwrite the input", mesh_output, 0, 0, "-o");
  CadMeshReport report;
  const Tet10Mesh m = mesh_cad_file(mesh_input, mesh_options, &report);
  // the volume is named after the input file, so a scene can select it among others
  std::string volume = std::filesystem::path(mesh_input).stem().string();
  std::replace(volume.begin(), volume.end(), '"', '_');
  write_gmsh(m, mesh_output, volume);
  fmt::print("{}\n", format_cad_report(report));
  fmt::print("{}", indent(format_mesh_quality(mesh_quality(m)), ""));
  fmt::print("wrote {}\n", mesh_output);
  return kExitOk;
}

}  // namespace femdem
