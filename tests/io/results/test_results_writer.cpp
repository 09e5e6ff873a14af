// SPDX-License-Identifier: GPL-3.0-or-later
// ResultsWriter: layout and values of results.h5, the time series in results.xdmf, the
// `complete` flag, and what a run killed in the middle of writing leaves behind.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "io/results/results_writer.hpp"

namespace fs = std::filesystem;
using namespace femdem;

namespace {

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::path(FEMDEM_TEST_TMP) / "results_writer" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A mesh and one frame's fields, filled with values that identify frame, entity and component.
struct TestData {
  std::vector<double> X;
  std::vector<Tet10> conn;
  std::vector<std::int32_t> node_body, element_body;
  std::vector<std::string> names;
  std::vector<double> u, v, s6, vm, p, eps;

  std::size_t nodes() const { return X.size() / 3; }
  std::size_t elements() const { return conn.size(); }
  ResultsMesh mesh() const { return {X, conn, node_body, element_body, names}; }
  FrameFields fields() const { return {u, v, s6, vm, p, eps}; }

  static double disp(int k, std::size_t i) { return k + 1e-6 * static_cast<double>(i); }
  static double sig(int k, std::size_t e, int c) {
    return 1e6 * k + 10.0 * static_cast<double>(e) + c;
  }
  static double scal(int which, int k, std::size_t e) {
    return which * 100.0 + k + 1e-6 * static_cast<double>(e);
  }
  void fill(int k) {
    u.resize(3 * nodes());
    v.resize(3 * nodes());
    for (std::size_t i = 0; i < u.size(); ++i) {
      u[i] = disp(k, i);
      v[i] = -disp(k, i);
    }
    s6.resize(6 * elements());
    vm.resize(elements());
    p.resize(elements());
    eps.resize(elements());
    for (std::size_t e = 0; e < elements(); ++e) {
      for (int c = 0; c < 6; ++c) s6[6 * e + c] = sig(k, e, c);
      vm[e] = scal(1, k, e);
      p[e] = scal(2, k, e);
      eps[e] = scal(3, k, e);
    }
  }
};

// Two right-handed TET10 elements sharing the face 1-2-3, two bodies.
TestData two_tets() {
  TestData d;
  const std::vector<std::array<double, 3>> corners = {
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  for (const auto& c : corners) d.X.insert(d.X.end(), c.begin(), c.end());
  std::map<std::pair<int, int>, int> mid;
  auto midnode = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int id = static_cast<int>(d.X.size() / 3);
    for (int c = 0; c < 3; ++c) d.X.push_back(0.5 * (d.X[3 * a + c] + d.X[3 * b + c]));
    mid[key] = id;
    return id;
  };
  for (const std::array<int, 4> t : {std::array<int, 4>{0, 1, 2, 3}, {1, 2, 3, 4}}) {
    Tet10 e{};
    for (int i = 0; i < 4; ++i) e[i] = t[i];
    for (int i = 0; i < 6; ++i) e[4 + i] = midnode(t[kTet10Edges[i][0]], t[kTet10Edges[i][1]]);
    d.conn.push_back(e);
  }
  d.node_body.assign(d.nodes(), 0);
  d.node_body[4] = 1;
  d.element_body = {0, 1};
  d.names = {"ball", "anvil"};
  return d;
}

// A large mesh for the kill and speed tests: connectivity is arbitrary but valid.
TestData big_mesh(std::size_t elements) {
  TestData d;
  const std::size_t nodes = elements * 7 / 5;
  d.X.resize(3 * nodes);
  for (std::size_t i = 0; i < d.X.size(); ++i) d.X[i] = 1e-3 * static_cast<double>(i % 1000);
  d.conn.resize(elements);
  for (std::size_t e = 0; e < elements; ++e) {
    for (int k = 0; k < 10; ++k) d.conn[e][k] = static_cast<std::int32_t>((e * 7 + k) % nodes);
  }
  d.node_body.assign(nodes, 0);
  d.element_body.assign(elements, 0);
  d.names = {"rod"};
  return d;
}

// --- HDF5 reading helpers ---
struct H5 {
  hid_t id;
  herr_t (*closer)(hid_t);
  ~H5() {
    if (id >= 0) closer(id);
  }
};

std::vector<hsize_t> dims_of(hid_t file, const char* path) {
  H5 d{H5Dopen2(file, path, H5P_DEFAULT), H5Dclose};
  EXPECT_GE(d.id, 0) << path;
  if (d.id < 0) return {};
  H5 s{H5Dget_space(d.id), H5Sclose};
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(s.id));
  H5Sget_simple_extent_dims(s.id, dims.data(), nullptr);
  return dims;
}

// Reads the whole dataset (frame < 0) or one frame of a frame dataset, as doubles or ints.
template <class T>
std::vector<T> read(hid_t file, const char* path, long frame = -1) {
  H5 d{H5Dopen2(file, path, H5P_DEFAULT), H5Dclose};
  if (d.id < 0) {
    ADD_FAILURE() << "cannot open " << path;
    return {};
  }
  H5 fs{H5Dget_space(d.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(fs.id);
  std::vector<hsize_t> dims(rank);
  H5Sget_simple_extent_dims(fs.id, dims.data(), nullptr);
  std::vector<hsize_t> start(rank, 0), count = dims;
  if (frame >= 0) {
    start[0] = static_cast<hsize_t>(frame);
    count[0] = 1;
  }
  H5Sselect_hyperslab(fs.id, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  hsize_t n = 1;
  for (hsize_t c : count) n *= c;
  std::vector<T> out(n);
  H5 ms{H5Screate_simple(1, &n, nullptr), H5Sclose};
  const hid_t mt = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT32;
  EXPECT_GE(H5Dread(d.id, mt, ms.id, fs.id, H5P_DEFAULT, out.data()), 0) << path;
  return out;
}

int read_complete(hid_t file) {
  H5 a{H5Aopen(file, "complete", H5P_DEFAULT), H5Aclose};
  int v = -1;
  EXPECT_GE(H5Aread(a.id, H5T_NATIVE_INT, &v), 0);
  return v;
}

// --- XDMF parsing ---
struct XdmfInfo {
  std::vector<double> times;
  std::vector<long> slab_frames;  // first hyperslab start of every frame attribute
  std::vector<std::string> paths;
  std::size_t grids = 0;
};

XdmfInfo parse_xdmf(const std::string& text) {
  XdmfInfo x;
  const std::regex time_re(R"(<Time Value="([^"]+)\"/>)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), time_re);
       it != std::sregex_iterator(); ++it) {
    x.times.push_back(std::stod((*it)[1]));
  }
  const std::regex grid_re(R"(<Grid Name="frame_\d+" GridType="Uniform">)");
  x.grids = static_cast<std::size_t>(std::distance(
      std::sregex_iterator(text.begin(), text.end(), grid_re), std::sregex_iterator()));
  const std::regex slab_re(R"(Format="XML">(\d+) )");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), slab_re);
       it != std::sregex_iterator(); ++it) {
    x.slab_frames.push_back(std::stol((*it)[1]));
  }
  const std::regex path_re(R"(>results\.h5:([^<]+)<)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), path_re);
       it != std::sregex_iterator(); ++it) {
    x.paths.push_back((*it)[1]);
  }
  return x;
}

// Checks that frame k of every field holds what TestData::fill(k) wrote.
void expect_frame(hid_t file, const TestData& d, long k) {
  const int ki = static_cast<int>(k);
  const auto u = read<double>(file, "/frames/displacement", k);
  const auto v = read<double>(file, "/frames/velocity", k);
  ASSERT_EQ(u.size(), 3 * d.nodes());
  ASSERT_EQ(v.size(), 3 * d.nodes());
  for (std::size_t i = 0; i < u.size(); ++i) {
    ASSERT_EQ(u[i], TestData::disp(ki, i)) << "frame " << k << " displacement " << i;
    ASSERT_EQ(v[i], -TestData::disp(ki, i)) << "frame " << k << " velocity " << i;
  }
  const auto s = read<double>(file, "/frames/stress", k);
  ASSERT_EQ(s.size(), 9 * d.elements());
  // xx yy zz xy yz xz -> row-major 3x3
  const int map9[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
  for (std::size_t e = 0; e < d.elements(); ++e) {
    for (int c = 0; c < 9; ++c) {
      ASSERT_EQ(s[9 * e + c], TestData::sig(ki, e, map9[c])) << "frame " << k << " stress " << e;
    }
  }
  const char* scalars[3] = {"/frames/von_mises", "/frames/pressure",
                            "/frames/equivalent_plastic_strain"};
  for (int w = 0; w < 3; ++w) {
    const auto a = read<double>(file, scalars[w], k);
    ASSERT_EQ(a.size(), d.elements());
    for (std::size_t e = 0; e < a.size(); ++e) {
      ASSERT_EQ(a[e], TestData::scal(w + 1, ki, e)) << scalars[w] << " frame " << k;
    }
  }
}

}  // namespace

TEST(ResultsWriter, WritesMeshFramesAndXdmf) {
  const fs::path dir = test_dir("basic");
  TestData d = two_tets();
  {
    ResultsWriter w(dir, d.mesh());
    for (int k = 0; k < 3; ++k) {
      d.fill(k);
      w.write_frame(0.5 * k, d.fields());
    }
    EXPECT_EQ(w.frame_count(), 3);
    w.close(true);
    EXPECT_FALSE(w.is_open());
    EXPECT_THROW(w.write_frame(2.0, d.fields()), std::logic_error);
  }

  H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(file.id, 0);
  EXPECT_EQ(read_complete(file.id), 1);
  EXPECT_EQ(read<double>(file.id, "/mesh/coordinates"), d.X);
  const auto conn = read<int>(file.id, "/mesh/connectivity");
  ASSERT_EQ(conn.size(), 20u);
  for (std::size_t e = 0; e < 2; ++e) {
    for (int i = 0; i < 10; ++i) EXPECT_EQ(conn[10 * e + i], d.conn[e][i]);
  }
  EXPECT_EQ(read<int>(file.id, "/mesh/node_body"), d.node_body);
  EXPECT_EQ(read<int>(file.id, "/mesh/element_body"), d.element_body);
  {
    H5 ds{H5Dopen2(file.id, "/mesh/body_names", H5P_DEFAULT), H5Dclose};
    H5 t{H5Dget_type(ds.id), H5Tclose};
    const std::size_t width = H5Tget_size(t.id);
    std::vector<char> buf(2 * width);
    ASSERT_GE(H5Dread(ds.id, t.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), 0);
    EXPECT_STREQ(buf.data(), "ball");
    EXPECT_STREQ(buf.data() + width, "anvil");
  }

  EXPECT_EQ(read<double>(file.id, "/frames/time"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(dims_of(file.id, "/frames/displacement"), (std::vector<hsize_t>{3, d.nodes(), 3}));
  EXPECT_EQ(dims_of(file.id, "/frames/stress"), (std::vector<hsize_t>{3, 2, 9}));
  EXPECT_EQ(dims_of(file.id, "/frames/von_mises"), (std::vector<hsize_t>{3, 2}));
  for (long k = 0; k < 3; ++k) expect_frame(file.id, d, k);

  const XdmfInfo x = parse_xdmf(read_text(dir / "results.xdmf"));
  EXPECT_EQ(x.grids, 3u);
  EXPECT_EQ(x.times, (std::vector<double>{0.0, 0.5, 1.0}));
  ASSERT_EQ(x.slab_frames.size(), 3u * 6u);
  for (std::size_t i = 0; i < x.slab_frames.size(); ++i) EXPECT_EQ(x.slab_frames[i], long(i / 6));
  ASSERT_FALSE(x.paths.empty());
  for (const std::string& p : x.paths) {
    EXPECT_GT(H5Lexists(file.id, p.c_str(), H5P_DEFAULT), 0) << p;
  }
  const std::string text = read_text(dir / "results.xdmf");
  EXPECT_NE(text.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(text.find("TopologyType=\"Tetrahedron_10\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"stress\" AttributeType=\"Tensor\""), std::string::npos);
  // No temporary files left behind.
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
  }
}

std::string read_string_attribute(hid_t obj, const char* name) {
  H5 a{H5Aopen(obj, name, H5P_DEFAULT), H5Aclose};
  if (a.id < 0) return "(missing)";
  H5 t{H5Aget_type(a.id), H5Tclose};
  std::string v(H5Tget_size(t.id), '\0');
  EXPECT_GE(H5Aread(a.id, t.id, v.data()), 0);
  return v.substr(0, v.find('\0'));
}

// The frames the writer expects get /frame_views: one dataset per field and frame, named by a
// plain HDF DataItem in results.xdmf (what meshio and ParaView's Xdmf3 readers need) and
// holding the same values as the frame's row of /frames; a frame past them is named by a
// HyperSlab. The root and the frame datasets say their units.
TEST(ResultsWriter, FrameViewsNameEachFrameAsAWholeDataset) {
  TestData d = two_tets();
  const fs::path dir = test_dir("views");
  {
    ResultsWriter w(dir, d.mesh(), ResultsOptions{.scene_digest = "abc", .expected_frames = 2});
    for (int k = 0; k < 3; ++k) {
      d.fill(k);
      w.write_frame(0.5 * k, d.fields());
    }
    w.close(true);
  }
  const std::string text = read_text(dir / "results.xdmf");
  const XdmfInfo x = parse_xdmf(text);
  EXPECT_EQ(x.grids, 3u);
  ASSERT_EQ(x.slab_frames.size(), 6u);  // frame 2 only
  for (long f : x.slab_frames) EXPECT_EQ(f, 2);
  for (const char* field : {"displacement", "velocity", "stress", "von_mises", "pressure",
                            "equivalent_plastic_strain"}) {
    for (const char* frame : {"000000", "000001"}) {
      const std::string path = std::string("/frame_views/") + frame + "/" + field;
      EXPECT_NE(text.find("Format=\"HDF\">results.h5:" + path + "<"), std::string::npos) << path;
    }
    EXPECT_EQ(text.find(std::string("/frame_views/000002/") + field), std::string::npos);
  }
  H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(file.id, 0);
  for (long k = 0; k < 2; ++k) {
    const std::string base = "/frame_views/00000" + std::to_string(k) + "/";
    for (const char* field : {"displacement", "stress", "equivalent_plastic_strain"}) {
      const std::string view = base + field, row = std::string("/frames/") + field;
      EXPECT_EQ(read<double>(file.id, view.c_str()), read<double>(file.id, row.c_str(), k)) << view;
    }
    EXPECT_EQ(dims_of(file.id, (base + "displacement").c_str()),
              (std::vector<hsize_t>{d.nodes(), 3}));
    EXPECT_EQ(dims_of(file.id, (base + "stress").c_str()), (std::vector<hsize_t>{2, 9}));
    EXPECT_EQ(dims_of(file.id, (base + "von_mises").c_str()), (std::vector<hsize_t>{2}));
  }
  EXPECT_EQ(read<double>(file.id, "/frame_views/000001/displacement")[0], TestData::disp(1, 0));
  EXPECT_LE(H5Lexists(file.id, "/frame_views/000002", H5P_DEFAULT), 0);
  EXPECT_EQ(read_string_attribute(file.id, "units"), "SI: m, s, kg, Pa, N, J");
  EXPECT_EQ(read_string_attribute(file.id, "scene_digest"), "abc");
  EXPECT_EQ(read_string_attribute(file.id, "femdem_version").rfind("0.", 0), 0u);
  EXPECT_NE(read_string_attribute(file.id, "node_order").find("0-1 1-2 2-0 0-3 1-3 2-3"),
            std::string::npos);
  const std::map<std::string, std::string> units = {
      {"displacement", "m"}, {"velocity", "m/s"}, {"stress", "Pa"},
      {"von_mises", "Pa"},   {"pressure", "Pa"},  {"equivalent_plastic_strain", "1"}};
  for (const auto& [field, unit] : units) {
    H5 ds{H5Dopen2(file.id, ("/frames/" + field).c_str(), H5P_DEFAULT), H5Dclose};
    EXPECT_EQ(read_string_attribute(ds.id, "unit"), unit) << field;
  }
}

// Walls: names, normals and patches once, each frame's displacement and force in /walls, and
// walls.xdmf with each wall's quadrilateral where it is at that frame. A run without walls
// leaves no walls.xdmf, not even a stale one.
TEST(ResultsWriter, WallsAreWrittenAsMovingQuadrilaterals) {
  TestData d = two_tets();
  const fs::path dir = test_dir("walls");
  std::vector<ResultsWall> walls = {
      {"floor", Vec3(0, 0, 1), {Vec3(-1, -1, 0), Vec3(2, -1, 0), Vec3(2, 2, 0), Vec3(-1, 2, 0)}},
      {"punch", Vec3(0, 0, -1), {Vec3(-1, 2, 1), Vec3(2, 2, 1), Vec3(2, -1, 1), Vec3(-1, -1, 1)}}};
  ResultsMesh mesh = d.mesh();
  mesh.walls = walls;
  {
    ResultsWriter w(dir, mesh);
    for (int k = 0; k < 3; ++k) {
      d.fill(k);
      const std::vector<double> disp = {0, 0, 0, 0, 0, -0.1 * k};
      const std::vector<double> force = {0, 0, -10.0 * k, 0, 0, 10.0 * k};
      FrameFields f = d.fields();
      f.wall_displacement = disp;
      f.wall_force = force;
      w.write_frame(0.5 * k, f);
    }
    FrameFields short_walls = d.fields();  // the wall fields are required with walls
    EXPECT_THROW(w.write_frame(2.0, short_walls), std::invalid_argument);
    w.close(true);
  }
  {
    H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(file.id, 0);
    EXPECT_EQ(dims_of(file.id, "/walls/patch"), (std::vector<hsize_t>{2, 4, 3}));
    EXPECT_EQ(read<double>(file.id, "/walls/normal"), (std::vector<double>{0, 0, 1, 0, 0, -1}));
    EXPECT_EQ(read<double>(file.id, "/walls/displacement", 2),
              (std::vector<double>{0, 0, 0, 0, 0, -0.2}));
    EXPECT_EQ(read<double>(file.id, "/walls/force", 1), (std::vector<double>{0, 0, -10, 0, 0, 10}));
    {
      H5 ds{H5Dopen2(file.id, "/walls/force", H5P_DEFAULT), H5Dclose};
      EXPECT_EQ(read_string_attribute(ds.id, "unit"), "N");
    }
  }  // (closed: a writer cannot replace a file open elsewhere in this process)
  const std::string text = read_text(dir / "walls.xdmf");
  const std::regex grid_re(R"(<Grid Name="walls_\d+" GridType="Uniform">)");
  EXPECT_EQ(std::distance(std::sregex_iterator(text.begin(), text.end(), grid_re),
                          std::sregex_iterator()),
            3);
  EXPECT_NE(text.find("TopologyType=\"Quadrilateral\" NumberOfElements=\"2\""), std::string::npos);
  // the punch's first corner in the last frame: (-1, 2, 1) moved by -0.2 in z
  EXPECT_NE(text.find("-1 2 0.80000000000000004 2 2 0.80000000000000004"), std::string::npos)
      << text;
  EXPECT_NE(text.find(">0 0 -20 0 0 20</DataItem>"), std::string::npos) << text;

  // the same folder reused by a run without walls: the stale walls.xdmf goes
  {
    ResultsWriter w(dir, d.mesh());
    w.close(true);
  }
  EXPECT_FALSE(fs::exists(dir / "walls.xdmf"));
}

TEST(ResultsWriter, IncompleteCloseAndDestructorLeaveCompleteZero) {
  TestData d = two_tets();
  d.fill(0);
  const fs::path a = test_dir("close_false"), b = test_dir("destructor");
  {
    ResultsWriter w(a, d.mesh());
    w.write_frame(0.0, d.fields());
    w.close(false);
  }
  {
    ResultsWriter w(b, d.mesh());
    w.write_frame(0.0, d.fields());
    w.write_frame(1.0, d.fields());
  }
  for (const auto& [dir, n] : {std::pair{a, 1u}, std::pair{b, 2u}}) {
    // A closed file (even an incomplete one) opens without SWMR.
    H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(file.id, 0);
    EXPECT_EQ(read_complete(file.id), 0);
    EXPECT_EQ(read<double>(file.id, "/frames/time").size(), n);
    EXPECT_EQ(parse_xdmf(read_text(dir / "results.xdmf")).grids, n);
  }
}

TEST(ResultsWriter, RejectsWrongSizes) {
  TestData d = two_tets();
  d.fill(0);
  const fs::path dir = test_dir("sizes");
  ResultsWriter w(dir, d.mesh());
  TestData bad = d;
  bad.vm.pop_back();
  EXPECT_THROW(w.write_frame(0.0, bad.fields()), std::invalid_argument);
  bad = d;
  bad.u.push_back(0.0);
  EXPECT_THROW(w.write_frame(0.0, bad.fields()), std::invalid_argument);
  EXPECT_EQ(w.frame_count(), 0);
  w.write_frame(0.0, d.fields());  // still usable
  EXPECT_EQ(w.frame_count(), 1);

  TestData broken = d;
  broken.conn[1][9] = 99;
  EXPECT_THROW(ResultsWriter(test_dir("bad_conn"), broken.mesh()), std::invalid_argument);
}

TEST(ResultsWriter, SinglePrecisionOption) {
  TestData d = two_tets();
  d.fill(2);
  const fs::path dir = test_dir("float32");
  {
    ResultsWriter w(dir, d.mesh(), ResultsOptions{.single_precision = true});
    w.write_frame(1.0, d.fields());
    w.close(true);
  }
  H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  H5 ds{H5Dopen2(file.id, "/frames/velocity", H5P_DEFAULT), H5Dclose};
  H5 t{H5Dget_type(ds.id), H5Tclose};
  EXPECT_EQ(H5Tget_size(t.id), 4u);
  const auto v = read<double>(file.id, "/frames/velocity", 0);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_FLOAT_EQ(v[i], d.v[i]);
  EXPECT_NE(read_text(dir / "results.xdmf").find("Precision=\"4\""), std::string::npos);
}

// A writer process is SIGKILLed at varying moments while it writes frames of a 20k-element
// mesh. Every frame named by results.xdmf must then be fully readable from results.h5.
TEST(ResultsWriter, KilledWriterLeavesReadableFrames) {
  const TestData proto = big_mesh(20000);
  for (int trial = 0; trial < 8; ++trial) {
    const fs::path dir = test_dir("kill_" + std::to_string(trial));
    const int min_frames = 2 + trial % 3;
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      try {
        TestData d = proto;
        ResultsWriter w(dir, d.mesh(), ResultsOptions{.expected_frames = 300});
        for (int k = 0; k < 300; ++k) {
          d.fill(k);
          w.write_frame(1e-3 * k, d.fields());
        }
      } catch (...) {
        _exit(3);
      }
      _exit(2);  // not killed in time
    }
    // Wait until the xdmf names enough frames, then kill at a trial-dependent moment.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (parse_xdmf(read_text(dir / "results.xdmf")).grids >= std::size_t(min_frames)) break;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    std::this_thread::sleep_for(std::chrono::microseconds(450 * trial));
    kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "writer exited with " << WEXITSTATUS(status);

    const XdmfInfo x = parse_xdmf(read_text(dir / "results.xdmf"));
    ASSERT_GE(x.grids, std::size_t(min_frames));
    // The writer's SWMR mark stays on a killed file: open it as a SWMR reader.
    H5 file{H5Fopen((dir / "results.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT),
            H5Fclose};
    ASSERT_GE(file.id, 0) << "trial " << trial;
    EXPECT_EQ(read_complete(file.id), 0);
    const auto time = read<double>(file.id, "/frames/time");
    EXPECT_GE(time.size(), x.grids);      // the xdmf never names an unfinished frame
    EXPECT_LE(time.size(), x.grids + 1);  // at most the frame being announced
    for (const std::string& p : x.paths) {
      EXPECT_GT(H5Lexists(file.id, p.c_str(), H5P_DEFAULT), 0) << p;
    }
    for (std::size_t k = 0; k < x.grids; ++k) {
      EXPECT_EQ(time[k], 1e-3 * static_cast<double>(k));
      EXPECT_EQ(x.times[k], time[k]);
    }
    // The last frame the xdmf names, and every frame /frames/time counts, read back intact.
    for (std::size_t k = 0; k < time.size(); ++k) {
      expect_frame(file.id, proto, static_cast<long>(k));
    }
    // ... and so do the views results.xdmf names for its last frame
    char last[64];
    std::snprintf(last, sizeof last, "/frame_views/%06zu/displacement", x.grids - 1);
    EXPECT_EQ(read<double>(file.id, last),
              read<double>(file.id, "/frames/displacement", static_cast<long>(x.grids - 1)));
    std::printf("[ trial %d ] killed with %zu frames in results.xdmf, %zu in /frames/time\n", trial,
                x.grids, time.size());
    fs::remove_all(dir);
  }
}

// Not a limit, a measurement: time per frame for 1e5 elements (1.4e5 nodes).
TEST(ResultsWriter, TimePerFrame100kElements) {
  TestData d = big_mesh(100000);
  const fs::path dir = test_dir("speed");
  const std::int64_t views = 2000;
  const auto c0 = std::chrono::steady_clock::now();
  ResultsWriter w(dir, d.mesh(), ResultsOptions{.expected_frames = views});
  const double create_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
  std::printf("[ measure ] file with the mesh and the views of %lld frames made in %.2f s\n",
              static_cast<long long>(views), create_s);
  d.fill(0);
  const int frames = 10;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < frames; ++k) w.write_frame(1e-3 * k, d.fields());
  const double per =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / frames;
  w.close(true);
  std::printf("[ measure ] %d frames of %zu elements / %zu nodes: %.1f ms per frame\n", frames,
              d.elements(), d.nodes(), 1e3 * per);
  EXPECT_LT(per, 2.0);
  fs::remove_all(dir);
}
