// SPDX-License-Identifier: GPL-3.0-or-later
#include "fuzz_input.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace femdem::fuzz {
namespace {

namespace fs = std::filesystem;

struct WorkFolder {
  std::string path;
  WorkFolder() {
    const char* tmp = std::getenv("TMPDIR");
    const fs::path base = tmp && *tmp ? fs::path(tmp) : fs::temp_directory_path();
    path = (base / ("femdem_fuzz_" + std::to_string(::getpid()))).string();
    fs::create_directories(path);
    // Copies, not links: a scene may write where it points (a packing's `cache`), and a
    // mutated one must not overwrite the shipped files.
    const fs::path source(FEMDEM_SOURCE_DIR);
    const auto copy_options = fs::copy_options::recursive | fs::copy_options::overwrite_existing;
    fs::copy(source / "scenes" / "meshes", fs::path(path) / "meshes", copy_options);
    fs::copy(source / "scenes" / "packings", fs::path(path) / "packings", copy_options);
    fs::copy(source / "tests" / "data", fs::path(path) / "data", copy_options);
    fs::create_directories(fs::path(path) / "mesh_cache");
    ::setenv("FEMDEM_MESH_CACHE", (fs::path(path) / "mesh_cache").c_str(), 1);
  }
  ~WorkFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

const std::string& work_folder() {
  static const WorkFolder folder;
  return folder.path;
}

std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = work_folder() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  if (std::fclose(f) != 0) std::abort();
  return path;
}

}  // namespace femdem::fuzz
