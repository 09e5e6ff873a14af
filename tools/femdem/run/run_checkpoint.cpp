// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/run_checkpoint.hpp"

#include "io/checkpoint/checkpoint_file.hpp"

namespace femdem {

void exchange_origin(StateArchive& a, RunOrigin& origin) {
  const StateArchive::Scope scope(a, "origin");
  a.text("scene_path", origin.scene_path);
  a.text("resolved_scene", origin.resolved_toml);
  // the overrides one after another, each ended by a NUL (a value may hold any other character)
  std::string joined;
  for (const std::string& o : origin.overrides) joined += o + '\0';
  a.text("overrides", joined);
  if (a.saving()) return;
  origin.overrides.clear();
  std::size_t start = 0;
  for (std::size_t end; (end = joined.find('\0', start)) != std::string::npos; start = end + 1)
    origin.overrides.push_back(joined.substr(start, end - start));
}

RunOrigin read_run_origin(const std::filesystem::path& checkpoint) {
  RunOrigin origin;
  read_checkpoint(checkpoint, [&](StateArchive& a) {
    const StateArchive::Scope scope(a, "run");
    exchange_origin(a, origin);
  });
  return origin;
}

}  // namespace femdem
