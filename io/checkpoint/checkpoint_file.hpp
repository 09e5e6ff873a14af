// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// checkpoint.h5: one HDF5 file per run folder holding the whole state between two steps, as the
// parts' exchange_state functions list it (engine/state_archive.hpp), one dataset per array
// under its scoped name, and in the root's attributes what it belongs to: the format version,
// the femdem version and revision that wrote it, a digest of the resolved scene, the time and
// step.
//
// Written to a temporary file in the same folder, flushed and fsync'ed, then renamed over the
// old checkpoint (and the folder fsync'ed): a run killed at any moment, even by a power loss,
// leaves either the previous complete checkpoint or the new complete one.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "engine/state_archive.hpp"

namespace femdem {

// The layout version of checkpoint.h5: raised whenever what a part saves changes, so that a
// checkpoint of another layout is refused by name rather than loaded wrongly.
// 2: the walls' reach list keyed by global boundary-node index (near_key, reach_surface).
inline constexpr int kCheckpointFormat = 2;

struct CheckpointInfo {
  int format = kCheckpointFormat;
  std::string femdem_version;  // e.g. "0.9.0 (e7bc820)"
  std::string scene_digest;    // of the resolved scene (io/scene/resolved_scene.hpp)
  double time = 0.0;           // s, simulated
  std::int64_t step = 0;
};

// Writes `path` atomically: `fill` saves the state into the archive it is given. Throws
// std::runtime_error naming the file on an I/O error (the previous checkpoint then stays).
void write_checkpoint(const std::filesystem::path& path, const CheckpointInfo& info,
                      const std::function<void(StateArchive&)>& fill);

// The root attributes of a checkpoint. Throws CheckpointError naming the file when it is
// missing, not a complete HDF5 file, or not a femdem checkpoint of this format.
CheckpointInfo read_checkpoint_info(const std::filesystem::path& path);

// Loads a checkpoint: `load` reads the state from the archive it is given. Throws
// CheckpointError naming the file and the array that is missing or does not fit.
void read_checkpoint(const std::filesystem::path& path,
                     const std::function<void(StateArchive&)>& load);

}  // namespace femdem
