// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One HDF5 identifier owned (closed with its own H5?close on destruction), HDF5's error printing
// held off, and a string attribute read, for the files io/ writes and reads: results.h5 and
// checkpoint.h5. Only io/**/*.cpp include it (HDF5 stays out of
// every other header).
#include <hdf5.h>

#include <string>
#include <utility>

namespace femdem {

// Owns one HDF5 identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      closer_ = o.closer_;
    }
    return *this;
  }
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  // Returns the close status (0 if nothing to close).
  herr_t reset() {
    herr_t status = 0;
    if (id_ >= 0 && closer_) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// HDF5's own error printing off while femdem reports the errors itself.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// A fixed-length string attribute of obj into out; false when absent or of another kind.
inline bool read_string_attribute(hid_t obj, const char* name, std::string& out) {
  if (H5Aexists(obj, name) <= 0) return false;
  Handle attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()))
    return false;
  std::string s(H5Tget_size(type.get()), '\0');
  // read as stored (ASCII or UTF-8; a memory type of the other character set would not convert)
  if (H5Aread(attr.get(), type.get(), s.data()) < 0) return false;
  s.resize(s.find('\0') == std::string::npos ? s.size() : s.find('\0'));
  out = s;
  return true;
}

}  // namespace femdem
