// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// gmsh MSH files (format 4.1 and 2.x, ASCII or binary) <-> Tet10Mesh.
//
// Reading:
//  - Only tetrahedra are kept: type 4 (TET4, promoted to TET10 by adding one node at the
//    midpoint of every edge, shared between the elements around that edge) and type 11 (TET10,
//    reordered from gmsh's node order, which swaps our 8 and 9). Points, lines, triangles,
//    quadrangles and other volume types are ignored; other sections are skipped.
//  - Node tags may be arbitrary (non-contiguous, unordered). Nodes not used by any tetrahedron
//    are dropped; the others keep the file's order, and promoted mid-edge nodes follow them.
//  - If every tetrahedron is negatively oriented, all are flipped (GmshReadInfo::flipped). If
//    only some are, or an element is degenerate (|corner volume| <= 1e-10 of the mean) or its
//    quadratic map folds (scaled Jacobian <= 0), InputError names the element's gmsh tag.
//  - Physical groups ($PhysicalNames, and $Entities in MSH 4.1, or the elements' physical tags in
//    MSH 2) come back in GmshReadInfo::groups: a volume as the tetrahedra in it, a point, curve
//    or surface as the nodes of its elements that the tetrahedra use (with, after a TET4
//    promotion, the new mid-edge nodes on its lines, triangles and quadrangles).
//  - Every problem throws InputError with the file and the 1-based line (and column where it
//    helps; in binary data the byte offset): unsupported versions (MSH 4.0, 3.x), binary files
//    of the other byte order or of a data size other than 8, element types of unknown node
//    count in binary data, truncated files, malformed or non-numeric data, dangling node
//    references, no tetrahedra at all.
// Writing: MSH 4.1 ASCII, one volume entity (a physical volume when given a name), TET10
// elements (type 11), node tags 1..N in mesh order, element tags 1..E, coordinates in shortest
// round-trip form, so write + read gives the same mesh bit for bit.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

struct GmshPhysicalGroup {
  int dim = 0;                         // 0 point, 1 curve, 2 surface, 3 volume
  std::int64_t tag = 0;                // the physical tag
  std::string name;                    // from $PhysicalNames; "" when the file names none
  std::vector<std::int32_t> elements;  // a volume: its tetrahedra (mesh element indices)
  std::vector<std::int32_t> nodes;     // a point, curve or surface: mesh node indices, sorted

  // The name, or "#TAG" for an unnamed group: what a scene uses to select it.
  std::string label() const { return name.empty() ? "#" + std::to_string(tag) : name; }
};

struct GmshReadInfo {
  std::string version;                    // as in the file, e.g. "4.1" or "2.2"
  std::int64_t tet4 = 0;                  // TET4 elements read (and promoted)
  std::int64_t tet10 = 0;                 // TET10 elements read
  std::int64_t ignored_elements = 0;      // non-tetrahedral elements skipped
  std::int64_t unused_nodes = 0;          // nodes dropped because no tetrahedron uses them
  bool flipped = false;                   // all tetrahedra were inverted and have been flipped
  std::vector<std::string> notes;         // human-readable remarks about the above
  std::vector<GmshPhysicalGroup> groups;  // by dimension, then tag
};

// A body taken from a gmsh file: its mesh and its named node sets.
struct GmshBody {
  Tet10Mesh mesh;
  // every point, curve and surface group with nodes in the body: (label, body node indices)
  std::vector<std::pair<std::string, std::vector<std::int32_t>>> node_sets;
};

// The whole mesh (`volume` empty) or the tetrahedra of the physical volume labelled `volume`
// with the nodes they use (in their order in the file's mesh), and the lower-dimensional groups
// as node sets of it. Throws std::invalid_argument when no volume has that label.
GmshBody gmsh_body(Tet10Mesh mesh, const GmshReadInfo& info, const std::string& volume);

Tet10Mesh read_gmsh(const std::string& path, GmshReadInfo* info = nullptr);

// The MSH 4.1 text of the mesh (what write_gmsh writes).
// `physical_volume`: the name of a physical volume holding every element ("" for none).
std::string gmsh_text(const Tet10Mesh& mesh, const std::string& physical_volume = {});

// Writes the file atomically (a temporary file renamed over `path`, see io/atomic_file.hpp).
// Throws std::runtime_error if the file cannot be written.
void write_gmsh(const Tet10Mesh& mesh, const std::string& path,
                const std::string& physical_volume = {});

}  // namespace femdem
