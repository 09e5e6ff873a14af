// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/mesh/gmsh_io.hpp"
#include "io/mesh/mesh_generators.hpp"

using namespace femdem;

namespace {

std::string tmp_path(const std::string& name) {
  std::filesystem::create_directories(FEMDEM_TEST_TMP);
  return std::string(FEMDEM_TEST_TMP) + "/gmsh_io_" + name;
}

std::string data_path(const std::string& name) {
  return std::string(FEMDEM_SOURCE_DIR) + "/tests/data/" + name;
}

std::string write_lines(const std::string& name, const std::vector<std::string>& lines) {
  const std::string p = tmp_path(name);
  std::ofstream out(p, std::ios::binary);
  for (const auto& l : lines) out << l << '\n';
  return p;
}

// Reads path and expects an InputError on `line` whose message contains `text`.
void expect_error(const std::string& path, int line, const std::string& text) {
  try {
    read_gmsh(path);
    FAIL() << "no InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, line) << e.describe();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos)
        << "message: " << e.describe() << "\nexpected to contain: " << text;
  }
}

// Every mid-edge node is at the midpoint of its edge (straight elements), in OUR order.
void expect_straight_midpoints(const Tet10Mesh& m) {
  for (const Tet10& el : m.elements)
    for (int k = 0; k < 6; ++k) {
      const Vec3 mid = 0.5 * (m.nodes[el[kTet10Edges[k][0]]] + m.nodes[el[kTet10Edges[k][1]]]);
      EXPECT_LT((m.nodes[el[4 + k]] - mid).norm(), 1e-14) << "edge " << k;
    }
}

double total_volume(const Tet10Mesh& m) {
  double v = 0.0;
  for (std::size_t e = 0; e < m.elements.size(); ++e) v += tet10_volume(m, e);
  return v;
}

// A valid two-element TET4 file in format 2.2 (lines numbered from 1).
std::vector<std::string> tet4_v22() {
  return {"$MeshFormat",  // 1
          "2.2 0 8",      // 2
          "$EndMeshFormat",
          "$Nodes",  // 4
          "5",
          "10 0 0 0",  // 6
          "20 1 0 0",
          "30 0 1 0",
          "40 0 0 1",
          "50 1 1 1",  // 10
          "$EndNodes",
          "$Elements",  // 12
          "3",
          "1 2 2 0 1 10 20 30",  // 14
          "2 4 2 0 1 10 20 30 40",
          "3 4 2 0 1 20 30 40 50",  // 16
          "$EndElements"};
}

}  // namespace

TEST(GmshIo, ReadsHandWrittenV22Tet4AndPromotes) {
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(data_path("cube_tet4_v22.msh"), &info);
  EXPECT_EQ(info.version, "2.2");
  EXPECT_EQ(info.tet4, 5);
  EXPECT_EQ(info.tet10, 0);
  EXPECT_EQ(info.ignored_elements, 4);
  EXPECT_EQ(info.unused_nodes, 1);  // tag 999
  EXPECT_FALSE(info.flipped);
  ASSERT_EQ(m.elements.size(), 5u);
  // 8 corners + 12 cube edges + 6 face diagonals (5-tet split of a cube).
  EXPECT_EQ(m.nodes.size(), 26u);
  expect_straight_midpoints(m);
  EXPECT_NEAR(total_volume(m), 1.0, 1e-14);
  EXPECT_EQ(mesh_quality(m).bad_elements, 0);
  // No duplicate nodes.
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (std::size_t j = i + 1; j < m.nodes.size(); ++j)
      EXPECT_GT((m.nodes[i] - m.nodes[j]).norm(), 1e-9);
}

TEST(GmshIo, ReadsHandWrittenV41Tet10WithGmshOrder) {
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(data_path("two_tet10_v41.msh"), &info);
  EXPECT_EQ(info.version, "4.1");
  EXPECT_EQ(info.tet10, 2);
  EXPECT_EQ(info.ignored_elements, 1);
  ASSERT_EQ(m.elements.size(), 2u);
  EXPECT_EQ(m.nodes.size(), 14u);
  // Fails if gmsh's 8/9 (edges 2-3, 1-3) were not swapped into our 8/9 (edges 1-3, 2-3).
  expect_straight_midpoints(m);
  EXPECT_NEAR(total_volume(m), 0.5, 1e-14);
  // Node order follows the file: the first corner is tag 1 at the origin.
  EXPECT_EQ(m.nodes[0], Vec3(0, 0, 0));
  EXPECT_EQ(m.nodes[4], Vec3(1, 1, 1));
}

TEST(GmshIo, RoundTripIsExact) {
  for (const Tet10Mesh& m : {generate_sphere(0.7, 0.2), generate_cylinder(0.3, 1.1, 0.1)}) {
    const std::string p = tmp_path("roundtrip.msh");
    write_gmsh(m, p);
    GmshReadInfo info;
    const Tet10Mesh r = read_gmsh(p, &info);
    EXPECT_EQ(info.version, "4.1");
    EXPECT_FALSE(info.flipped);
    ASSERT_EQ(r.nodes.size(), m.nodes.size());
    ASSERT_EQ(r.elements.size(), m.elements.size());
    for (std::size_t i = 0; i < m.nodes.size(); ++i) ASSERT_EQ(r.nodes[i], m.nodes[i]) << i;
    for (std::size_t e = 0; e < m.elements.size(); ++e)
      ASSERT_EQ(r.elements[e], m.elements[e]) << e;
  }
}

TEST(GmshIo, AllInvertedAreFlipped) {
  Tet10Mesh m = generate_box(Vec3(1, 1, 1), 0.5);
  const double v0 = total_volume(m);
  for (Tet10& el : m.elements) {
    std::swap(el[1], el[2]);
    std::swap(el[4], el[6]);
    std::swap(el[8], el[9]);
  }
  const std::string p = tmp_path("inverted.msh");
  write_gmsh(m, p);
  GmshReadInfo info;
  const Tet10Mesh r = read_gmsh(p, &info);
  EXPECT_TRUE(info.flipped);
  EXPECT_FALSE(info.notes.empty());
  const MeshQuality q = mesh_quality(r);
  EXPECT_EQ(q.bad_elements, 0);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_NEAR(total_volume(r), v0, 1e-14);
  expect_straight_midpoints(r);
}

TEST(GmshIo, SomeInvertedIsAnErrorNamingTheElement) {
  Tet10Mesh m = generate_box(Vec3(1, 1, 1), 0.5);
  Tet10& el = m.elements[5];
  std::swap(el[1], el[2]);
  std::swap(el[4], el[6]);
  std::swap(el[8], el[9]);
  const std::string p = tmp_path("one_inverted.msh");
  write_gmsh(m, p);
  // Header: 7 lines of format + entities, $Nodes, 2 header lines, N tags, N coordinates,
  // $EndNodes, $Elements, 2 header lines; element tag 6 is the 6th element line.
  const int line = 7 + 1 + 2 + 2 * static_cast<int>(m.nodes.size()) + 1 + 1 + 2 + 6;
  expect_error(p, line, "element 6 is inverted");
}

TEST(GmshIo, DegenerateElementIsAnError) {
  auto lines = tet4_v22();
  // Node 40 into the plane z = 0 of nodes 10 20 30: element 2 (line 15) becomes flat while
  // element 3 (20 30 40 50) stays valid.
  lines[8] = "40 0.3 0.3 0";
  expect_error(write_lines("degenerate.msh", lines), 15, "element 2 is degenerate");
}

TEST(GmshIo, FoldedTet10IsAnError) {
  Tet10Mesh m = generate_box(Vec3(1, 1, 1), 1.0);
  // Pull a mid-edge node of element 0 far beyond the opposite face.
  const Tet10& el = m.elements[0];
  m.nodes[el[4]] += 3.0 * (m.nodes[el[3]] - m.nodes[el[4]]);
  const std::string p = tmp_path("folded.msh");
  write_gmsh(m, p);
  try {
    read_gmsh(p);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("folded"), std::string::npos) << e.describe();
  }
}

TEST(GmshIo, ValidV22Fixture) {
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(write_lines("valid22.msh", tet4_v22()), &info);
  EXPECT_EQ(m.elements.size(), 2u);
  EXPECT_EQ(m.nodes.size(), 5u + 9u);  // 6 + 6 edges, 3 shared
  EXPECT_EQ(info.ignored_elements, 1);
}

TEST(GmshIo, MalformedFilesNameTheLine) {
  auto base = tet4_v22();
  {
    auto l = base;
    l[1] = "2.2 1 8";
    expect_error(write_lines("binary.msh", l), 2, "binary");
  }
  {
    auto l = base;
    l[1] = "4.0 0 8";
    expect_error(write_lines("v40.msh", l), 2, "unsupported MSH version '4.0'");
  }
  {
    auto l = base;
    l[1] = "3 0 8";
    expect_error(write_lines("v3.msh", l), 2, "unsupported MSH version");
  }
  {
    auto l = base;
    l[0] = "solid cube";
    expect_error(write_lines("notmsh.msh", l), 1, "not a gmsh MSH file");
  }
  {
    auto l = base;
    l[6] = "20 1 zero 0";
    expect_error(write_lines("nonnumeric.msh", l), 7, "'zero'");
    try {
      read_gmsh(tmp_path("nonnumeric.msh"));
    } catch (const InputError& e) {
      EXPECT_EQ(e.column, 6);
    }
  }
  {
    auto l = base;
    l[15] = "3 4 2 0 1 20 30 40 77";
    expect_error(write_lines("dangling.msh", l), 16, "node tag 77");
  }
  {
    auto l = base;
    l[14] = "2 4 2 0 1 10 20 30";
    expect_error(write_lines("short_element.msh", l), 15, "missing node tag");
  }
  {
    auto l = base;
    l[14] = "2 4 2 0 1 10 20 30 40 50";
    expect_error(write_lines("long_element.msh", l), 15, "extra data");
  }
  {
    // Truncated in the middle of the node list: the first missing line is named.
    std::vector<std::string> l(base.begin(), base.begin() + 8);
    expect_error(write_lines("truncated_nodes.msh", l), 9, "unexpected end of file");
  }
  {
    std::vector<std::string> l(base.begin(), base.begin() + 15);
    expect_error(write_lines("truncated_elements.msh", l), 16, "unexpected end of file");
  }
  {
    // No tetrahedra: only the triangle.
    auto l = base;
    l.erase(l.begin() + 14, l.begin() + 16);
    l[12] = "1";
    expect_error(write_lines("no_tets.msh", l), 12, "no tetrahedra");
  }
  {
    auto l = base;
    l.insert(l.begin() + 3, "$Comments");
    expect_error(write_lines("unclosed_section.msh", l), static_cast<int>(l.size()) + 1,
                 "$Comments");
  }
  {
    auto l = base;
    l[4] = "6";  // one node more than listed: $EndNodes is read as a node
    expect_error(write_lines("count_mismatch.msh", l), 11, "expected an integer node tag");
  }
  {
    auto l = base;
    l[5] = "20 1 0 0";  // duplicate tag
    expect_error(write_lines("duplicate_tag.msh", l), 4, "node tag 20 is defined twice");
  }
  {
    auto l = base;
    l[7] = "30 0 1 nan";
    expect_error(write_lines("nan.msh", l), 8, "finite");
  }
  {
    const std::string p = tmp_path("empty.msh");
    std::ofstream(p).close();
    expect_error(p, 1, "empty");
  }
  try {
    read_gmsh(tmp_path("does_not_exist.msh"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, tmp_path("does_not_exist.msh"));
  }
}

TEST(GmshIo, MalformedV41) {
  const auto good = [] {
    std::ifstream in(data_path("two_tet10_v41.msh"));
    std::vector<std::string> l;
    for (std::string s; std::getline(in, s);) l.push_back(s);
    return l;
  }();
  ASSERT_EQ(good[8], "2 14 1 124");
  read_gmsh(write_lines("good41.msh", good));
  {
    auto l = good;
    l[8] = "2 15 1 124";  // more nodes announced than the blocks hold
    expect_error(write_lines("count41.msh", l), 40, "announced 15 nodes");
  }
  {
    auto l = good;
    l[9] = "0 3 0 6";  // block claims 6 nodes: the 6th tag line is a coordinate line
    expect_error(write_lines("block41.msh", l), 16, "extra data");
  }
  {
    auto l = good;
    l[46] = "21 3 5 7 9 103 112 115 118 121";  // TET10 with 9 nodes
    expect_error(write_lines("short41.msh", l), 47, "missing node tag");
  }
  {
    std::vector<std::string> l(good.begin(), good.begin() + 44);
    expect_error(write_lines("trunc41.msh", l), 45, "unexpected end of file");
  }
}

TEST(GmshIo, MixedTet4AndTet10ShareMidEdgeNodes) {
  auto l = tet4_v22();
  l[4] = "11";
  l.insert(l.begin() + 10, {"60 0.5 0 0", "61 0.5 0.5 0", "62 0 0.5 0", "63 0 0 0.5",
                            "64 0 0.5 0.5", "65 0.5 0 0.5"});
  // Element 2 becomes a TET10 in gmsh order (8: edge 2-3, 9: edge 1-3); element 3 stays TET4
  // and shares the face 20 30 40 with it.
  l[14 + 6] = "2 11 2 0 1 10 20 30 40 60 61 62 63 64 65";
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(write_lines("mixed.msh", l), &info);
  EXPECT_EQ(info.tet4, 1);
  EXPECT_EQ(info.tet10, 1);
  EXPECT_EQ(m.nodes.size(), 14u);  // 5 corners + 9 edges: the shared face's 3 are reused
  expect_straight_midpoints(m);
}

TEST(GmshIo, V41ParametricNodesAndUnorderedTags) {
  const std::vector<std::string> l = {
      "$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$Nodes",        "2 4 3 900",
      "2 1 1 2",  // surface block with parametric (u, v)
      "900",         "7",       "0 0 0 0.1 0.2",  "1 0 0 0.3 0.4",
      "3 1 0 2",  // volume block
      "3 5",         "0 1 0",   "0 0 1",          "$EndNodes",     "$Elements",
      "1 1 1 1",     "3 1 4 1", "1 900 7 3 5",    "$EndElements"};
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(write_lines("param41.msh", l), &info);
  ASSERT_EQ(m.elements.size(), 1u);
  EXPECT_EQ(m.nodes.size(), 10u);
  EXPECT_NEAR(tet10_volume(m, 0), 1.0 / 6, 1e-15);
  expect_straight_midpoints(m);
}

// ---------------------------------------------------------------------------------------------
// Binary MSH, against the ASCII file gmsh wrote of the same mesh (tests/data/gmsh/two_blocks.geo
// gives the commands): two unit cubes, 201 TET10 in all.

namespace {

std::string gmsh_data(const std::string& name) {
  return data_path("gmsh/" + name);
}

void expect_same_mesh(const Tet10Mesh& a, const Tet10Mesh& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.elements.size(), b.elements.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    // gmsh prints 16 significant digits in ASCII: the binary doubles agree to that
    EXPECT_LT((a.nodes[i] - b.nodes[i]).norm(), 1e-15 * (1.0 + a.nodes[i].norm())) << i;
  for (std::size_t e = 0; e < a.elements.size(); ++e) EXPECT_EQ(a.elements[e], b.elements[e]) << e;
}

}  // namespace

TEST(GmshIo, BinaryFilesReadAsTheirAsciiTwins) {
  for (const char* version : {"41", "22"}) {
    SCOPED_TRACE(version);
    GmshReadInfo ascii_info, binary_info;
    const Tet10Mesh ascii =
        read_gmsh(gmsh_data(std::string("two_blocks_ascii") + version + ".msh"), &ascii_info);
    const Tet10Mesh binary =
        read_gmsh(gmsh_data(std::string("two_blocks_bin") + version + ".msh"), &binary_info);
    // counted in the ASCII files: 101 + 100 type-11 elements, 28 six-node triangles of the two
    // physical surfaces and one point
    EXPECT_EQ(binary_info.tet10, 201);
    EXPECT_EQ(binary_info.tet4, 0);
    EXPECT_EQ(binary_info.ignored_elements, ascii_info.ignored_elements);
    expect_same_mesh(ascii, binary);
    EXPECT_NEAR(total_volume(binary), 2.0, 1e-12);  // two unit cubes
  }
}

TEST(GmshIo, BinaryTet4FilesArePromoted) {
  for (const char* name : {"two_blocks_tet4_bin41.msh", "two_blocks_tet4_bin22.msh"}) {
    SCOPED_TRACE(name);
    GmshReadInfo info;
    const Tet10Mesh m = read_gmsh(gmsh_data(name), &info);
    EXPECT_GT(info.tet4, 0);
    EXPECT_EQ(info.tet10, 0);
    EXPECT_NEAR(total_volume(m), 2.0, 1e-12);
    expect_straight_midpoints(m);
  }
}

TEST(GmshIo, TruncatedOrCorruptBinaryFilesNameTheByte) {
  const std::string whole = [] {
    std::ifstream in(gmsh_data("two_blocks_bin41.msh"), std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }();
  const auto write_bytes = [](const std::string& name, const std::string& bytes) {
    const std::string p = tmp_path(name);
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  };
  const std::size_t nodes = whole.find("$Nodes\n") + 7;
  ASSERT_NE(nodes, std::string::npos + 7);
  // cut in the middle of the node coordinates
  const std::string cut = write_bytes("bin_cut.msh", whole.substr(0, nodes + 600));
  try {
    read_gmsh(cut);
    FAIL() << "no InputError for a truncated binary file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unexpected end of file in binary data"),
              std::string::npos)
        << e.describe();
    EXPECT_NE(std::string(e.what()).find("byte "), std::string::npos) << e.describe();
  }
  // the number of nodes of the $Nodes header (second size_t) one too large: the blocks end
  // before it, where their counts say
  std::string more = whole;
  std::uint64_t total = 0;
  std::memcpy(&total, more.data() + nodes + 8, 8);
  ++total;
  std::memcpy(more.data() + nodes + 8, &total, 8);
  try {
    read_gmsh(write_bytes("bin_count.msh", more));
    FAIL() << "no InputError for a wrong node count";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes but its blocks hold"), std::string::npos)
        << e.describe();
  }
  // the byte-order mark of another machine
  std::string swapped = whole;
  const std::size_t mark = swapped.find("4.1 1 8\n") + 8;
  std::swap(swapped[mark], swapped[mark + 3]);
  try {
    read_gmsh(write_bytes("bin_order.msh", swapped));
    FAIL() << "no InputError for the other byte order";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("other byte order"), std::string::npos) << e.describe();
  }
}

// ---------------------------------------------------------------------------------------------
// Physical groups, in every format gmsh 4.8.4 wrote of two_blocks.geo: the volumes "left" (the
// cube [0,1]^3) and "right" ([2,3] x [0,1]^2), the surfaces "left_bottom" (z = 0 of the left
// cube) and "right_top" (z = 1 of the right one) and the point "left_top_corner" (0, 0, 1).
// Each group is checked against the geometry it was drawn on, not against the reader's output.

namespace {

const GmshPhysicalGroup* find_group(const GmshReadInfo& info, int dim, const std::string& name) {
  for (const GmshPhysicalGroup& g : info.groups)
    if (g.dim == dim && g.name == name) return &g;
  return nullptr;
}

// The mesh nodes that `inside` holds for, sorted.
template <class Pred>
std::vector<std::int32_t> nodes_where(const Tet10Mesh& m, Pred inside) {
  std::vector<std::int32_t> out;
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    if (inside(m.nodes[n])) out.push_back(static_cast<std::int32_t>(n));
  return out;
}

}  // namespace

TEST(GmshIo, PhysicalGroupsMatchTheGeometryTheyWereDrawnOn) {
  constexpr double eps = 1e-9;
  for (const char* name :
       {"two_blocks_ascii41.msh", "two_blocks_bin41.msh", "two_blocks_ascii22.msh",
        "two_blocks_bin22.msh", "two_blocks_tet4_bin41.msh", "two_blocks_tet4_bin22.msh"}) {
    SCOPED_TRACE(name);
    GmshReadInfo info;
    const Tet10Mesh m = read_gmsh(gmsh_data(name), &info);
    ASSERT_EQ(info.groups.size(), 5u);
    const GmshPhysicalGroup* left = find_group(info, 3, "left");
    const GmshPhysicalGroup* right = find_group(info, 3, "right");
    ASSERT_TRUE(left && right);
    EXPECT_EQ(left->elements.size() + right->elements.size(), m.elements.size());
    for (const auto& [g, x0] : {std::pair{left, 0.0}, std::pair{right, 2.0}}) {
      double volume = 0.0;
      for (std::int32_t e : g->elements) {
        volume += tet10_volume(m, static_cast<std::size_t>(e));
        for (std::int32_t n : m.elements[static_cast<std::size_t>(e)]) {
          EXPECT_GE(m.nodes[static_cast<std::size_t>(n)].x(), x0 - eps);
          EXPECT_LE(m.nodes[static_cast<std::size_t>(n)].x(), x0 + 1 + eps);
        }
      }
      EXPECT_NEAR(volume, 1.0, 1e-12);
    }
    const GmshPhysicalGroup* bottom = find_group(info, 2, "left_bottom");
    const GmshPhysicalGroup* top = find_group(info, 2, "right_top");
    const GmshPhysicalGroup* corner = find_group(info, 0, "left_top_corner");
    ASSERT_TRUE(bottom && top && corner);
    // every node on the face, mid-edge nodes included (those a TET4 promotion adds too)
    EXPECT_EQ(bottom->nodes, nodes_where(m, [&](const Vec3& p) {
                return std::abs(p.z()) < eps && p.x() < 1 + eps;
              }));
    EXPECT_EQ(top->nodes, nodes_where(m, [&](const Vec3& p) {
                return std::abs(p.z() - 1) < eps && p.x() > 2 - eps;
              }));
    EXPECT_EQ(corner->nodes,
              nodes_where(m, [&](const Vec3& p) { return (p - Vec3(0, 0, 1)).norm() < eps; }));
    EXPECT_EQ(corner->nodes.size(), 1u);
    EXPECT_GE(bottom->nodes.size(), 9u);  // at least a 2 x 2 grid of six-node triangles
  }
}

TEST(GmshIo, APhysicalVolumeIsABodyWithTheNodeSetsItTouches) {
  GmshReadInfo info;
  Tet10Mesh m = read_gmsh(gmsh_data("two_blocks_bin41.msh"), &info);
  const GmshBody left = gmsh_body(m, info, "left");
  EXPECT_NEAR(total_volume(left.mesh), 1.0, 1e-12);
  EXPECT_EQ(left.mesh.elements.size(), find_group(info, 3, "left")->elements.size());
  for (const Vec3& p : left.mesh.nodes) EXPECT_LE(p.x(), 1 + 1e-9);
  for (const Tet10& e : left.mesh.elements)
    for (std::int32_t n : e) EXPECT_LT(static_cast<std::size_t>(n), left.mesh.nodes.size());
  std::map<std::string, std::vector<std::int32_t>> sets(left.node_sets.begin(),
                                                        left.node_sets.end());
  ASSERT_EQ(sets.size(), 2u);  // right_top has no node in the left cube
  for (std::int32_t n : sets.at("left_bottom"))
    EXPECT_NEAR(left.mesh.nodes[static_cast<std::size_t>(n)].z(), 0.0, 1e-12);
  EXPECT_EQ(sets.at("left_bottom").size(), find_group(info, 2, "left_bottom")->nodes.size());
  ASSERT_EQ(sets.at("left_top_corner").size(), 1u);
  EXPECT_LT(
      (left.mesh.nodes[static_cast<std::size_t>(sets.at("left_top_corner")[0])] - Vec3(0, 0, 1))
          .norm(),
      1e-12);
  const GmshBody whole = gmsh_body(m, info, "");
  EXPECT_EQ(whole.mesh.elements.size(), m.elements.size());
  EXPECT_EQ(whole.node_sets.size(), 3u);
  EXPECT_THROW(gmsh_body(m, info, "middle"), std::invalid_argument);
}

TEST(GmshIo, WrittenPhysicalVolumeReadsBack) {
  GmshReadInfo info;
  const Tet10Mesh m = read_gmsh(gmsh_data("two_blocks_ascii41.msh"));
  const std::string p = tmp_path("named_volume.msh");
  write_gmsh(m, p, "block");
  const Tet10Mesh back = read_gmsh(p, &info);
  EXPECT_EQ(back.elements, m.elements);
  ASSERT_EQ(info.groups.size(), 1u);
  EXPECT_EQ(info.groups[0].dim, 3);
  EXPECT_EQ(info.groups[0].name, "block");
  EXPECT_EQ(info.groups[0].elements.size(), m.elements.size());
}
