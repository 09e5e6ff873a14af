// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Reads a scene file (TOML, see docs/SCENES.md), applies --set overrides, checks every value
// and builds the meshes. Every problem is an InputError naming the file, line, column and the
// dotted key (arrays of tables are named by their `name`: "bodies.ball.mesh.radius").
#include <cstdint>
#include <string>
#include <vector>

#include "engine/model_spec.hpp"

namespace femdem {

struct SceneFile {
  std::string path;                // as given on the command line
  std::string stem;                // file name without folder and extension: "taylor_bar"
  std::string directory;           // folder the scene's relative paths are resolved against
  std::string resolved_toml;       // the scene with overrides applied and every default filled in
  ModelSpec model;                 // checked; meshes generated or read, rotated and placed
  std::vector<std::string> notes;  // for the log: how CAD meshes were made (cache hit or miss)
};

// overrides: "KEY=VALUE" strings (the command line's --set). KEY is dotted, with entries of
// arrays of tables addressed by their name ("bodies.ball.velocity"); VALUE is read as a TOML
// value, or as a bare string when it is not one ("mesh.file=part.msh").
// Throws InputError.
struct SceneReadLimits {
  // > 0: a body's mesh (generated, or made from a CAD surface) of more elements than this is an
  // input error before it is made. 0: only the generators' and the mesher's own limits. What the
  // scene fuzz target sets, so that an input costs milliseconds (tests/fuzz).
  std::int64_t max_mesh_elements = 0;
  // > 0: a scene whose bodies and packings would have more elements than this in all is an
  // input error, found before a packing's bodies are meshed. 0: no cap beyond the generators'.
  std::int64_t max_total_elements = 0;
};
SceneFile load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                     SceneReadLimits limits = {});

// The rotation of `rotation = [rx, ry, rz]` (degrees) in scenes: Rz(rz) Ry(ry) Rx(rx).
Eigen::Matrix3d rotation_from_degrees(const Vec3& rotation_degrees);

// Mesh placement used by the reader: p' = Rz(rz) Ry(ry) Rx(rx) p + position, i.e. the mesh is
// turned about the fixed x axis first, then y, then z (angles in degrees, right-handed), about
// its own origin, and then translated.
void place_mesh(Tet10Mesh& mesh, const Vec3& rotation_degrees, const Vec3& position);

}  // namespace femdem
