// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz target: the scene reader with --set overrides (load_scene: TOML, every section, the mesh
// generators and mesh files it names, packings). Lines of the input that start with "#set "
// are also passed as overrides ("#set bodies.ball.velocity=[0,0,-1]"): they are TOML comments,
// so the same file is a valid scene, and the fuzzer mutates scene and overrides together.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_input.hpp"
#include "io/scene/scene_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> overrides;
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("#set ", 0) == 0) overrides.push_back(line.substr(5));
  const std::string path = femdem::fuzz::write_input("scene.toml", data, size);
  // (meshes capped, each and in all, so that an input costs milliseconds: a mutated element_size
  // or packing would otherwise make millions of elements, or CAD meshes of minutes)
  femdem::fuzz::expect_result_or_input_error([&] {
    femdem::load_scene(path, overrides, {.max_mesh_elements = 2000, .max_total_elements = 10000});
  });
  return 0;
}
