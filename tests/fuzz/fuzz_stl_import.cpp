// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz target: STL import (ASCII and binary, through assimp) and the surface check and repair
// that precede meshing (merging, collapsed and duplicate triangles, open and non-manifold edges,
// orientation, self-intersections, components). Meshing itself is not fuzzed: a limit of one
// tetrahedron makes every surface that passes the checks stop at the size estimate, so an input
// costs milliseconds instead of a CGAL meshing run.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "io/mesh/cad_mesh.hpp"

namespace {
constexpr std::size_t kMaxCheckedTriangles = 300;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = femdem::fuzz::write_input("surface.stl", data, size);
  femdem::fuzz::expect_result_or_input_error([&] {
    femdem::CadMeshOptions options;
    options.element_size = 1.0;
    options.max_elements = 1;
    femdem::CadMeshReport report;
    femdem::TriangleSurface surface =
        femdem::import_surface(path, options.scale, options.merge_tolerance, &report.import);
    // the check and repair only for small surfaces: CGAL's self-intersection test on the
    // 47 kB tetrapod seed and its mutations costs up to a second an input, which starves the
    // fuzzer; the import is fuzzed on every input
    if (surface.triangles.size() > kMaxCheckedTriangles) return;
    femdem::mesh_surface(std::move(surface), options, path, &report);
  });
  return 0;
}
