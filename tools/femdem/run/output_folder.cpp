// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "engine/errors.hpp"

namespace femdem {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLockFile = ".femdem.lock";

// What an earlier run left in `dir`, in words ("" when nothing).
std::string earlier_run(const fs::path& dir) {
  std::error_code ec;
  const bool summary = fs::exists(dir / "summary.json", ec);
  const bool checkpoint = fs::exists(dir / "checkpoint.h5", ec);
  const bool outputs = fs::exists(dir / "results.h5", ec) || fs::exists(dir / "history.csv", ec) ||
                       fs::exists(dir / "run.log", ec);
  if (!summary && !checkpoint && !outputs) return "";
  if (summary) {
    std::string status;
    try {
      std::ifstream in(dir / "summary.json");
      status = nlohmann::json::parse(in).value("status", "");
    } catch (const std::exception&) {
    }
    if (status == "completed") return "the outputs of a run that completed";
    if (status == "interrupted") return "the outputs of a run that was interrupted";
    if (status == "unstable") return "the outputs of a run that diverged";
    return "the outputs of an earlier run";
  }
  return checkpoint ? "the outputs of a run that was killed (a checkpoint, no summary)"
                    : "the outputs of a run that was killed or is still running (no summary)";
}

}  // namespace

void check_new_run_folder(const std::string& dir, bool force) {
  if (dir.empty())
    throw InputError(
        "the output folder's name is empty (name a folder, or drop --out for "
        "out/<scene stem>/)",
        "", 0, 0, "--out");
  if (force) return;
  const std::string what = earlier_run(dir);
  if (what.empty()) return;
  throw InputError("the output folder '" + dir + "' holds " + what +
                       ": --force replaces them, `femdem resume " + dir +
                       "` continues that run, or choose another --out",
                   "", 0, 0, "--out");
}

OutputFolderLock::OutputFolderLock(const fs::path& dir, const std::string& command_line) {
  fs::create_directories(dir);
  const fs::path lock = dir / kLockFile;
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw std::runtime_error("cannot create '" + lock.string() + "': " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    std::string owner(512, '\0');
    const ssize_t n = ::pread(fd_, owner.data(), owner.size() - 1, 0);
    owner.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    while (!owner.empty() && (owner.back() == '\n' || owner.back() == '\0')) owner.pop_back();
    ::close(fd_);
    fd_ = -1;
    throw InputError("the output folder '" + dir.string() + "' is in use by another femdem (" +
                         (owner.empty() ? std::string("pid unknown") : owner) +
                         "): wait for it to finish, or choose another --out",
                     "", 0, 0, "--out");
  }
  const std::string me = "pid " + std::to_string(::getpid()) + ": " + command_line + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
    // the lock holds without the note; only the message of a refused second run is poorer
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock (so does the process ending)
}

}  // namespace femdem
