// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/results/history_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace femdem {

namespace {

constexpr std::size_t kMaxBuffer = std::size_t{1} << 20;

std::string csv_field(const std::string& name) {
  if (name.find_first_of(",\"\r\n") == std::string::npos) return name;
  std::string quoted = "\"";
  for (char c : name) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

void append_double(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip
  out.append(buf, res.ptr);
}

}  // namespace

HistoryWriter::HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                             double flush_interval_s, int)
    : path_(path),
      columns_(std::move(columns)),
      flush_interval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(flush_interval_s > 0 ? flush_interval_s : 0.0))),
      last_flush_(std::chrono::steady_clock::now()) {
  if (columns_.empty()) throw std::invalid_argument("history.csv: no columns");
}

HistoryWriter::HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                             double flush_interval_s)
    : HistoryWriter(path, std::move(columns), flush_interval_s, 0) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot create '" + path_.string() + "': " + std::strerror(errno));
  }
  buffer_ = header_line(columns_);
  flush();
}

HistoryWriter::HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                             ContinueAt at, double flush_interval_s)
    : HistoryWriter(path, std::move(columns), flush_interval_s, 0) {
  check_continuable(path_, columns_, at);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0 || ::ftruncate(fd_, static_cast<off_t>(at.bytes)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(at.bytes), SEEK_SET) < 0) {
    const int err = errno;
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("cannot cut back '" + path_.string() + "': " + std::strerror(err));
  }
  file_size_ = at.bytes;
  rows_ = at.rows;
}

void HistoryWriter::check_continuable(const std::filesystem::path& path,
                                      const std::vector<std::string>& columns, ContinueAt at) {
  if (columns.empty()) throw std::invalid_argument("history.csv: no columns");
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw std::runtime_error("cannot open '" + path.string() + "': " + std::strerror(errno));
  const off_t size = ::lseek(fd, 0, SEEK_END);
  const std::string header = header_line(columns);
  std::string head(header.size(), '\0');
  const bool header_read =
      ::pread(fd, head.data(), head.size(), 0) == static_cast<ssize_t>(head.size());
  ::close(fd);
  if (size < 0 || static_cast<std::uint64_t>(size) < at.bytes)
    throw std::runtime_error("'" + path.string() + "' holds " + std::to_string(size) +
                             " bytes, fewer than the " + std::to_string(at.bytes) +
                             " the checkpoint counts: rows were lost");
  if (!header_read || head != header)
    throw std::runtime_error("'" + path.string() +
                             "' does not start with this run's header line (other columns)");
}

std::string HistoryWriter::header_line(const std::vector<std::string>& columns) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i) line += ',';
    line += csv_field(columns[i]);
  }
  line += '\n';
  return line;
}

HistoryWriter::~HistoryWriter() {
  try {
    close();
  } catch (...) {
  }
}

void HistoryWriter::write_row(std::span<const double> values) {
  if (fd_ < 0) throw std::logic_error("history.csv: write_row after close");
  if (values.size() != columns_.size()) {
    throw std::invalid_argument("history.csv: row has " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) + " columns");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) buffer_ += ',';
    append_double(buffer_, values[i]);
  }
  buffer_ += '\n';
  ++rows_;
  if (buffer_.size() >= kMaxBuffer ||
      std::chrono::steady_clock::now() - last_flush_ >= flush_interval_) {
    flush();
  }
}

void HistoryWriter::flush() {
  last_flush_ = std::chrono::steady_clock::now();
  if (fd_ < 0 || buffer_.empty()) return;
  // Linux copies a write() into the page cache one page at a time and lets SIGKILL stop it only
  // between pages, so a write that stays inside one page of the file lands whole or not at all.
  // The buffer is therefore handed over in pieces that end on a line break and, whenever the
  // lines allow it, do not cross a page boundary of the file: a killed run leaves whole lines.
  // (A single row longer than a page cannot be protected this way; it is still written whole
  // unless the kill lands inside it.)
  static const std::size_t page = [] {
    const long s = ::sysconf(_SC_PAGESIZE);
    return s > 0 ? static_cast<std::size_t>(s) : std::size_t{4096};
  }();
  std::size_t done = 0;
  while (done < buffer_.size()) {
    const std::size_t room = page - static_cast<std::size_t>(file_size_ % page);
    const std::size_t window_end = std::min(buffer_.size(), done + room);
    std::size_t end = buffer_.rfind('\n', window_end - 1);
    if (end == std::string::npos || end < done) {
      // Not even one whole line fits before the page boundary: write the next line whole (it
      // crosses the boundary) rather than split it; the following pieces realign to pages.
      end = buffer_.find('\n', done);
      if (end == std::string::npos) end = buffer_.size() - 1;
    }
    const std::size_t chunk_end = end + 1;
    while (done < chunk_end) {
      const ssize_t n = ::write(fd_, buffer_.data() + done, chunk_end - done);
      if (n < 0) {
        if (errno == EINTR) continue;
        const int err = errno;
        buffer_.erase(0, done);
        throw std::runtime_error("cannot write '" + path_.string() + "': " + std::strerror(err));
      }
      done += static_cast<std::size_t>(n);
      file_size_ += static_cast<std::uint64_t>(n);
    }
  }
  buffer_.clear();
}

void HistoryWriter::close() {
  if (fd_ < 0) return;
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    throw std::runtime_error("cannot close '" + path_.string() + "': " + std::strerror(errno));
  }
}

}  // namespace femdem
