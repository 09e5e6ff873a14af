// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A cache of CAD volume meshes, so that the runs of a sweep (or repeated runs of a scene) mesh
// a CAD file once.
//
// Key: SHA-256 of the CAD file's bytes together with cad_options_key() (element_size, scale,
// every mesher option, kCadMesherVersion and the CGAL version). The entry is
// DIR/<SHA-256 of the key>.msh, a gmsh MSH 4.1 file written atomically (io/atomic_file.hpp), so
// parallel jobs that miss together each mesh and the last rename wins with identical content;
// a reader never sees a partial file. An unreadable entry is re-meshed and replaced.
//
// DIR is $FEMDEM_MESH_CACHE if set (the value "off" disables the cache), else
// $XDG_CACHE_HOME/femdem/meshes, else $HOME/.cache/femdem/meshes. Entries are never deleted
// automatically; removing the folder is always safe.
#include <filesystem>
#include <string>
#include <string_view>

#include "io/mesh/cad_mesh.hpp"

namespace femdem {

// Lower-case hex SHA-256 (FIPS 180-4) of `data`.
std::string sha256_hex(std::string_view data);

// The cache folder; empty if the cache is disabled.
std::filesystem::path mesh_cache_dir();

struct CachedCadMesh {
  Tet10Mesh mesh;
  bool hit = false;        // read from the cache
  std::string cache_file;  // the entry (read or written); empty if the cache is off
  std::string note;        // one line for the log: hit or miss, where, how long
  CadMeshReport report;    // filled when meshed (a miss)
};

// mesh_cad_file through the cache. Errors in the input are InputErrors as for mesh_cad_file; a
// cache folder that cannot be written only adds a warning to the note.
CachedCadMesh mesh_cad_file_cached(const std::string& path, const CadMeshOptions& options);

}  // namespace femdem
