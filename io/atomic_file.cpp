// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace femdem {

namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int err) {
  throw std::runtime_error(what + " '" + path.string() + "': " + std::strerror(err));
}

// Writes all of `data` to `fd`, retrying short writes and EINTR.
bool write_all(int fd, std::string_view data, int& err) {
  const char* p = data.data();
  std::size_t left = data.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

// Same folder (rename is only atomic within one file system), hidden, unique per process.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  std::filesystem::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  std::string tmp_name = ".";
  tmp_name += path.filename().string();
  tmp_name += ".tmp.";
  tmp_name += std::to_string(::getpid());
  return folder / tmp_name;
}

// Renames tmp over path (removing tmp on failure); with durable, then fsyncs the folder.
void rename_into_place(const std::filesystem::path& tmp, const std::filesystem::path& path,
                       bool durable) {
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot rename '" + tmp.string() + "' to", path, err);
  }
  if (durable) {
    // Make the rename itself durable. Failure here is not an error for the content.
    std::filesystem::path folder = path.parent_path();
    if (folder.empty()) folder = ".";
    const int dfd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      ::fsync(dfd);
      ::close(dfd);
    }
  }
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool durable) {
  const std::filesystem::path tmp = temporary_beside(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create", tmp, errno);
  int err = 0;
  bool ok = write_all(fd, content, err);
  if (ok && durable && ::fsync(fd) != 0) {
    err = errno;
    ok = false;
  }
  if (::close(fd) != 0 && ok) {
    err = errno;
    ok = false;
  }
  if (!ok) {
    ::unlink(tmp.c_str());
    fail("cannot write", tmp, err);
  }
  rename_into_place(tmp, path, durable);
}

void replace_file_atomically(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path& tmp)>& write,
                             bool durable) {
  const std::filesystem::path tmp = temporary_beside(path);
  try {
    write(tmp);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  if (durable) {
    const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    const int err = fd < 0 ? errno : (::fsync(fd) != 0 ? errno : 0);
    if (fd >= 0) ::close(fd);
    if (err != 0) {
      ::unlink(tmp.c_str());
      fail("cannot write", tmp, err);
    }
  }
  rename_into_place(tmp, path, durable);
}

}  // namespace femdem
