// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/results/results_writer.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "femdem_version.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5_handle.hpp"

namespace femdem {

namespace {

constexpr const char* kH5Name = "results.h5";
constexpr const char* kXdmfName = "results.xdmf";
constexpr const char* kWallsXdmfName = "walls.xdmf";
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;  // target size of one frame chunk
constexpr hsize_t kTimeChunk = 1024;

std::string fmt_double(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// One extendible per-frame dataset [frames, rows(, comps)].
struct FrameDataset {
  const char* name;
  bool node_centred;
  hsize_t rows;
  hsize_t comps;  // 1: scalar, stored as rank 2
  const char* xdmf_type;
  const char* unit;
  Handle dset;
  // where write_frame takes the values from; a symmetric tensor comes as 6 (xx yy zz xy yz xz)
  // and is stored as the full row-major 3x3
  std::span<const double> FrameFields::*source = nullptr;
  std::vector<double> full = {};  // the 3x3 rows of a symmetric tensor, reused every frame
  int rank() const { return comps > 1 ? 3 : 2; }
  hsize_t given_comps() const { return comps == 9 ? 6 : comps; }
};

}  // namespace

struct ResultsWriter::Impl {
  std::filesystem::path folder, h5_path, xdmf_path, walls_xdmf_path;
  ResultsOptions options;
  hsize_t nodes = 0, elements = 0;
  Handle file;
  Handle time_dset;
  std::vector<FrameDataset> fields;  // displacement, velocity, stress, von_mises, pressure, eps
  std::vector<ResultsWall> walls;
  std::vector<FrameDataset> wall_fields;  // /walls/displacement, /walls/force (with walls)
  std::string walls_frames;               // the Grid elements of walls.xdmf so far
  std::int64_t frames = 0;
  std::int64_t views = 0;   // frames 0..views-1 have /frame_views
  std::string xdmf_frames;  // the Grid elements of all frames written so far
  bool open = false;

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(h5_path.string() + ": HDF5 " + what + " failed");
  }
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) fail(what);
    return id;
  }
  void check_status(herr_t status, const std::string& what) const {
    if (status < 0) fail(what);
  }

  void write_attribute_int(hid_t obj, const char* name, int value) {
    Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      std::string("creating attribute ") + name),
                H5Aclose);
    check_status(H5Awrite(attr.get(), H5T_NATIVE_INT, &value),
                 std::string("writing attribute ") + name);
  }

  void write_attribute_string(hid_t obj, const char* name, const std::string& value) {
    Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
    check_status(H5Tset_size(type.get(), std::max<std::size_t>(1, value.size())), "H5Tset_size");
    check_status(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
    Handle space(check(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      std::string("creating attribute ") + name),
                H5Aclose);
    std::string padded = value.empty() ? std::string(1, '\0') : value;
    check_status(H5Awrite(attr.get(), type.get(), padded.data()),
                 std::string("writing attribute ") + name);
  }

  // A contiguous, fixed-size dataset written once.
  void write_static(hid_t group, const char* name, hid_t file_type, hid_t mem_type, int rank,
                    const hsize_t* dims, const void* data) {
    Handle space(check(H5Screate_simple(rank, dims, nullptr), "H5Screate_simple"), H5Sclose);
    Handle dset(check(H5Dcreate2(group, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                 H5P_DEFAULT),
                      std::string("creating ") + name),
                H5Dclose);
    hsize_t total = 1;
    for (int i = 0; i < rank; ++i) total *= dims[i];
    if (total > 0) {
      check_status(H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                   std::string("writing ") + name);
    }
  }

  // The files' paths, the options and the mesh's sizes (checked: std::invalid_argument).
  void set_up(const std::filesystem::path& dir, const ResultsMesh& mesh, ResultsOptions o) {
    folder = dir;
    h5_path = dir / kH5Name;
    xdmf_path = dir / kXdmfName;
    walls_xdmf_path = dir / kWallsXdmfName;
    options = std::move(o);
    set_mesh(mesh);
  }

  // Checks the mesh's sizes and remembers them (std::invalid_argument when inconsistent).
  void set_mesh(const ResultsMesh& mesh) {
    if (mesh.coordinates.size() % 3 != 0 || mesh.coordinates.empty()) {
      throw std::invalid_argument("results: coordinates must be 3 per node, at least one node");
    }
    if (mesh.connectivity.empty()) throw std::invalid_argument("results: mesh has no elements");
    nodes = mesh.coordinates.size() / 3;
    elements = mesh.connectivity.size();
    if (mesh.node_body.size() != nodes) {
      throw std::invalid_argument("results: node_body must have one entry per node");
    }
    if (mesh.element_body.size() != elements) {
      throw std::invalid_argument("results: element_body must have one entry per element");
    }
    for (const Tet10& t : mesh.connectivity) {
      for (std::int32_t id : t) {
        if (id < 0 || static_cast<hsize_t>(id) >= nodes) {
          throw std::invalid_argument("results: connectivity refers to node " + std::to_string(id) +
                                      " of " + std::to_string(nodes));
        }
      }
    }
    walls.assign(mesh.walls.begin(), mesh.walls.end());
  }

  void list_fields() {
    using F = FrameFields;
    fields.push_back({"displacement", true, nodes, 3, "Vector", "m", {}, &F::displacement});
    fields.push_back({"velocity", true, nodes, 3, "Vector", "m/s", {}, &F::velocity});
    fields.push_back({"stress", false, elements, 9, "Tensor", "Pa", {}, &F::stress});
    fields.push_back({"von_mises", false, elements, 1, "Scalar", "Pa", {}, &F::von_mises});
    fields.push_back({"pressure", false, elements, 1, "Scalar", "Pa", {}, &F::pressure});
    fields.push_back({"equivalent_plastic_strain",
                      false,
                      elements,
                      1,
                      "Scalar",
                      "1",
                      {},
                      &F::equivalent_plastic_strain});
    const FrameDataset optional[] = {
        {"log_strain", false, elements, 9, "Tensor", "1", {}, &F::log_strain},
        {"nodal_stress", true, nodes, 9, "Tensor", "Pa", {}, &F::nodal_stress},
        {"contact_force", true, nodes, 3, "Vector", "N", {}, &F::contact_force},
        {"contact_pressure", true, nodes, 1, "Scalar", "Pa", {}, &F::contact_pressure},
        {"body_velocity", true, nodes, 3, "Vector", "m/s", {}, &F::body_velocity}};
    for (const std::string& name : options.optional_fields) {
      if (name == "node_body") continue;  // /mesh/node_body, named in results.xdmf
      const auto it = std::find_if(std::begin(optional), std::end(optional),
                                   [&](const FrameDataset& d) { return d.name == name; });
      if (it == std::end(optional))
        throw std::invalid_argument("results: unknown optional field '" + name + "'");
      fields.push_back({it->name,
                        it->node_centred,
                        it->rows,
                        it->comps,
                        it->xdmf_type,
                        it->unit,
                        {},
                        it->source});
    }
    for (FrameDataset& fd : fields)
      if (fd.comps == 9) fd.full.resize(9 * fd.rows);
    if (!walls.empty()) {
      const hsize_t w = walls.size();
      wall_fields.push_back(
          {"displacement", false, w, 3, "Vector", "m", {}, &F::wall_displacement});
      wall_fields.push_back({"force", false, w, 3, "Vector", "N", {}, &F::wall_force});
    }
  }

  // Opens the Uniform grid of frame `frames - 1` (named prefix + its six-digit index) with its
  // time; returns the name.
  std::string open_grid(std::string& s, const char* prefix, double time) const {
    char name[48];
    std::snprintf(name, sizeof name, "%s%06lld", prefix, static_cast<long long>(frames - 1));
    s += "      <Grid Name=\"";
    s += name;
    s += "\" GridType=\"Uniform\">\n";
    s += "        <Time Value=\"" + fmt_double(time) + "\"/>\n";
    return name;
  }

  // walls.xdmf: the walls' quadrilaterals where they are at each frame, numbers inline.
  std::string walls_xdmf_text() const {
    std::string s = "<?xml version=\"1.0\" ?>\n<!-- femdem walls: ";
    s += std::to_string(frames);
    s += " frames, each wall a rectangle where it is at that time; open beside results.xdmf -->\n";
    s += "<Xdmf Version=\"3.0\">\n  <Domain>\n";
    s += "    <Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    s += walls_frames;
    s += "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return s;
  }

  // Appends frame `frames - 1` of walls.xdmf: displacement and force 3 per wall.
  void append_walls_frame(double time, const double* displacement, const double* force) {
    const std::size_t w = walls.size();
    const std::string nw = std::to_string(w);
    std::string& s = walls_frames;
    open_grid(s, "walls_", time);
    s += "        <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"" + nw + "\">\n";
    s += "          <DataItem Dimensions=\"" + nw +
         " 4\" NumberType=\"Int\" Precision=\"4\" Format=\"XML\">";
    for (std::size_t i = 0; i < 4 * w; ++i) {
      if (i) s += ' ';
      s += std::to_string(i);
    }
    s += "</DataItem>\n        </Topology>\n";
    s += "        <Geometry GeometryType=\"XYZ\">\n";
    s += "          <DataItem Dimensions=\"" + std::to_string(4 * w) +
         " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">";
    for (std::size_t i = 0; i < w; ++i)
      for (const Vec3& c : walls[i].patch)
        for (int k = 0; k < 3; ++k) {
          if (i || &c != &walls[i].patch[0] || k) s += ' ';
          s += fmt_double(c[k] + displacement[3 * i + k]);
        }
    s += "</DataItem>\n        </Geometry>\n";
    s += "        <Attribute Name=\"wall\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    s += "          <DataItem Dimensions=\"" + nw +
         "\" NumberType=\"Int\" Precision=\"4\" Format=\"XML\">";
    for (std::size_t i = 0; i < w; ++i) {
      if (i) s += ' ';
      s += std::to_string(i);
    }
    s += "</DataItem>\n        </Attribute>\n";
    s += "        <Attribute Name=\"force\" AttributeType=\"Vector\" Center=\"Cell\">\n";
    s += "          <DataItem Dimensions=\"" + nw +
         " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">";
    for (std::size_t i = 0; i < 3 * w; ++i) {
      if (i) s += ' ';
      s += fmt_double(force[i]);
    }
    s += "</DataItem>\n        </Attribute>\n      </Grid>\n";
  }

  // Replaces walls.xdmf (a folder of a run without walls keeps none).
  void write_walls_xdmf(bool durable) const {
    if (walls.empty()) {
      std::error_code ec;
      std::filesystem::remove(walls_xdmf_path, ec);
      return;
    }
    write_file_atomically(walls_xdmf_path, walls_xdmf_text(), durable);
  }

  hid_t frame_file_type() const {
    return options.single_precision ? H5T_IEEE_F32LE : H5T_IEEE_F64LE;
  }

  // The frames that get /frame_views: those the run expects, within the cap.
  std::int64_t wanted_views() const {
    return std::clamp<std::int64_t>(options.expected_frames, 0, kMaxFrameViews);
  }

  // Makes /frame_views/NNNNNN/<field> for frames [views, until): virtual datasets onto row
  // NNNNNN of /frames/<field> ("." = this file). Not allowed once SWMR writing has started.
  void create_views(hid_t f, std::int64_t until) {
    if (until <= views) return;
    const QuietErrors quiet;
    Handle top(H5Lexists(f, "frame_views", H5P_DEFAULT) > 0
                   ? H5Gopen2(f, "frame_views", H5P_DEFAULT)
                   : H5Gcreate2(f, "frame_views", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
               H5Gclose);
    check(top.get(), "creating /frame_views");
    for (std::int64_t k = views; k < until; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "%06lld", static_cast<long long>(k));
      Handle g(check(H5Gcreate2(top.get(), name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     std::string("creating /frame_views/") + name),
               H5Gclose);
      for (const FrameDataset& fd : fields) {
        const int rank = fd.rank();
        const hsize_t src_dims[3] = {static_cast<hsize_t>(k) + 1, fd.rows, fd.comps};
        const hsize_t src_max[3] = {H5S_UNLIMITED, fd.rows, fd.comps};
        Handle src(check(H5Screate_simple(rank, src_dims, src_max), "H5Screate_simple"), H5Sclose);
        const hsize_t start[3] = {static_cast<hsize_t>(k), 0, 0};
        const hsize_t count[3] = {1, fd.rows, fd.comps};
        check_status(H5Sselect_hyperslab(src.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
                     "H5Sselect_hyperslab");
        const hsize_t view_dims[2] = {fd.rows, fd.comps};
        Handle view(check(H5Screate_simple(rank - 1, view_dims, nullptr), "H5Screate_simple"),
                    H5Sclose);
        Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
        const std::string source = std::string("/frames/") + fd.name;
        check_status(H5Pset_virtual(dcpl.get(), view.get(), ".", source.c_str(), src.get()),
                     "H5Pset_virtual");
        Handle d(check(H5Dcreate2(g.get(), fd.name, frame_file_type(), view.get(), H5P_DEFAULT,
                                  dcpl.get(), H5P_DEFAULT),
                       std::string("creating /frame_views/") + name + "/" + fd.name),
                 H5Dclose);
      }
    }
    views = until;
  }

  // The number of frames with views in an existing file (0 in a file of format_version 1).
  std::int64_t count_views(hid_t f) const {
    const QuietErrors quiet;
    if (H5Lexists(f, "frame_views", H5P_DEFAULT) <= 0) return 0;
    Handle top(check(H5Gopen2(f, "frame_views", H5P_DEFAULT), "opening /frame_views"), H5Gclose);
    H5G_info_t info{};
    check_status(H5Gget_info(top.get(), &info), "reading /frame_views");
    return static_cast<std::int64_t>(info.nlinks);
  }

  void write_root_attributes(hid_t root) {
    write_attribute_int(root, "complete", 0);
    write_attribute_int(root, "format_version", 2);
    write_attribute_string(root, "format", "femdem-results");
    write_attribute_string(root, "femdem_version",
                           std::string(FEMDEM_VERSION) + " (git " + FEMDEM_GIT_REVISION + ")");
    write_attribute_string(root, "units", "SI: m, s, kg, Pa, N, J");
    write_attribute_string(root, "node_order",
                           "TET10, VTK quadratic tetra: corners 0 1 2 3, then the mid-edge nodes "
                           "of edges 0-1 1-2 2-0 0-3 1-3 2-3");
    if (!options.scene_digest.empty())
      write_attribute_string(root, "scene_digest", options.scene_digest);
  }

  // The frame datasets' access: no chunk cache (whole chunks go straight to the file).
  Handle frame_access() const {
    Handle dapl(check(H5Pcreate(H5P_DATASET_ACCESS), "H5Pcreate"), H5Pclose);
    check_status(H5Pset_chunk_cache(dapl.get(), H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0,
                                    H5D_CHUNK_CACHE_W0_DEFAULT),
                 "H5Pset_chunk_cache");
    return dapl;
  }

  // Resuming: the results of the run so far, cut back to their first `keep` frames (those the
  // checkpoint counts), then opened to append in SWMR mode as a new run's.
  void reopen(std::int64_t keep) {
    {
      // A killed run leaves the SWMR writer's mark in the superblock, which refuses a new
      // writer: clear it as `h5clear -s` does (the frames up to the checkpoint are whole).
      Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
      hbool_t clear = true;
      H5Pset(fapl.get(), "clear_status_flags", &clear);
      Handle file_rw(check(H5Fopen(h5_path.c_str(), H5F_ACC_RDWR, fapl.get()), "reopening"),
                     H5Fclose);
      const hid_t f = file_rw.get();
      auto extent = [&](const char* path, int rank) {
        Handle d(check(H5Dopen2(f, path, H5P_DEFAULT), std::string("opening ") + path), H5Dclose);
        Handle sp(check(H5Dget_space(d.get()), "H5Dget_space"), H5Sclose);
        hsize_t dims[3] = {0, 0, 0};
        if (H5Sget_simple_extent_ndims(sp.get()) != rank) fail(std::string("reading ") + path);
        H5Sget_simple_extent_dims(sp.get(), dims, nullptr);
        return std::array<hsize_t, 3>{dims[0], dims[1], dims[2]};
      };
      const auto c = extent("/mesh/connectivity", 2);
      const auto x = extent("/mesh/coordinates", 2);
      if (c[0] != elements || x[0] != nodes)
        throw std::runtime_error(h5_path.string() + " holds a mesh of " + std::to_string(x[0]) +
                                 " nodes and " + std::to_string(c[0]) +
                                 " elements, the scene's model " + std::to_string(nodes) + " and " +
                                 std::to_string(elements) + ": not this run's results");
      const auto t = extent("/frames/time", 1);
      if (t[0] < static_cast<hsize_t>(keep))
        throw std::runtime_error(h5_path.string() + " holds " + std::to_string(t[0]) +
                                 " frames, fewer than the " + std::to_string(keep) +
                                 " the checkpoint counts: the results were cut short");
      std::vector<double> times(t[0]);
      {
        Handle d(check(H5Dopen2(f, "/frames/time", H5P_DEFAULT), "opening /frames/time"), H5Dclose);
        if (!times.empty())
          check_status(
              H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times.data()),
              "reading /frames/time");
        const hsize_t kept[1] = {static_cast<hsize_t>(keep)};
        check_status(H5Dset_extent(d.get(), kept), "cutting /frames/time");
      }
      for (const FrameDataset& fd : fields) {
        const std::string path = std::string("/frames/") + fd.name;
        Handle d(check(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "opening " + path), H5Dclose);
        const hsize_t kept[3] = {static_cast<hsize_t>(keep), fd.rows, fd.comps};
        check_status(H5Dset_extent(d.get(), kept), "cutting " + path);
      }
      // the walls' frames up to the checkpoint, for walls.xdmf
      std::vector<std::vector<double>> wall_data;
      if (!walls.empty() && H5Lexists(f, "walls", H5P_DEFAULT) <= 0)
        throw std::runtime_error(h5_path.string() +
                                 " holds no walls, the scene has some: not this run's results");
      for (const FrameDataset& fd : wall_fields) {
        const std::string path = std::string("/walls/") + fd.name;
        Handle d(check(H5Dopen2(f, path.c_str(), H5P_DEFAULT), "opening " + path), H5Dclose);
        const auto dims = extent(path.c_str(), 3);
        if (dims[0] < static_cast<hsize_t>(keep) || dims[1] != fd.rows)
          throw std::runtime_error(h5_path.string() + ": " + path +
                                   " does not hold this run's walls and frames");
        std::vector<double>& v = wall_data.emplace_back(dims[0] * fd.rows * fd.comps);
        if (!v.empty())
          check_status(H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()),
                       "reading " + path);
        const hsize_t kept[3] = {static_cast<hsize_t>(keep), fd.rows, fd.comps};
        check_status(H5Dset_extent(d.get(), kept), "cutting " + path);
      }
      Handle attr(check(H5Aopen(f, "complete", H5P_DEFAULT), "opening 'complete'"), H5Aclose);
      const int zero = 0;
      check_status(H5Awrite(attr.get(), H5T_NATIVE_INT, &zero), "writing 'complete'");
      attr.reset();
      views = count_views(f);
      create_views(f, wanted_views());
      if (file_rw.reset() < 0) fail("closing the file");
      xdmf_frames.clear();
      walls_frames.clear();
      const std::size_t per_frame = 3 * walls.size();
      for (frames = 1; frames <= keep; ++frames) {
        append_xdmf_frame(times[frames - 1]);
        if (!walls.empty())
          append_walls_frame(times[frames - 1], wall_data[0].data() + (frames - 1) * per_frame,
                             wall_data[1].data() + (frames - 1) * per_frame);
      }
      frames = keep;
    }
    write_file_atomically(xdmf_path, xdmf_text(), /*durable=*/false);
    write_walls_xdmf(/*durable=*/false);
    file = Handle(check(H5Fopen(h5_path.c_str(), H5F_ACC_RDWR | H5F_ACC_SWMR_WRITE, H5P_DEFAULT),
                        "reopening for SWMR writing"),
                  H5Fclose);
    const Handle dapl = frame_access();
    time_dset = Handle(
        check(H5Dopen2(file.get(), "/frames/time", H5P_DEFAULT), "opening /frames/time"), H5Dclose);
    for (FrameDataset& fd : fields)
      fd.dset = Handle(
          check(H5Dopen2(file.get(), (std::string("/frames/") + fd.name).c_str(), dapl.get()),
                std::string("opening /frames/") + fd.name),
          H5Dclose);
    for (FrameDataset& fd : wall_fields)
      fd.dset =
          Handle(check(H5Dopen2(file.get(), (std::string("/walls/") + fd.name).c_str(), dapl.get()),
                       std::string("opening /walls/") + fd.name),
                 H5Dclose);
  }

  // Fixed-length, NUL-terminated UTF-8 strings, one per entry.
  void write_strings(hid_t group, const char* name, const std::vector<std::string>& values) {
    std::size_t width = 1;
    for (const std::string& b : values) width = std::max(width, b.size() + 1);
    std::vector<char> chars(std::max<std::size_t>(1, width * values.size()), '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
      std::copy(values[i].begin(), values[i].end(), chars.begin() + i * width);
    Handle stype(check(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
    check_status(H5Tset_size(stype.get(), width), "H5Tset_size");
    check_status(H5Tset_strpad(stype.get(), H5T_STR_NULLTERM), "H5Tset_strpad");
    check_status(H5Tset_cset(stype.get(), H5T_CSET_UTF8), "H5Tset_cset");
    const hsize_t dims[1] = {values.size()};
    write_static(group, name, stype.get(), stype.get(), 1, dims, chars.data());
  }

  // /walls: names, normals and patches once, and the per-frame datasets.
  void create_walls(hid_t root) {
    Handle g(
        check(H5Gcreate2(root, "walls", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating /walls"),
        H5Gclose);
    std::vector<std::string> names;
    std::vector<double> normal, patch;
    for (const ResultsWall& w : walls) {
      names.push_back(w.name);
      normal.insert(normal.end(), {w.normal.x(), w.normal.y(), w.normal.z()});
      for (const Vec3& c : w.patch) patch.insert(patch.end(), {c.x(), c.y(), c.z()});
    }
    write_strings(g.get(), "names", names);
    const hsize_t ndims[2] = {walls.size(), 3}, pdims[3] = {walls.size(), 4, 3};
    write_static(g.get(), "normal", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, ndims, normal.data());
    write_static(g.get(), "patch", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, pdims, patch.data());
    for (FrameDataset& f : wall_fields) create_frame_dataset(g.get(), f, H5T_IEEE_F64LE);
  }

  void create_frame_dataset(hid_t group, FrameDataset& f, hid_t type = H5I_INVALID_HID) {
    const hid_t file_type = type >= 0 ? type : frame_file_type();
    const std::size_t value_size = H5Tget_size(file_type);
    const int rank = f.rank();
    const hsize_t dims[3] = {0, f.rows, f.comps};
    const hsize_t maxdims[3] = {H5S_UNLIMITED, f.rows, f.comps};
    const hsize_t chunk_rows = std::clamp<hsize_t>(kChunkBytes / (f.comps * value_size), 1, f.rows);
    const hsize_t chunk[3] = {1, chunk_rows, f.comps};
    Handle space(check(H5Screate_simple(rank, dims, maxdims), "H5Screate_simple"), H5Sclose);
    Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
    check_status(H5Pset_chunk(dcpl.get(), rank, chunk), "H5Pset_chunk");
    // Every chunk is written whole (or to the end of the data): no fill values needed.
    check_status(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_NEVER), "H5Pset_fill_time");
    const Handle dapl = frame_access();
    f.dset = Handle(check(H5Dcreate2(group, f.name, file_type, space.get(), H5P_DEFAULT, dcpl.get(),
                                     dapl.get()),
                          std::string("creating ") + f.name),
                    H5Dclose);
    write_attribute_string(f.dset.get(), "unit", f.unit);
  }

  // Appends row `frames` of dataset `dset` (rank 1..3, fixed trailing dims) from `data`.
  void append(hid_t dset, int rank, hsize_t rows, hsize_t comps, const double* data,
              const char* name) {
    const hsize_t index = static_cast<hsize_t>(frames);
    const hsize_t extent[3] = {index + 1, rows, comps};
    check_status(H5Dset_extent(dset, extent), std::string("extending ") + name);
    Handle fspace(check(H5Dget_space(dset), "H5Dget_space"), H5Sclose);
    const hsize_t start[3] = {index, 0, 0};
    const hsize_t count[3] = {1, rows, comps};
    check_status(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
                 "H5Sselect_hyperslab");
    Handle mspace(check(H5Screate_simple(rank, count, nullptr), "H5Screate_simple"), H5Sclose);
    check_status(H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT, data),
                 std::string("writing ") + name);
  }

  std::string xdmf_text() const {
    std::string s;
    s.reserve(xdmf_frames.size() + 512);
    s += "<?xml version=\"1.0\" ?>\n";
    s += "<!-- femdem results: ";
    s += std::to_string(frames);
    s += " complete frames in results.h5; geometry is the reference configuration, apply "
         "\"Warp By Vector\" with displacement for the deformed shape -->\n";
    s += "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n";
    s += "  <Domain>\n";
    s += "    <Grid Name=\"femdem\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    s += xdmf_frames;
    s += "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return s;
  }

  void append_xdmf_frame(double time) {
    const std::string k = std::to_string(frames - 1);
    const std::string f = std::to_string(frames);  // declared extent: frames 0..k
    const std::string n = std::to_string(nodes), e = std::to_string(elements);
    const char* precision = options.single_precision ? "4" : "8";
    std::string& s = xdmf_frames;
    const std::string name = open_grid(s, "frame_", time);
    s += "        <Topology TopologyType=\"Tetrahedron_10\" NumberOfElements=\"" + e + "\">\n";
    s += "          <DataItem Dimensions=\"" + e +
         " 10\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">results.h5:/mesh/connectivity"
         "</DataItem>\n";
    s += "        </Topology>\n";
    s += "        <Geometry GeometryType=\"XYZ\">\n";
    s += "          <DataItem Dimensions=\"" + n +
         " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">results.h5:/mesh/coordinates"
         "</DataItem>\n";
    s += "        </Geometry>\n";
    if (std::find(options.optional_fields.begin(), options.optional_fields.end(), "node_body") !=
        options.optional_fields.end()) {
      s += "        <Attribute Name=\"node_body\" AttributeType=\"Scalar\" Center=\"Node\">\n";
      s += "          <DataItem Dimensions=\"" + n +
           "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">results.h5:/mesh/node_body"
           "</DataItem>\n";
      s += "        </Attribute>\n";
    }
    s += "        <Attribute Name=\"body\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
    s += "          <DataItem Dimensions=\"" + e +
         "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">results.h5:/mesh/element_body"
         "</DataItem>\n";
    s += "        </Attribute>\n";
    const bool viewed = frames - 1 < views;
    for (const FrameDataset& fd : fields) {
      const std::string rows = std::to_string(fd.rows);
      const bool vec = fd.comps > 1;
      const std::string c = std::to_string(fd.comps);
      const std::string shape = rows + (vec ? " " + c : "");
      s += "        <Attribute Name=\"";
      s += fd.name;
      s += "\" AttributeType=\"";
      s += fd.xdmf_type;
      s += "\" Center=\"";
      s += fd.node_centred ? "Node" : "Cell";
      s += "\">\n";
      if (viewed) {
        s += "          <DataItem Dimensions=\"" + shape + "\" NumberType=\"Float\" Precision=\"" +
             precision + "\" Format=\"HDF\">results.h5:/frame_views/" + name.substr(6) + "/" +
             fd.name + "</DataItem>\n";
      } else {
        s += "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"1 " + shape +
             "\" Type=\"HyperSlab\" NumberType=\"Float\" Precision=\"" + precision + "\">\n";
        s += "            <DataItem Dimensions=\"3 " + std::string(vec ? "3" : "2") +
             "\" NumberType=\"UInt\" Precision=\"4\" Format=\"XML\">" + k +
             (vec ? " 0 0 1 1 1 1 " : " 0 1 1 1 ") + shape + "</DataItem>\n";
        s += "            <DataItem Dimensions=\"" + f + " " + shape +
             "\" NumberType=\"Float\" Precision=\"" + precision +
             "\" Format=\"HDF\">results.h5:/frames/" + fd.name + "</DataItem>\n";
        s += "          </DataItem>\n";
      }
      s += "        </Attribute>\n";
    }
    s += "      </Grid>\n";
  }
};

ResultsWriter::ResultsWriter(const std::filesystem::path& folder, const ResultsMesh& mesh,
                             ResultsOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.set_up(folder, mesh, options);
  std::filesystem::create_directories(folder);
  // A stale results.xdmf must never point into the new results.h5.
  write_file_atomically(m.xdmf_path, m.xdmf_text(), /*durable=*/false);
  m.write_walls_xdmf(/*durable=*/false);

  Handle fapl(m.check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
  m.check_status(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST),
                 "H5Pset_libver_bounds");
  m.file = Handle(m.check(H5Fcreate(m.h5_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()),
                          "creating the file"),
                  H5Fclose);
  const hid_t root = m.file.get();
  m.write_root_attributes(root);

  // --- mesh ---
  {
    Handle g(
        m.check(H5Gcreate2(root, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "creating /mesh"),
        H5Gclose);
    const hsize_t cdims[2] = {m.nodes, 3};
    m.write_static(g.get(), "coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 2, cdims,
                   mesh.coordinates.data());
    static_assert(sizeof(Tet10) == 10 * sizeof(std::int32_t));
    const hsize_t tdims[2] = {m.elements, 10};
    m.write_static(g.get(), "connectivity", H5T_STD_I32LE, H5T_NATIVE_INT32, 2, tdims,
                   mesh.connectivity.data());
    m.write_static(g.get(), "node_body", H5T_STD_I32LE, H5T_NATIVE_INT32, 1, &m.nodes,
                   mesh.node_body.data());
    m.write_static(g.get(), "element_body", H5T_STD_I32LE, H5T_NATIVE_INT32, 1, &m.elements,
                   mesh.element_body.data());
    m.write_strings(g.get(), "body_names",
                    std::vector<std::string>(mesh.body_names.begin(), mesh.body_names.end()));
  }

  // --- frames ---
  {
    Handle g(m.check(H5Gcreate2(root, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     "creating /frames"),
             H5Gclose);
    const hsize_t dims[1] = {0}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {kTimeChunk};
    Handle space(m.check(H5Screate_simple(1, dims, maxdims), "H5Screate_simple"), H5Sclose);
    Handle dcpl(m.check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
    m.check_status(H5Pset_chunk(dcpl.get(), 1, chunk), "H5Pset_chunk");
    m.time_dset = Handle(m.check(H5Dcreate2(g.get(), "time", H5T_IEEE_F64LE, space.get(),
                                            H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                                 "creating /frames/time"),
                         H5Dclose);
    m.list_fields();
    for (FrameDataset& f : m.fields) m.create_frame_dataset(g.get(), f);
    for (FrameDataset& fd : m.fields)
      if (fd.comps == 9)
        m.write_attribute_string(fd.dset.get(), "components", "xx xy xz yx yy yz zx zy zz");
  }
  if (!m.walls.empty()) m.create_walls(root);
  m.create_views(root, m.wanted_views());

  // From here on the file stays valid whatever happens to this process.
  m.check_status(H5Fstart_swmr_write(root), "H5Fstart_swmr_write");
  m.open = true;
}

ResultsWriter::ResultsWriter(const std::filesystem::path& folder, const ResultsMesh& mesh,
                             ContinueFrom from, ResultsOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.set_up(folder, mesh, options);
  m.list_fields();
  if (!std::filesystem::is_regular_file(m.h5_path))
    throw std::runtime_error(m.h5_path.string() + " is missing: nothing to resume");
  m.reopen(from.frames);
  m.open = true;
}

ResultsWriter::~ResultsWriter() {
  try {
    close(false);
  } catch (...) {
  }
}

void ResultsWriter::write_frame(double time, const FrameFields& f) {
  Impl& m = *impl_;
  if (!m.open) throw std::logic_error("results: write_frame after close");
  auto need = [](std::span<const double> s, hsize_t n, const char* what) {
    if (s.size() != n) {
      throw std::invalid_argument(std::string("results: ") + what + " has " +
                                  std::to_string(s.size()) + " values, expected " +
                                  std::to_string(n));
    }
  };
  for (const FrameDataset& fd : m.fields) need(f.*fd.source, fd.rows * fd.given_comps(), fd.name);
  for (const FrameDataset& fd : m.wall_fields)
    need(f.*fd.source, fd.rows * fd.given_comps(), ("wall_" + std::string(fd.name)).c_str());
  for (FrameDataset& fd : m.fields) {
    const double* data = (f.*fd.source).data();
    if (fd.comps == 9) {
      // Symmetric (xx yy zz xy yz xz) -> full row-major 3x3.
      const double* s6 = data;
      double* s9 = fd.full.data();
      for (hsize_t e = 0; e < fd.rows; ++e, s6 += 6, s9 += 9) {
        s9[0] = s6[0];
        s9[1] = s6[3];
        s9[2] = s6[5];
        s9[3] = s6[3];
        s9[4] = s6[1];
        s9[5] = s6[4];
        s9[6] = s6[5];
        s9[7] = s6[4];
        s9[8] = s6[2];
      }
      data = fd.full.data();
    }
    m.append(fd.dset.get(), fd.rank(), fd.rows, fd.comps, data, fd.name);
  }
  for (FrameDataset& fd : m.wall_fields)
    m.append(fd.dset.get(), fd.rank(), fd.rows, fd.comps, (f.*fd.source).data(), fd.name);
  // The frame's data and chunk indices reach the file before /frames/time counts the frame.
  m.check_status(H5Fflush(m.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  m.append(m.time_dset.get(), 1, 1, 1, &time, "time");
  m.check_status(H5Fflush(m.file.get(), H5F_SCOPE_LOCAL), "H5Fflush");
  ++m.frames;

  m.append_xdmf_frame(time);
  write_file_atomically(m.xdmf_path, m.xdmf_text(), /*durable=*/false);
  if (!m.walls.empty()) {
    m.append_walls_frame(time, f.wall_displacement.data(), f.wall_force.data());
    m.write_walls_xdmf(/*durable=*/false);
  }
}

void ResultsWriter::close(bool complete) {
  Impl& m = *impl_;
  if (!m.open) return;
  m.open = false;
  m.fields.clear();
  m.wall_fields.clear();
  m.time_dset.reset();
  if (m.file.reset() < 0) m.fail("closing the file");
  if (complete) {
    // Attributes cannot change in SWMR mode: reopen normally to mark the run complete.
    Handle file(m.check(H5Fopen(m.h5_path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "reopening"),
                H5Fclose);
    Handle attr(m.check(H5Aopen(file.get(), "complete", H5P_DEFAULT), "opening 'complete'"),
                H5Aclose);
    const int one = 1;
    m.check_status(H5Awrite(attr.get(), H5T_NATIVE_INT, &one), "writing 'complete'");
    attr.reset();
    if (file.reset() < 0) m.fail("closing the file");
  }
  // Make the finished outputs durable.
  const int fd = ::open(m.h5_path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  write_file_atomically(m.xdmf_path, m.xdmf_text(), /*durable=*/true);
  m.write_walls_xdmf(/*durable=*/true);
}

std::string results_scene_digest(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / kH5Name;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return "";
  const QuietErrors quiet;
  std::string digest;
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT), H5Fclose);
  if (f.valid()) read_string_attribute(f.get(), "scene_digest", digest);
  return digest;
}

std::int64_t ResultsWriter::frame_count() const {
  return impl_->frames;
}
bool ResultsWriter::is_open() const {
  return impl_->open;
}
std::filesystem::path ResultsWriter::h5_path() const {
  return impl_->h5_path;
}
std::filesystem::path ResultsWriter::xdmf_path() const {
  return impl_->xdmf_path;
}
std::filesystem::path ResultsWriter::walls_xdmf_path() const {
  return impl_->walls_xdmf_path;
}

}  // namespace femdem
