// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a checkpoint is made of, seen from the code that owns the state: named arrays and values,
// saved or loaded by one and the same function (`exchange_state(StateArchive&)` of each part), so
// that what is written and what is read back cannot drift apart. A part lists everything that
// changes the bits of the steps after it (not what the next step recomputes before reading).
//
// The archive itself (an HDF5 file, io/checkpoint/checkpoint_file.hpp; memory in the tests)
// implements the three protected calls. Loading throws CheckpointError naming the array when it
// is missing, of another type or, for arrays the model fixes, of another size.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

// A checkpoint that does not fit what it is loaded into (missing, truncated, foreign).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  // How an array's items are stored: numbers as themselves (a reader such as h5dump shows them),
  // other plain structs as records of bytes whose size is checked on loading.
  enum class Type : std::uint8_t { f64, i64, u64, i32, u32, u8, record };
  // Whether an array's length is fixed by the model (checked on loading) or is part of the
  // state (a candidate list: loaded at whatever length it was saved).
  enum class Length : std::uint8_t { fixed, variable };

  virtual ~StateArchive() = default;
  virtual bool saving() const = 0;

  // The names below are prefixed with the open scopes' names ("body_contact/pairs").
  class Scope {
   public:
    Scope(StateArchive& a, std::string_view name) : a_(a), size_(a.prefix_.size()) {
      a_.prefix_.append(name).push_back('/');
    }
    ~Scope() { a_.prefix_.resize(size_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StateArchive& a_;
    std::size_t size_;
  };

  template <class T>
  void array(std::string_view name, std::vector<T>& v, Length length = Length::fixed) {
    static_assert(std::is_trivially_copyable_v<T>, "an archived item must be plain data");
    const std::string path = prefix_ + std::string(name);
    if (skips(path)) return;
    if (saving()) {
      write(path, type_of<T>(), sizeof(T), v.size(), v.data());
      return;
    }
    const std::size_t n = stored_count(path, type_of<T>(), sizeof(T));
    if (length == Length::fixed && n != v.size())
      throw CheckpointError("'" + path + "' holds " + std::to_string(n) +
                            " items where the scene's model has " + std::to_string(v.size()));
    v.resize(n);
    read(path, v.data());
  }
  // Positions and the like: three doubles each.
  void array(std::string_view name, std::vector<Vec3>& v, Length length = Length::fixed) {
    if (skips(prefix_ + std::string(name))) return;
    std::vector<double> flat;
    if (saving()) {
      flat.resize(3 * v.size());
      for (std::size_t i = 0; i < v.size(); ++i)
        for (int k = 0; k < 3; ++k) flat[3 * i + k] = v[i][k];
    } else if (length == Length::fixed) {
      flat.resize(3 * v.size());
    }
    array(name, flat, length);
    if (saving()) return;
    v.resize(flat.size() / 3);
    for (std::size_t i = 0; i < v.size(); ++i)
      v[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  }
  template <class T>
  void value(std::string_view name, T& x) {
    std::vector<T> one{x};
    array(name, one);
    x = one[0];
  }
  void value(std::string_view name, bool& x) {
    std::uint8_t b = x ? 1 : 0;
    value(name, b);
    x = b != 0;
  }
  // Text (a path, a scene), stored as its bytes.
  void text(std::string_view name, std::string& s) {
    std::vector<std::uint8_t> bytes(s.begin(), s.end());
    array(name, bytes, Length::variable);
    s.assign(bytes.begin(), bytes.end());
  }
  void value(std::string_view name, Vec3& x) {
    std::vector<double> three{x[0], x[1], x[2]};
    array(name, three);
    x = Vec3(three[0], three[1], three[2]);
  }

 protected:
  // An archive of part of the state (a distributed run's gather of what the outputs read) skips
  // the other arrays: neither saved nor loaded, they keep their values.
  virtual bool skips(const std::string& /*path*/) const { return false; }
  // Saving: `count` items of `item_bytes` each.
  virtual void write(const std::string& path, Type type, std::size_t item_bytes, std::size_t count,
                     const void* data) = 0;
  // Loading: how many items are stored under `path` (CheckpointError when there is no such
  // array, or it holds another type or item size) ...
  virtual std::size_t stored_count(const std::string& path, Type type, std::size_t item_bytes) = 0;
  // ... and those items, into `data`.
  virtual void read(const std::string& path, void* data) = 0;

 private:
  template <class T>
  static constexpr Type type_of() {
    if constexpr (std::is_same_v<T, double>)
      return Type::f64;
    else if constexpr (std::is_same_v<T, std::int64_t>)
      return Type::i64;
    else if constexpr (std::is_same_v<T, std::uint64_t>)
      return Type::u64;
    else if constexpr (std::is_same_v<T, std::int32_t>)
      return Type::i32;
    else if constexpr (std::is_same_v<T, std::uint32_t>)
      return Type::u32;
    else if constexpr (std::is_same_v<T, std::uint8_t>)
      return Type::u8;
    else
      return Type::record;
  }
  std::string prefix_;
};

}  // namespace femdem
