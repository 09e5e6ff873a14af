// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `femdem pack OUT ...`: generates a particle packing (io/packing), writes it for [[packings]]
// and prints what it got.
#include <string>

#include "io/packing/packing.hpp"

namespace femdem {

// Returns the exit code; throws InputError naming the command-line option (--count, ...).
int pack_command(const PackingParams& params, const std::string& out, bool quiet);

}  // namespace femdem
