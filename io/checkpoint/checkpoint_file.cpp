// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/checkpoint/checkpoint_file.hpp"

#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/hdf5_handle.hpp"

namespace femdem {
namespace {

constexpr const char* kKind = "femdem checkpoint";

// The file type of each archive type (little-endian, as results.h5) and the memory type.
hid_t file_type(StateArchive::Type t) {
  using T = StateArchive::Type;
  switch (t) {
    case T::f64:
      return H5T_IEEE_F64LE;
    case T::i64:
      return H5T_STD_I64LE;
    case T::u64:
      return H5T_STD_U64LE;
    case T::i32:
      return H5T_STD_I32LE;
    case T::u32:
      return H5T_STD_U32LE;
    case T::u8:
    case T::record:
      return H5T_STD_U8LE;
  }
  return H5T_STD_U8LE;
}
hid_t memory_type(StateArchive::Type t) {
  using T = StateArchive::Type;
  switch (t) {
    case T::f64:
      return H5T_NATIVE_DOUBLE;
    case T::i64:
      return H5T_NATIVE_INT64;
    case T::u64:
      return H5T_NATIVE_UINT64;
    case T::i32:
      return H5T_NATIVE_INT32;
    case T::u32:
      return H5T_NATIVE_UINT32;
    case T::u8:
    case T::record:
      return H5T_NATIVE_UINT8;
  }
  return H5T_NATIVE_UINT8;
}
const char* type_name(StateArchive::Type t) {
  using T = StateArchive::Type;
  switch (t) {
    case T::f64:
      return "float64";
    case T::i64:
      return "int64";
    case T::u64:
      return "uint64";
    case T::i32:
      return "int32";
    case T::u32:
      return "uint32";
    case T::u8:
      return "uint8";
    case T::record:
      return "record";
  }
  return "?";
}

void write_string_attribute(hid_t obj, const char* name, const std::string& value,
                            const std::string& file) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.empty() ? 1 : value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  if (!attr.valid() || H5Awrite(attr.get(), type.get(), v.data()) < 0)
    throw std::runtime_error("cannot write attribute '" + std::string(name) + "' of '" + file +
                             "'");
}

template <class T>
void write_number_attribute(hid_t obj, const char* name, hid_t file_t, hid_t mem_t, T value,
                            const std::string& file) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, name, file_t, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), mem_t, &value) < 0)
    throw std::runtime_error("cannot write attribute '" + std::string(name) + "' of '" + file +
                             "'");
}

template <class T>
bool read_number_attribute(hid_t obj, const char* name, hid_t mem_t, T& out) {
  if (H5Aexists(obj, name) <= 0) return false;
  Handle attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
  return attr.valid() && H5Aread(attr.get(), mem_t, &out) >= 0;
}

class WritingArchive final : public StateArchive {
 public:
  WritingArchive(hid_t file, std::string name) : file_(file), name_(std::move(name)) {
    lcpl_ = Handle(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
    H5Pset_create_intermediate_group(lcpl_.get(), 1);
  }
  bool saving() const override { return true; }

 protected:
  void write(const std::string& path, Type type, std::size_t item_bytes, std::size_t count,
             const void* data) override {
    const std::size_t values = type == Type::record ? count * item_bytes : count;
    const hsize_t dims[1] = {static_cast<hsize_t>(values)};
    Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    Handle dset(H5Dcreate2(file_, path.c_str(), file_type(type), space.get(), lcpl_.get(),
                           H5P_DEFAULT, H5P_DEFAULT),
                H5Dclose);
    if (!dset.valid()) fail(path);
    if (values > 0 &&
        H5Dwrite(dset.get(), memory_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      fail(path);
    if (type == Type::record)
      write_number_attribute(dset.get(), "item_bytes", H5T_STD_U64LE, H5T_NATIVE_UINT64,
                             static_cast<std::uint64_t>(item_bytes), name_);
  }
  std::size_t stored_count(const std::string&, Type, std::size_t) override { return 0; }
  void read(const std::string&, void*) override {}

 private:
  [[noreturn]] void fail(const std::string& path) const {
    throw std::runtime_error("cannot write '" + path + "' into '" + name_ + "'");
  }
  hid_t file_;
  std::string name_;
  Handle lcpl_;
};

class ReadingArchive final : public StateArchive {
 public:
  ReadingArchive(hid_t file, std::string name) : file_(file), name_(std::move(name)) {}
  bool saving() const override { return false; }

 protected:
  void write(const std::string&, Type, std::size_t, std::size_t, const void*) override {}
  std::size_t stored_count(const std::string& path, Type type, std::size_t item_bytes) override {
    if (H5Lexists(file_, path.c_str(), H5P_DEFAULT) <= 0) fail(path, "is missing");
    dset_ = Handle(H5Dopen2(file_, path.c_str(), H5P_DEFAULT), H5Dclose);
    if (!dset_.valid()) fail(path, "is not readable");
    type_ = type;
    Handle ftype(H5Dget_type(dset_.get()), H5Tclose);
    if (H5Tequal(ftype.get(), file_type(type)) <= 0)
      fail(path, std::string("is not of type ") + type_name(type));
    Handle space(H5Dget_space(dset_.get()), H5Sclose);
    if (H5Sget_simple_extent_ndims(space.get()) != 1) fail(path, "is not one-dimensional");
    const auto values = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get()));
    values_ = values;
    if (type != Type::record) return values;
    std::uint64_t stored_bytes = 0;
    if (!read_number_attribute(dset_.get(), "item_bytes", H5T_NATIVE_UINT64, stored_bytes) ||
        stored_bytes != item_bytes || values % item_bytes != 0)
      fail(path, "holds records of " + std::to_string(stored_bytes) +
                     " bytes where this femdem has " + std::to_string(item_bytes));
    return values / item_bytes;
  }
  void read(const std::string& path, void* data) override {
    if (values_ > 0 &&
        H5Dread(dset_.get(), memory_type(type_), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      fail(path, "cannot be read (the file is damaged)");
    dset_.reset();
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw CheckpointError("checkpoint '" + name_ + "': '" + path + "' " + what);
  }
  hid_t file_;
  std::string name_;
  Handle dset_;
  Type type_ = Type::u8;
  std::size_t values_ = 0;
};

// Opens a checkpoint for reading and checks what it is (CheckpointError otherwise).
Handle open_checkpoint(const std::filesystem::path& path, CheckpointInfo& info) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw CheckpointError("no checkpoint '" + name + "'");
  if (H5Fis_hdf5(name.c_str()) <= 0)
    throw CheckpointError("checkpoint '" + name +
                          "' is not a complete HDF5 file (truncated or damaged)");
  Handle file(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid())
    throw CheckpointError("checkpoint '" + name + "' cannot be opened (truncated or damaged)");
  std::string kind;
  if (!read_string_attribute(file.get(), "kind", kind) || kind != kKind)
    throw CheckpointError("'" + name + "' is not a femdem checkpoint");
  if (!read_number_attribute(file.get(), "format", H5T_NATIVE_INT, info.format))
    throw CheckpointError("checkpoint '" + name + "' has no format version");
  if (info.format != kCheckpointFormat)
    throw CheckpointError("checkpoint '" + name + "' has format " + std::to_string(info.format) +
                          ", this femdem reads format " + std::to_string(kCheckpointFormat) +
                          " (it was written by another version of femdem)");
  if (!read_string_attribute(file.get(), "femdem_version", info.femdem_version) ||
      !read_string_attribute(file.get(), "scene_digest", info.scene_digest) ||
      !read_number_attribute(file.get(), "time", H5T_NATIVE_DOUBLE, info.time) ||
      !read_number_attribute(file.get(), "step", H5T_NATIVE_INT64, info.step))
    throw CheckpointError("checkpoint '" + name + "' lacks its identity attributes");
  return file;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const CheckpointInfo& info,
                      const std::function<void(StateArchive&)>& fill) {
  replace_file_atomically(path, [&](const std::filesystem::path& tmp) {
    const QuietErrors quiet;
    const std::string name = tmp.string();
    Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST);
    Handle file(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
    if (!file.valid()) throw std::runtime_error("cannot create '" + name + "'");
    write_string_attribute(file.get(), "kind", kKind, name);
    write_number_attribute(file.get(), "format", H5T_STD_I32LE, H5T_NATIVE_INT, info.format, name);
    write_string_attribute(file.get(), "femdem_version", info.femdem_version, name);
    write_string_attribute(file.get(), "scene_digest", info.scene_digest, name);
    write_number_attribute(file.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, info.time, name);
    write_number_attribute(file.get(), "step", H5T_STD_I64LE, H5T_NATIVE_INT64, info.step, name);
    WritingArchive archive(file.get(), path.string());
    fill(archive);
    if (H5Fflush(file.get(), H5F_SCOPE_LOCAL) < 0 || file.reset() < 0)
      throw std::runtime_error("cannot write '" + name + "'");
  });
}

CheckpointInfo read_checkpoint_info(const std::filesystem::path& path) {
  const QuietErrors quiet;
  CheckpointInfo info;
  open_checkpoint(path, info);
  return info;
}

void read_checkpoint(const std::filesystem::path& path,
                     const std::function<void(StateArchive&)>& load) {
  const QuietErrors quiet;
  CheckpointInfo info;
  Handle file = open_checkpoint(path, info);
  ReadingArchive archive(file.get(), path.string());
  load(archive);
}

}  // namespace femdem
