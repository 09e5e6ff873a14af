// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Atomic replacement of small text files (results.xdmf, summary.json): the content goes to a
// temporary file in the same folder, which is then renamed over the target. A reader (or a run
// killed at any moment) sees either the old complete file or the new complete file, never a
// half-written one.
#include <filesystem>
#include <functional>
#include <string_view>

namespace femdem {

// Writes `content` to `path` atomically. With `durable`, the temporary file is fsync'ed before
// the rename and the folder after it, so the new content also survives a power loss; without,
// the replacement is still atomic for readers and against the process being killed (the data
// is in the kernel's page cache), only cheaper. Throws std::runtime_error (naming the file and
// the failing call) on any error; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool durable = true);

// The same for a file another library writes (an HDF5 checkpoint): `write` creates and closes
// the temporary file it is given; it is then fsync'ed (durable), renamed over `path` and the
// folder fsync'ed. If `write` throws, the temporary file is removed and the exception passes on.
void replace_file_atomically(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path& tmp)>& write,
                             bool durable = true);

}  // namespace femdem
