// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem check`: what a scene builds, printed without running anything; and, with --material
// and --strain-path, one material point of the scene driven through a deformation history.
#include <string>

#include "io/scene/scene_reader.hpp"

namespace femdem {

// The scene's simulation settings, materials, bodies (with mesh quality), walls, compaction,
// constraints and contact, then "Scene OK.".
void print_scene_summary(const SceneFile& scene);

// The stress path of material `name` under the deformation gradients of `path_file`, as CSV on
// standard output. Returns the exit code; throws InputError.
int material_point(const SceneFile& scene, const std::string& name, const std::string& path_file,
                   int substeps);

}  // namespace femdem
