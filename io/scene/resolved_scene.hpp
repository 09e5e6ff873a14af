// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Writing TOML for the scene reader: the resolved scene (SceneFile::resolved_toml) and string
// literals (also used to read a bare --set value as a string).
#include <toml++/toml.h>
#include <string>
#include <string_view>

namespace femdem::scene {

// A TOML basic string literal holding s.
std::string toml_string_literal(std::string_view s);

// The resolved scene as TOML text: sections in the order of the documentation, "name" first in
// each entry, sub-tables inline, numbers in shortest round-trip form (so it reads back exactly).
std::string resolved_scene_text(const toml::table& root);

}  // namespace femdem::scene
