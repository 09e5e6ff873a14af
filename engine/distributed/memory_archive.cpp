// SPDX-License-Identifier: GPL-3.0-or-later
#include "engine/distributed/memory_archive.hpp"

#include <cstring>

namespace femdem {
namespace {

// packed layout, per entry: path length, path bytes, type, item bytes, count, data
template <class T>
void put(std::vector<std::byte>& out, const T& x) {
  const auto* p = reinterpret_cast<const std::byte*>(&x);
  out.insert(out.end(), p, p + sizeof(T));
}

class Reader {
 public:
  explicit Reader(std::span<const std::byte> b) : b_(b) {}
  bool done() const { return at_ == b_.size(); }
  template <class T>
  T get() {
    T x;
    std::memcpy(&x, take(sizeof(T)), sizeof(T));
    return x;
  }
  const std::byte* take(std::size_t n) {
    if (n > b_.size() - at_) throw CheckpointError("a packed state archive is cut short");
    const std::byte* p = b_.data() + at_;
    at_ += n;
    return p;
  }

 private:
  std::span<const std::byte> b_;
  std::size_t at_ = 0;
};

}  // namespace

MemoryArchive::MemoryArchive(std::span<const std::byte> packed) : saving_(false) {
  Reader r(packed);
  while (!r.done()) {
    Entry e;
    const auto len = r.get<std::uint64_t>();
    const std::byte* p = r.take(len);
    e.path.assign(reinterpret_cast<const char*>(p), len);
    e.type = static_cast<Type>(r.get<std::uint8_t>());
    e.item_bytes = r.get<std::uint64_t>();
    e.count = r.get<std::uint64_t>();
    if (e.item_bytes != 0 && e.count > packed.size() / e.item_bytes)
      throw CheckpointError("a packed state archive is cut short");
    const std::byte* d = r.take(e.count * e.item_bytes);
    e.data.assign(d, d + e.count * e.item_bytes);
    entries_.push_back(std::move(e));
  }
  index();
}

void MemoryArchive::index() {
  by_path_.clear();
  for (std::size_t i = 0; i < entries_.size(); ++i) by_path_[entries_[i].path] = i;
}

MemoryArchive::Entry& MemoryArchive::add(Entry e) {
  entries_.push_back(std::move(e));
  by_path_[entries_.back().path] = entries_.size() - 1;
  return entries_.back();
}

const MemoryArchive::Entry* MemoryArchive::find(const std::string& path) const {
  const auto it = by_path_.find(path);
  return it == by_path_.end() ? nullptr : &entries_[it->second];
}

MemoryArchive::Entry* MemoryArchive::find(const std::string& path) {
  const auto it = by_path_.find(path);
  return it == by_path_.end() ? nullptr : &entries_[it->second];
}

std::vector<std::byte> MemoryArchive::pack() const {
  std::size_t bytes = 0;
  for (const Entry& e : entries_) bytes += e.path.size() + e.data.size() + 32;
  std::vector<std::byte> out;
  out.reserve(bytes);
  for (const Entry& e : entries_) {
    put(out, static_cast<std::uint64_t>(e.path.size()));
    const auto* p = reinterpret_cast<const std::byte*>(e.path.data());
    out.insert(out.end(), p, p + e.path.size());
    put(out, static_cast<std::uint8_t>(e.type));
    put(out, static_cast<std::uint64_t>(e.item_bytes));
    put(out, static_cast<std::uint64_t>(e.count));
    out.insert(out.end(), e.data.begin(), e.data.end());
  }
  return out;
}

void MemoryArchive::write(const std::string& path, Type type, std::size_t item_bytes,
                          std::size_t count, const void* data) {
  Entry e{path, type, item_bytes, count, {}};
  const auto* p = static_cast<const std::byte*>(data);
  e.data.assign(p, p + count * item_bytes);
  if (Entry* old = find(path)) {
    *old = std::move(e);
    return;
  }
  by_path_[path] = entries_.size();
  entries_.push_back(std::move(e));
}

std::size_t MemoryArchive::stored_count(const std::string& path, Type type,
                                        std::size_t item_bytes) {
  reading_ = find(path);
  if (reading_ == nullptr) throw CheckpointError("state '" + path + "' is missing");
  if (reading_->type != type || reading_->item_bytes != item_bytes)
    throw CheckpointError("state '" + path + "' is of another type");
  return reading_->count;
}

void MemoryArchive::read(const std::string&, void* data) {
  if (!reading_->data.empty()) std::memcpy(data, reading_->data.data(), reading_->data.size());
  reading_ = nullptr;
}

}  // namespace femdem
