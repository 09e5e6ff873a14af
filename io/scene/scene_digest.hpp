// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What identifies a run's scene for `femdem resume`: the resolved scene without the settings a
// resume may change (they do not alter the past: the end time, the output, history and
// checkpoint intervals, the rest criteria, the threads), and its digest. A checkpoint carries
// the digest; a resume whose scene (file, overrides, meshes) resolves to another digest is
// refused, naming the first line that differs.
#include <string>
#include <vector>

namespace femdem {

// The dotted keys a resume may set ("simulation.end_time", ...).
const std::vector<std::string>& resumable_keys();

// The resolved scene text (io/scene/resolved_scene.hpp) without the resumable keys, as TOML.
// Throws std::invalid_argument when the text is not TOML.
std::string scene_identity_text(const std::string& resolved_toml);

// 16 hexadecimal digits: the 64-bit FNV-1a hash of scene_identity_text (a check that the scene
// is the same, not a protection against forgery).
std::string scene_digest(const std::string& resolved_toml);

// "KEY=VALUE" overrides that set each resumable key to its value in the resolved scene (those
// the scene has), in the order of resumable_keys(): what a resume starts from before its own
// --set.
std::vector<std::string> resumable_settings(const std::string& resolved_toml);

// The first line of a that differs from b ("" when they are equal), for messages.
std::string first_differing_line(const std::string& a, const std::string& b);

}  // namespace femdem
