// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What every fuzz target shares. The readers under test take paths, so each input is written to
// a file in a folder private to the process (made once, under TMPDIR, removed at exit); the
// folder holds copies of the shipped scenes' meshes/ and packings/ and of the tests' data/, so
// that seeds naming "meshes/cube.stl" or "data/cube_tet4_v22.msh" resolve and whatever a
// mutated scene writes (a packing cache) lands in the copies. CAD meshes are cached in that
// folder too (FEMDEM_MESH_CACHE), never in the user's cache.
//
// The contract a target checks: a reader either returns or throws femdem::InputError. Anything
// else (another exception, a crash, a sanitizer report, a hang caught by the fuzzer's timeout)
// is a bug; the caught error must also name something (a non-empty message).
#include <cstddef>
#include <cstdint>
#include <string>

namespace femdem::fuzz {

// The private folder, created on first use.
const std::string& work_folder();

// Writes the bytes to work_folder()/name and returns the file's path.
std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size);

// Runs f(); an InputError is the expected answer to a bad input and is swallowed after checking
// that it says something; every other exception escapes and so aborts the fuzzer on this input.
template <class F>
void expect_result_or_input_error(F&& f);

}  // namespace femdem::fuzz

#include "engine/errors.hpp"

template <class F>
void femdem::fuzz::expect_result_or_input_error(F&& f) {
  try {
    f();
  } catch (const femdem::InputError& e) {
    if (std::string(e.what()).empty()) __builtin_trap();
  }
}
