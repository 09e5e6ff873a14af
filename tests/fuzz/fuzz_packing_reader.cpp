// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz target: the packing-file reader (read_packing: the CSV of particle centres, diameters and
// orientations with its commented header, docs/OUTPUTS.md "Packing files").
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "io/packing/packing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = femdem::fuzz::write_input("packing.csv", data, size);
  femdem::fuzz::expect_result_or_input_error([&] { femdem::read_packing(path); });
  return 0;
}
