// SPDX-License-Identifier: GPL-3.0-or-later
// A tiny program outside femdem's tree: loads a scene with the installed library and prints
// each body's name, node and element count, the way a user's own tool would.
#include <cstdio>
#include <exception>

#include "engine/errors.hpp"
#include "io/scene/scene_reader.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: load_scene SCENE.toml\n");
    return 2;
  }
  try {
    const femdem::SceneFile scene = femdem::load_scene(argv[1]);
    for (const femdem::BodySpec& b : scene.model.bodies)
      std::printf("%s: %zu nodes, %zu elements\n", b.name.c_str(), b.mesh.nodes.size(),
                  b.mesh.elements.size());
    return 0;
  } catch (const femdem::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
