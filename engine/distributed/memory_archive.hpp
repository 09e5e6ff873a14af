// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A state archive in memory (engine/state_archive.hpp): what a distributed run passes between
// its ranks to gather the whole model's state on rank 0 (for outputs and checkpoints) and to
// hand a checkpoint's state to every rank (engine/distributed/state_transfer.hpp). It keeps the
// arrays in the order they were saved, can be edited array by array, loaded back, and packed
// into bytes for a message.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/state_archive.hpp"

namespace femdem {

class MemoryArchive final : public StateArchive {
 public:
  struct Entry {
    std::string path;
    Type type = Type::u8;
    std::size_t item_bytes = 1;
    std::size_t count = 0;
    std::vector<std::byte> data;  // count * item_bytes
  };

  // Saves until load() is called; with `keep`, only the arrays it is true for (the others are
  // skipped, saving and loading).
  MemoryArchive() = default;
  explicit MemoryArchive(std::function<bool(const std::string&)> keep) : keep_(std::move(keep)) {}
  // From pack()'s bytes (loading). Throws CheckpointError on bytes that are not a packed archive.
  explicit MemoryArchive(std::span<const std::byte> packed);

  bool saving() const override { return saving_; }
  // From now on the archive gives back what it holds.
  void load() { saving_ = false; }

  const std::vector<Entry>& entries() const { return entries_; }
  std::vector<Entry>& entries() { return entries_; }
  // Appends an array no Simulation saves (a gather's figures of its own), found by its path.
  Entry& add(Entry e);
  // The entry saved under `path`, or null.
  const Entry* find(const std::string& path) const;
  Entry* find(const std::string& path);

  std::vector<std::byte> pack() const;

 protected:
  bool skips(const std::string& path) const override { return keep_ && !keep_(path); }
  void write(const std::string& path, Type type, std::size_t item_bytes, std::size_t count,
             const void* data) override;
  std::size_t stored_count(const std::string& path, Type type, std::size_t item_bytes) override;
  void read(const std::string& path, void* data) override;

 private:
  void index();
  bool saving_ = true;
  std::vector<Entry> entries_;
  std::unordered_map<std::string, std::size_t> by_path_;
  const Entry* reading_ = nullptr;
  std::function<bool(const std::string&)> keep_;
};

}  // namespace femdem
