// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz target: the gmsh MSH reader (read_gmsh: ASCII 4.1 and 2.x, TET4 promotion, TET10
// reordering, orientation and quality checks).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "io/mesh/gmsh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = femdem::fuzz::write_input("mesh.msh", data, size);
  femdem::fuzz::expect_result_or_input_error([&] {
    femdem::GmshReadInfo info;
    femdem::read_gmsh(path, &info);
  });
  return 0;
}
