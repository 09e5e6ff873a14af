// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Below these sizes an OpenMP parallel region costs more than it saves (and on a busy machine
// waiting threads are expensive), so the element and node loops run serially.
#include <cstdint>

namespace femdem {

constexpr std::int32_t kParallelMinElements = 512;
constexpr std::int32_t kParallelMinNodes = 4096;

}  // namespace femdem
