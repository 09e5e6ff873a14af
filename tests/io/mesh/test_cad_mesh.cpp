// SPDX-License-Identifier: GPL-3.0-or-later
// CAD surfaces -> TET10 meshes (io/mesh/cad_mesh.hpp), the mesh cache (io/mesh/mesh_cache.hpp), the
// scene path and `femdem mesh`: volumes of meshed cubes and spheres against the exact values, every
// kind of broken surface giving exit code 2 with a message that says what and where,
// determinism, the .msh round trip and the cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/cad_mesh.hpp"
#include "io/mesh/gmsh_io.hpp"
#include "io/mesh/mesh_cache.hpp"
#include "io/scene/scene_reader.hpp"
#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;
using femdem::TriangleSurface;
using femdem::Vec3;
using Tri = std::array<std::int32_t, 3>;

fs::path tmp_dir(const std::string& name) {
  const fs::path d = fs::path(FEMDEM_TEST_TMP) / "cad" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---------------------------------------------------------------------------------------------
// Surfaces and writers

// The cube [0, a]^3, 12 outward triangles.
TriangleSurface cube(double a = 1.0, Vec3 origin = Vec3::Zero()) {
  TriangleSurface s;
  for (int i = 0; i < 8; ++i)
    s.points.push_back(origin + a * Vec3(i & 1 ? 1 : 0, i & 2 ? 1 : 0, i & 4 ? 1 : 0));
  // corners: bit 0 = x, bit 1 = y, bit 2 = z
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

// Unit-radius icosphere: the icosahedron with every triangle split in 4, `levels` times.
TriangleSurface icosphere(int levels, double radius = 1.0) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleSurface s;
  for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    s.points.push_back(p.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      s.points.push_back((s.points[a] + s.points[b]).normalized());
      return mid[key] = static_cast<int>(s.points.size()) - 1;
    };
    std::vector<Tri> next;
    for (const Tri& f : s.triangles) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    s.triangles = std::move(next);
  }
  for (Vec3& p : s.points) p *= radius;
  return s;
}

double enclosed_volume(const TriangleSurface& s) {
  double v = 0.0;
  for (const Tri& t : s.triangles)
    v += s.points[t[0]].dot(s.points[t[1]].cross(s.points[t[2]])) / 6.0;
  return v;
}

void write_stl_binary(const TriangleSurface& s, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = "femdem test surface";
  out.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(s.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const Tri& t : s.triangles) {
    const Vec3 nrm = (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
    float f[12];
    for (int k = 0; k < 3; ++k) f[k] = static_cast<float>(nrm[k]);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) f[3 + 3 * c + k] = static_cast<float>(s.points[t[c]][k]);
    out.write(reinterpret_cast<const char*>(f), sizeof f);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

void write_stl_ascii(const TriangleSurface& s, const fs::path& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid part\n";
  for (const Tri& t : s.triangles) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (int c = 0; c < 3; ++c)
      out << "   vertex " << s.points[t[c]][0] << ' ' << s.points[t[c]][1] << ' '
          << s.points[t[c]][2] << '\n';
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid part\n";
}

void write_obj(const TriangleSurface& s, const fs::path& path) {
  std::ofstream out(path);
  out.precision(17);
  for (const Vec3& p : s.points) out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (const Tri& t : s.triangles)
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

void write_off(const TriangleSurface& s, const fs::path& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << s.points.size() << ' ' << s.triangles.size() << " 0\n";
  for (const Vec3& p : s.points) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (const Tri& t : s.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

void write_ply(const TriangleSurface& s, const fs::path& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex " << s.points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face "
      << s.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : s.points) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (const Tri& t : s.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

femdem::CadMeshOptions options(double h, double scale = 1.0) {
  femdem::CadMeshOptions o;
  o.element_size = h;
  o.scale = scale;
  return o;
}

double mesh_volume(const femdem::Tet10Mesh& m) {
  return femdem::mesh_quality(m).total_volume;
}

// ---------------------------------------------------------------------------------------------
// Meshing good surfaces

TEST(CadMesh, CubeInEveryFormatMeshesToTheExactVolumeWithItsCorners) {
  const fs::path d = tmp_dir("formats");
  const TriangleSurface c = cube();
  std::vector<fs::path> files = {d / "cube_bin.stl", d / "cube_ascii.stl", d / "cube.obj",
                                 d / "cube.off", d / "cube.ply"};
  write_stl_binary(c, files[0]);
  write_stl_ascii(c, files[1]);
  write_obj(c, files[2]);
  write_off(c, files[3]);
  write_ply(c, files[4]);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    femdem::CadMeshReport rep;
    const femdem::Tet10Mesh m = femdem::mesh_cad_file(f.string(), options(0.25), &rep);
    const femdem::MeshQuality q = femdem::mesh_quality(m);
    EXPECT_EQ(rep.surface_triangles, 12);
    EXPECT_EQ(rep.import.merged_vertices, 8);
    EXPECT_EQ(rep.sharp_edges, 12);  // the cube's edges, not the face diagonals
    EXPECT_NEAR(q.total_volume, 1.0, 1e-12);
    EXPECT_EQ(q.bad_elements, 0);
    EXPECT_GT(q.min_dihedral_deg, 5.0);
    EXPECT_GE(q.p05_min_dihedral_deg, q.min_dihedral_deg);
    EXPECT_LE(q.p95_aspect_ratio, q.max_aspect_ratio);
    // The corners survive exactly (feature protection).
    int corners = 0;
    for (const Vec3& x : m.nodes) {
      bool corner = true;
      for (int k = 0; k < 3; ++k) corner &= x[k] == 0.0 || x[k] == 1.0;
      corners += corner;
    }
    EXPECT_EQ(corners, 8);
    // Every node inside the cube.
    for (const Vec3& x : m.nodes) EXPECT_TRUE(x.minCoeff() >= -1e-12 && x.maxCoeff() <= 1 + 1e-12);
  }
}

// glTF places meshes through a node hierarchy; the node's transform must be applied. (This
// 2 m cube at x = 10 and h 0.5 also made CGAL 5.5's ODT crash, which is why ODT is opt-in.)
TEST(CadMesh, GltfNodeTransformIsApplied) {
  const fs::path d = tmp_dir("gltf");
  const TriangleSurface c = cube();
  std::string bin;
  for (const Vec3& p : c.points)
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(p[k]);
      bin.append(reinterpret_cast<const char*>(&f), 4);
    }
  for (const Tri& t : c.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint16_t i = static_cast<std::uint16_t>(t[k]);
      bin.append(reinterpret_cast<const char*>(&i), 2);
    }
  std::ofstream(d / "cube.bin", std::ios::binary) << bin;
  std::ofstream(d / "cube.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
  "buffers": [{"byteLength": 168, "uri": "cube.bin"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96, "target": 34962},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 72, "target": 34963}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0],
     "max": [1, 1, 1]},
    {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]})";
  const auto m = femdem::mesh_cad_file((d / "cube.gltf").string(), options(0.5));
  EXPECT_NEAR(mesh_volume(m), 8.0, 1e-12);
  Vec3 lo = m.nodes[0], hi = m.nodes[0];
  for (const Vec3& x : m.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  EXPECT_EQ(lo, Vec3(10, 0, 0));
  EXPECT_EQ(hi, Vec3(12, 2, 2));
}

TEST(CadMesh, SphereVolumeIsWithinOnePercentOfTheExactOne) {
  const fs::path d = tmp_dir("sphere");
  const TriangleSurface s = icosphere(4);  // 5120 triangles
  write_stl_binary(s, d / "sphere.stl");
  const double exact = 4.0 / 3.0 * std::numbers::pi;
  // The faceted input itself is 0.3 % short of the sphere.
  EXPECT_NEAR(enclosed_volume(s) / exact, 1.0, 0.005);
  femdem::CadMeshReport rep;
  const double h = 0.12;
  const femdem::Tet10Mesh m = femdem::mesh_cad_file((d / "sphere.stl").string(), options(h), &rep);
  const femdem::MeshQuality q = femdem::mesh_quality(m);
  EXPECT_NEAR(q.total_volume / exact, 1.0, 0.01) << femdem::format_mesh_quality(q);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_EQ(rep.sharp_edges, 0);
  // element_size is the target (mean) edge length.
  EXPECT_NEAR(q.mean_edge / h, 1.0, 0.1) << femdem::format_mesh_quality(q);
}

TEST(CadMesh, ScaleConvertsUnits) {
  const fs::path d = tmp_dir("scale");
  write_stl_binary(cube(100.0), d / "cube_mm.stl");  // a 100 mm cube
  const femdem::Tet10Mesh m =
      femdem::mesh_cad_file((d / "cube_mm.stl").string(), options(0.025, 0.001));
  EXPECT_NEAR(mesh_volume(m), 1e-3, 1e-15);
  Vec3 hi = m.nodes[0];
  for (const Vec3& x : m.nodes) hi = hi.cwiseMax(x);
  EXPECT_NEAR(hi.maxCoeff(), 0.1, 1e-15);
}

TEST(CadMesh, SameInputGivesTheSameMeshBitForBit) {
  const fs::path d = tmp_dir("determinism");
  write_stl_binary(icosphere(3), d / "s.stl");
  const auto a = femdem::mesh_cad_file((d / "s.stl").string(), options(0.3));
  const auto b = femdem::mesh_cad_file((d / "s.stl").string(), options(0.3));
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.elements.size(), b.elements.size());
  EXPECT_TRUE(a.elements == b.elements);
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(Vec3)), 0);
}

TEST(CadMesh, MeshRoundTripsThroughMsh) {
  const fs::path d = tmp_dir("roundtrip");
  write_stl_binary(icosphere(2), d / "s.stl");
  const auto m = femdem::mesh_cad_file((d / "s.stl").string(), options(0.4));
  femdem::write_gmsh(m, (d / "s.msh").string());
  const auto r = femdem::read_gmsh((d / "s.msh").string());
  EXPECT_TRUE(r.elements == m.elements);
  ASSERT_EQ(r.nodes.size(), m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) EXPECT_EQ(r.nodes[i], m.nodes[i]);
}

TEST(CadMesh, InvertedAndInconsistentSurfacesAreRepairedOrRefused) {
  // Inside out: every triangle reversed.
  TriangleSurface inv = cube();
  for (Tri& t : inv.triangles) std::swap(t[1], t[2]);
  femdem::CadMeshReport rep;
  auto m = femdem::mesh_surface(inv, options(0.5), "inv", &rep);
  EXPECT_NEAR(mesh_volume(m), 1.0, 1e-12);
  ASSERT_EQ(rep.repairs.size(), 1u);
  EXPECT_TRUE(contains(rep.repairs[0], "inside out")) << rep.repairs[0];

  // Inconsistent: three triangles reversed.
  TriangleSurface mixed = cube();
  for (int i : {0, 5, 9}) std::swap(mixed.triangles[i][1], mixed.triangles[i][2]);
  m = femdem::mesh_surface(mixed, options(0.5), "mixed", &rep);
  EXPECT_NEAR(mesh_volume(m), 1.0, 1e-12);
  EXPECT_TRUE(contains(rep.repairs.at(0), "orientation consistent")) << rep.repairs[0];

  auto strict = options(0.5);
  strict.repair = false;
  try {
    femdem::mesh_surface(inv, strict, "inv");
    FAIL();
  } catch (const femdem::InputError& e) {
    EXPECT_TRUE(contains(e.what(), "inside out")) << e.what();
  }
  try {
    femdem::mesh_surface(mixed, strict, "mixed");
    FAIL();
  } catch (const femdem::InputError& e) {
    EXPECT_TRUE(contains(e.what(), "orientation is inconsistent")) << e.what();
  }
}

TEST(CadMesh, NestedShellsMeshTheSpaceBetweenThem) {
  // A hollow cube: outer [0, 3]^3, inner [1, 2]^3, both given outward (as a careless exporter
  // would): the orientation repair turns the inner one's 12 triangles inwards.
  TriangleSurface s = cube(3.0);
  const TriangleSurface inner = cube(1.0, Vec3(1, 1, 1));
  const auto off = static_cast<std::int32_t>(s.points.size());
  s.points.insert(s.points.end(), inner.points.begin(), inner.points.end());
  for (Tri t : inner.triangles) s.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  femdem::CadMeshReport rep;
  const auto m = femdem::mesh_surface(s, options(0.5), "hollow", &rep);
  EXPECT_EQ(rep.components, 2);
  EXPECT_NEAR(rep.surface_volume, 26.0, 1e-12);
  ASSERT_EQ(rep.repairs.size(), 1u);
  EXPECT_TRUE(contains(rep.repairs[0], "reversed 12 triangle(s) of nested shells"))
      << rep.repairs[0];
  EXPECT_NEAR(mesh_volume(m), 26.0, 1e-9);
}

TEST(CadMesh, Sha256MatchesTheStandardVectors) {
  EXPECT_EQ(femdem::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(femdem::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(femdem::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(femdem::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// ---------------------------------------------------------------------------------------------
// Scenes and the cache

std::string cad_scene(const std::string& mesh) {
  return R"(title = "CAD scene"
[simulation]
end_time = 1e-4

[[materials]]
name = "steel"
model = "elastic"
density = 8000
youngs_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "part"
material = "steel"
mesh = )" +
         mesh + "\n";
}

struct CacheEnv {
  explicit CacheEnv(const fs::path& dir) { setenv("FEMDEM_MESH_CACHE", dir.c_str(), 1); }
  ~CacheEnv() { unsetenv("FEMDEM_MESH_CACHE"); }
};

TEST(CadMesh, SceneMeshesOnLoadAndTheSecondLoadHitsTheCache) {
  const fs::path d = tmp_dir("scene");
  fs::create_directories(d / "meshes");
  write_stl_binary(cube(250.0), d / "meshes" / "cube.stl");  // mm
  std::ofstream(d / "scene.toml") << cad_scene(
      R"({ file = "meshes/cube.stl", element_size = 0.1, scale = 0.001 })");
  CacheEnv env(d / "cache");
  const femdem::SceneFile first = femdem::load_scene((d / "scene.toml").string());
  ASSERT_EQ(first.notes.size(), 1u);
  EXPECT_TRUE(contains(first.notes[0], "mesh cache miss")) << first.notes[0];
  EXPECT_NEAR(mesh_volume(first.model.bodies[0].mesh), 0.25 * 0.25 * 0.25, 1e-15);
  EXPECT_TRUE(contains(first.resolved_toml, "scale = 0.001")) << first.resolved_toml;

  const femdem::SceneFile second = femdem::load_scene((d / "scene.toml").string());
  ASSERT_EQ(second.notes.size(), 1u);
  EXPECT_TRUE(contains(second.notes[0], "mesh cache hit")) << second.notes[0];
  EXPECT_TRUE(first.model.bodies[0].mesh.elements == second.model.bodies[0].mesh.elements);
  EXPECT_TRUE(first.model.bodies[0].mesh.nodes == second.model.bodies[0].mesh.nodes);

  // Another element size is another entry.
  const femdem::SceneFile third =
      femdem::load_scene((d / "scene.toml").string(), {"bodies.part.mesh.element_size=0.2"});
  EXPECT_TRUE(contains(third.notes.at(0), "mesh cache miss")) << third.notes[0];
  int entries = 0;
  for (const auto& e : fs::directory_iterator(d / "cache"))
    entries += e.path().extension() == ".msh";
  EXPECT_EQ(entries, 2);
}

TEST(CadMesh, SceneErrorsNameTheFileLineAndKey) {
  const fs::path d = tmp_dir("scene_errors");
  TriangleSurface open = cube();
  open.triangles.pop_back();
  write_stl_binary(open, d / "open.stl");
  std::ofstream(d / "scene.toml") << cad_scene(R"({ file = "open.stl", element_size = 0.1 })");
  CacheEnv env(d / "cache");
  try {
    femdem::load_scene((d / "scene.toml").string());
    FAIL();
  } catch (const femdem::InputError& e) {
    EXPECT_EQ(e.key, "bodies.part.mesh.file");
    EXPECT_EQ(e.line, 15);
    EXPECT_TRUE(contains(e.what(), "surface is open: 3 border edge(s)")) << e.what();
  }
  write_stl_binary(cube(), d / "cube.stl");
  std::ofstream(d / "scene.toml") << cad_scene(R"({ file = "cube.stl", element_size = 1e-4 })");
  try {
    femdem::load_scene((d / "scene.toml").string());
    FAIL();
  } catch (const femdem::InputError& e) {
    EXPECT_EQ(e.key, "bodies.part.mesh.element_size");
    EXPECT_TRUE(contains(e.what(), "tetrahedra")) << e.what();
  }
  std::ofstream(d / "scene.toml") << cad_scene(R"({ file = "cube.stl" })");
  try {
    femdem::load_scene((d / "scene.toml").string());
    FAIL();
  } catch (const femdem::InputError& e) {
    EXPECT_EQ(e.key, "bodies.part.mesh.element_size");
  }
}

// ---------------------------------------------------------------------------------------------
// The command line

femdem::test::CommandResult run_femdem(const std::string& args) {
  // Appended piece by piece: GCC 12 gives a false -Wrestrict for "literal" + std::string.
  std::string cmd = "'";
  cmd += FEMDEM_EXE;
  cmd += "' ";
  cmd += args;
  return femdem::test::run_command(cmd);
}

TEST(CadMeshCli, MeshesACubeAndPrintsTheQuality) {
  const fs::path d = tmp_dir("cli_ok");
  write_stl_ascii(cube(), d / "cube.stl");
  const auto r = run_femdem("mesh '" + (d / "cube.stl").string() + "' --size 0.25 -o '" +
                            (d / "out.msh").string() + "'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "tetrahedra")) << r.output;
  EXPECT_TRUE(contains(r.output, "dihedral angles")) << r.output;
  EXPECT_TRUE(contains(r.output, "5 % of elements below")) << r.output;
  const auto m = femdem::read_gmsh((d / "out.msh").string());
  EXPECT_NEAR(mesh_volume(m), 1.0, 1e-12);
  // Default output name: the input's, with .msh.
  const auto r2 = run_femdem("mesh '" + (d / "cube.stl").string() + "' --size 0.5");
  ASSERT_EQ(r2.code, 0) << r2.output;
  EXPECT_TRUE(fs::exists(d / "cube.msh"));
  // --scale: a 100 mm cube.
  write_stl_binary(cube(100.0), d / "cube_mm.stl");
  const auto r3 = run_femdem("mesh '" + (d / "cube_mm.stl").string() +
                             "' --size 0.05 --scale 0.001 -o '" + (d / "mm.msh").string() + "'");
  ASSERT_EQ(r3.code, 0) << r3.output;
  EXPECT_NEAR(mesh_volume(femdem::read_gmsh((d / "mm.msh").string())), 1e-3, 1e-15);
}

struct BadCase {
  std::string name;
  std::string expected;  // in the message
  std::string extra_args = {};
};

TEST(CadMeshCli, BrokenSurfacesExitWithCode2AndSayWhatAndWhere) {
  const fs::path d = tmp_dir("cli_bad");
  TriangleSurface open = cube();
  open.triangles.pop_back();
  write_stl_binary(open, d / "open.stl");

  TriangleSurface inv = cube();
  for (Tri& t : inv.triangles) std::swap(t[1], t[2]);
  write_stl_binary(inv, d / "inverted.stl");

  TriangleSurface mixed = cube();
  std::swap(mixed.triangles[3][1], mixed.triangles[3][2]);
  write_obj(mixed, d / "inconsistent.obj");

  // Two cubes overlapping: each closed, together self-intersecting.
  TriangleSurface two = cube();
  const TriangleSurface other = cube(1.0, Vec3(0.5, 0.5, 0.5));
  two.points.insert(two.points.end(), other.points.begin(), other.points.end());
  for (Tri t : other.triangles) two.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  write_stl_binary(two, d / "self_intersecting.stl");

  // Two cubes sharing an edge: four triangles on one edge.
  TriangleSurface edge = cube();
  const TriangleSurface diag = cube(1.0, Vec3(1, 1, 0));
  edge.points.insert(edge.points.end(), diag.points.begin(), diag.points.end());
  for (Tri t : diag.triangles) edge.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  write_stl_ascii(edge, d / "non_manifold.stl");

  std::ofstream(d / "empty.stl") << "solid empty\nendsolid empty\n";
  std::ofstream(d / "empty.obj") << "# nothing here\n";
  std::ofstream(d / "text.stl") << "This is a shopping list, not a mesh.\n";
  std::ofstream(d / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

  const std::vector<BadCase> cases = {
      {"open.stl", "surface is open: 3 border edge(s), first near ("},
      {"inverted.stl", "inside out", "--no-repair"},
      {"inconsistent.obj", "orientation is inconsistent: 3 edge(s)", "--no-repair"},
      {"self_intersecting.stl", "pair(s) of self-intersecting faces, first input triangles "},
      {"non_manifold.stl", "not manifold: 1 edge(s) shared by more than two triangles"},
      {"empty.stl", "empty: no triangles"},
      {"empty.obj", "not a mesh: assimp says"},
      {"points.obj", "empty: no triangles"},
      {"text.stl", "not a mesh: assimp says"},
      {"missing.stl", "does not exist"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path out = d / (c.name + ".msh");
    const auto r = run_femdem("mesh '" + (d / c.name).string() + "' --size 0.25 -o '" +
                              out.string() + "' " + c.extra_args);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_TRUE(contains(r.output, c.expected)) << r.output;
    EXPECT_TRUE(contains(r.output, c.name)) << r.output;  // the message names the file
    EXPECT_FALSE(fs::exists(out)) << "no output on failure";
  }
  // The repairable ones mesh without --no-repair.
  for (const char* name : {"inverted.stl", "inconsistent.obj"}) {
    const auto r = run_femdem("mesh '" + (d / name).string() + "' --size 0.5 -o '" +
                              (d / "repaired.msh").string() + "'");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "repaired: ")) << r.output;
  }
  // A size that would need too many elements.
  write_stl_binary(cube(), d / "cube.stl");
  const auto r = run_femdem("mesh '" + (d / "cube.stl").string() + "' --size 1e-4 -o '" +
                            (d / "tiny.msh").string() + "'");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "element_size")) << r.output;
}

}  // namespace
