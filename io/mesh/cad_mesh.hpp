// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// CAD surfaces -> TET10 volume meshes.
//
//  1. import_surface (io/mesh/cad_import.cpp, assimp): any format assimp reads (STL ASCII and
//     binary, OBJ, PLY, OFF, glTF, 3MF, ...) becomes one indexed triangle surface; node
//     transforms of the file are applied, points and lines are ignored, polygons triangulated,
//     coordinates multiplied by `scale`, and vertices closer than merge_tolerance x (bounding
//     box diagonal) merged.
//  2. mesh_surface (io/mesh/cad_mesh.cpp, the only file that includes CGAL): the surface is checked
//     and repaired with CGAL Polygon_mesh_processing (degenerate and duplicate triangles
//     dropped, orientation made consistent and outward), then must be closed, edge- and
//     vertex-manifold and free of self-intersections; it is then meshed with CGAL Mesh_3
//     (polyhedral domain, sharp edges protected), and the tetrahedra promoted to TET10.
// Every problem with the input is an InputError naming the file and saying what is wrong and
// where ("surface is open: 12 border edges, first near (x, y, z)").
//
// The result is deterministic: the same file and options give the same mesh, bit for bit
// (CGAL's random generator is seeded, and no optimisation step has a time limit).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

// Changes whenever the meshing code changes its output for the same input and options; it is
// part of the mesh cache key (io/mesh/mesh_cache.hpp), so old cached meshes are not reused.
inline constexpr int kCadMesherVersion = 1;

struct TriangleSurface {
  std::vector<Vec3> points;
  std::vector<std::array<std::int32_t, 3>> triangles;
};

struct CadImportInfo {
  std::string format;                   // assimp's description of the importer, if known
  std::int64_t meshes = 0;              // meshes in the file (all are used)
  std::int64_t input_vertices = 0;      // vertices as stored in the file
  std::int64_t input_triangles = 0;     // triangles after assimp's triangulation
  std::int64_t skipped_primitives = 0;  // points and lines, ignored
  std::int64_t merged_vertices = 0;     // vertices after the tolerance merge
};

// Whether assimp has an importer for this file extension (".stl", lower case, with the dot),
// and the list of all it has ("*.3d;*.3ds;...", shortened for messages).
bool cad_format_supported(const std::string& extension);
std::string cad_extensions();

// Throws InputError (file = path) if assimp cannot read the file or it holds no triangles.
TriangleSurface import_surface(const std::string& path, double scale, double merge_tolerance,
                               CadImportInfo* info = nullptr);

struct CadMeshOptions {
  double element_size = 0.0;  // target edge length of the tetrahedra, after scaling (required)
  double scale = 1.0;         // file units -> m, e.g. 0.001 for a file in mm
  // Relative to the bounding-box diagonal: vertices closer than this are one vertex.
  double merge_tolerance = 1e-7;
  // Edges whose two faces' normals differ by more than this (degrees) are sharp: they are
  // protected, so the mesh keeps them (cube edges and corners). CGAL's detect_features.
  double feature_angle = 60.0;
  double facet_angle = 25.0;    // lower bound of the surface triangles' angles (degrees)
  double facet_distance = 0.0;  // surface approximation error; 0: element_size / 10
  double cell_radius_edge_ratio = 3.0;
  // ODT smoothing: on the test shapes it raised the 5th-percentile dihedral angle from 30-32 to
  // 36-39 degrees and lowered the worst aspect ratio on 7 of 8 meshes (sphere at h 0.1: 5.7 to
  // 4.6), for 1.3-2.4x the CPU time (docs/VALIDATION.md, section 6). Off by default because
  // CGAL 5.5's ODT crashed (segmentation fault in Mesh_global_optimizer) on a 2 m cube at
  // h 0.5 placed at x = 10; opt in with `femdem mesh --odt`.
  bool odt = false;
  bool lloyd = false;                  // Lloyd smoothing
  bool perturb = true;                 // sliver perturbation
  bool exude = true;                   // sliver exudation
  double perturb_sliver_bound = 10.0;  // degrees; perturbation stops when no angle is below
  unsigned seed = 0;                   // CGAL's random generator
  bool repair = true;                  // false: report what would be repaired as errors instead
  // A mesh estimated to need more tetrahedra than this is refused before meshing (a typo in
  // element_size must fail fast instead of exhausting memory).
  std::int64_t max_elements = 20'000'000;
};

// The options that change the mesh, as text: part of the cache key.
std::string cad_options_key(const CadMeshOptions& options);

struct CadMeshReport {
  CadImportInfo import;
  std::vector<std::string> repairs;  // what was repaired, human-readable
  std::int64_t surface_triangles = 0;
  std::int64_t components = 0;   // closed surface components (shells)
  std::int64_t sharp_edges = 0;  // input edges protected as features
  double surface_area = 0.0;
  double surface_volume = 0.0;  // volume enclosed by the (repaired) surface
  std::int64_t tet4 = 0;        // tetrahedra from Mesh_3
  double import_seconds = 0.0, check_seconds = 0.0, mesh_seconds = 0.0;
};

// Checks, repairs and meshes a surface. `path` is only used in error messages.
Tet10Mesh mesh_surface(TriangleSurface surface, const CadMeshOptions& options,
                       const std::string& path, CadMeshReport* report = nullptr);

// import_surface + mesh_surface.
Tet10Mesh mesh_cad_file(const std::string& path, const CadMeshOptions& options,
                        CadMeshReport* report = nullptr);

// A few lines about the surface and the meshing (for `femdem mesh` and the scene notes).
std::string format_cad_report(const CadMeshReport& report);

}  // namespace femdem
