// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// history.csv: one row per history sample, header on the first line, every value written with
// the shortest representation that reads back to the same double (std::to_chars).
//
// Crash behaviour: rows are collected in memory as complete lines and handed to the kernel when
// `flush_interval_s` of wall time has passed since the last flush (or the buffer exceeds 1 MiB,
// or flush()/destruction), in write() calls that end on a line break and do not cross a page
// boundary of the file. Linux lets SIGKILL interrupt a write() only between pages, so a run
// killed at any moment leaves a file of complete lines, losing at most the last
// `flush_interval_s` of rows. (Only a single row longer than a page, about 200 columns, can be
// cut; a reader that drops a last line without '\n' is safe in every case.)
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace femdem {

class HistoryWriter {
 public:
  // Creates (truncates) `path` and writes the header line immediately. Column names containing
  // a comma, quote or line break are quoted as in RFC 4180. flush_interval_s <= 0 flushes every
  // row. Throws std::runtime_error if the file cannot be created.
  HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                double flush_interval_s = 0.5);
  // Continues the history of an interrupted run (femdem resume): the file is cut back to the
  // first `bytes` (the header and the `rows` rows written before the checkpoint) and rows are
  // appended after them. Throws std::runtime_error naming the file when it is missing, shorter
  // than that, or starts with another header.
  struct ContinueAt {
    std::uint64_t bytes = 0;
    std::int64_t rows = 0;
  };
  HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns, ContinueAt at,
                double flush_interval_s = 0.5);
  // What that constructor checks, without changing the file (std::runtime_error naming it).
  static void check_continuable(const std::filesystem::path& path,
                                const std::vector<std::string>& columns, ContinueAt at);
  ~HistoryWriter();  // flushes and closes; never throws
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  // One row; values.size() must equal the number of columns (std::invalid_argument otherwise).
  // Non-finite values are written as nan, inf, -inf.
  void write_row(std::span<const double> values);
  // Hands all buffered rows to the kernel (one write() call). Throws std::runtime_error.
  void flush();
  // Flushes and closes; later write_row calls throw std::logic_error.
  void close();

  const std::vector<std::string>& columns() const { return columns_; }
  std::int64_t rows() const { return rows_; }
  // Bytes handed to the file so far (after flush(): the whole file), what a checkpoint records.
  std::uint64_t bytes_written() const { return file_size_; }

 private:
  // The members both public constructors set (the file is theirs to open).
  HistoryWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                double flush_interval_s, int);
  static std::string header_line(const std::vector<std::string>& columns);
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::chrono::steady_clock::duration flush_interval_;
  std::chrono::steady_clock::time_point last_flush_;
  std::string buffer_;
  std::int64_t rows_ = 0;
  std::uint64_t file_size_ = 0;  // bytes handed to the kernel so far
  int fd_ = -1;
};

}  // namespace femdem
