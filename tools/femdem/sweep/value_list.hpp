// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// --vary value lists of `femdem sweep`: values separated by the commas outside brackets, braces,
// parentheses and quotes, and the ranges START:STOP:STEP, linspace(A,B,N), logspace(A,B,N)
// (docs/OUTPUTS.md, "Parameter sweeps").
#include <string>
#include <string_view>
#include <vector>

namespace femdem {

// A --vary value list split into values. Values are separated by commas outside brackets,
// braces, parentheses and quotes, so arrays need no escaping: "[0,0,-5],[0,0,-10]" is two
// values. An item "START:STOP:STEP" expands to START, START+STEP, ... up to STOP (inclusive);
// "linspace(A,B,N)" to N evenly spaced values from A to B; "logspace(A,B,N)" to N values from A
// to B in geometric progression. Integers stay integers when every number of a range is one.
// `key` is only used in error messages. Throws InputError.
std::vector<std::string> split_value_list(const std::string& list, const std::string& key);

namespace sweep {
std::string trim(std::string_view s);  // without leading and trailing white space
}  // namespace sweep

}  // namespace femdem
