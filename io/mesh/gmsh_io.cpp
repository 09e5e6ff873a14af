// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/mesh/gmsh_io.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

#include "elements/tet_geometry.hpp"
#include "engine/errors.hpp"
#include "io/atomic_file.hpp"

namespace femdem {

namespace {

// gmsh TET10 node i is our node kGmshToOurs[i] (and vice versa: the permutation is an
// involution). gmsh: 4 edge 0-1, 5 edge 1-2, 6 edge 2-0, 7 edge 0-3, 8 edge 2-3, 9 edge 1-3.
constexpr std::array<int, 10> kGmshToOurs = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

constexpr int kTypeTet4 = 4;
constexpr int kTypeTet10 = 11;

// ---------------------------------------------------------------------------------------------
// Line-oriented reading with positions for error messages.

class Reader {
 public:
  Reader(std::string path, std::string data) : path_(std::move(path)), data_(std::move(data)) {}

  // Next line (without the end-of-line), false at end of file.
  bool next_line() {
    if (pos_ >= data_.size()) return false;
    std::size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) end = data_.size();
    line_ = std::string_view(data_).substr(pos_, end - pos_);
    if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
    pos_ = end + 1;
    ++line_no_;
    tok_ = 0;
    return true;
  }

  // Next line or an error saying what was expected there.
  void require_line(const std::string& what) {
    if (!next_line()) fail_eof(what);
  }

  // Next non-blank line, false at end of file.
  bool next_nonblank_line() {
    while (next_line())
      if (!trimmed().empty()) return true;
    return false;
  }

  std::string_view line() const { return line_; }
  std::string_view trimmed() const {
    std::string_view s = line_;
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
  }
  int line_no() const { return line_no_; }
  const std::string& path() const { return path_; }

  // Next whitespace-separated token of the current line; empty at its end. column() is the
  // 1-based column of the token last returned.
  std::string_view token() {
    while (tok_ < line_.size() && (line_[tok_] == ' ' || line_[tok_] == '\t')) ++tok_;
    const std::size_t start = tok_;
    while (tok_ < line_.size() && line_[tok_] != ' ' && line_[tok_] != '\t') ++tok_;
    col_ = static_cast<int>(start) + 1;
    return line_.substr(start, tok_ - start);
  }
  bool has_more_tokens() {
    std::size_t p = tok_;
    while (p < line_.size() && (line_[p] == ' ' || line_[p] == '\t')) ++p;
    return p < line_.size();
  }

  std::int64_t integer(const char* what) {
    const std::string_view t = token();
    if (t.empty()) fail(std::string("missing ") + what, col_);
    std::int64_t v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(std::string("expected an integer ") + what + ", got '" + std::string(t) + "'", col_);
    return v;
  }
  std::int64_t count(const char* what) {
    const std::int64_t v = integer(what);
    if (v < 0) fail(std::string(what) + " must not be negative", col_);
    return v;
  }
  double real(const char* what) {
    const std::string_view t = token();
    if (t.empty()) fail(std::string("missing ") + what, col_);
    double v = 0.0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(v))
      fail(std::string("expected a finite number ") + what + ", got '" + std::string(t) + "'",
           col_);
    return v;
  }
  // An integer that may continue on the following lines (node tag lists).
  std::int64_t integer_any_line(const char* what, const std::string& section) {
    while (!has_more_tokens()) require_line(what + std::string(" in ") + section);
    return integer(what);
  }

  void expect_end_of_line() {
    if (has_more_tokens()) {
      const std::string_view t = token();
      fail("unexpected extra data '" + std::string(t) + "'", col_);
    }
  }
  void expect_exact(std::string_view keyword) {
    if (trimmed() != keyword)
      fail("expected " + std::string(keyword) + ", got '" + std::string(trimmed()) + "'");
  }

  // Binary data (binary MSH files): the next sizeof(T) bytes as a T, in the machine's byte order
  // (read_gmsh checks the file's against it). Line numbers count the text lines read so far;
  // a problem in binary data names the byte offset too.
  template <class T>
  T binary(const char* what) {
    if (data_.size() - std::min(pos_, data_.size()) < sizeof(T))
      fail_binary(std::string("unexpected end of file in binary data: expected ") + what +
                  " (truncated file?)");
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  // A size_t of binary data (MSH 4.1 counts and tags) as a non-negative int64.
  std::int64_t binary_size(const char* what) {
    const auto v = binary<std::uint64_t>(what);
    if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      fail_binary(std::string(what) + " is out of range");
    return static_cast<std::int64_t>(v);
  }
  // An int of binary data that must not be negative (MSH 2 counts).
  std::int64_t binary_count(const char* what) {
    const auto v = binary<std::int32_t>(what);
    if (v < 0) fail_binary(std::string(what) + " must not be negative");
    return v;
  }
  double binary_real(const char* what) {
    const double v = binary<double>(what);
    if (!std::isfinite(v)) fail_binary(std::string("expected a finite number ") + what);
    return v;
  }
  // The end of a section's binary data: the line break before its end marker.
  void end_binary(const char* section) {
    if (pos_ >= data_.size() || data_[pos_] != '\n')
      fail_binary(std::string("the binary data of ") + section +
                  " does not end where its counts say (a line break was expected)");
    ++pos_;
  }
  [[noreturn]] void fail_binary(const std::string& msg) const {
    throw InputError(msg + " (binary data, byte " + std::to_string(pos_) + ")", path_, line_no_);
  }

  [[noreturn]] void fail(const std::string& msg, int column = 0) const {
    throw InputError(msg, path_, line_no_, column);
  }
  [[noreturn]] void fail_at(const std::string& msg, int line) const {
    throw InputError(msg, path_, line);
  }
  [[noreturn]] void fail_eof(const std::string& what) const {
    throw InputError("unexpected end of file: expected " + what + " (truncated file?)", path_,
                     line_no_ + 1);
  }

 private:
  std::string path_;
  std::string data_;
  std::size_t pos_ = 0;
  std::string_view line_;
  int line_no_ = 0;
  std::size_t tok_ = 0;
  int col_ = 0;
};

// The number of nodes of a gmsh element type, 0 when unknown: binary element data can only be
// stepped over when it is known. Types 1-31 and the few higher-order ones gmsh writes by
// default for orders up to 4 (gmsh's GmshDefines.h lists them).
int element_type_nodes(std::int64_t type) {
  static constexpr std::array<int, 32> kNodes = {0,  2,  3,  4,  4, 8, 6,  5,  3,  6, 9,
                                                 10, 27, 18, 14, 1, 8, 20, 15, 13, 9, 10,
                                                 12, 15, 15, 21, 4, 5, 6,  20, 35, 56};
  if (type >= 0 && type < static_cast<std::int64_t>(kNodes.size()))
    return kNodes[static_cast<std::size_t>(type)];
  switch (type) {
    case 92:
      return 64;  // hexahedron of order 3
    case 93:
      return 125;  // hexahedron of order 4
    default:
      return 0;
  }
}

// The dimension of a gmsh element type's shape (0 point, 1 line, 2 surface, 3 volume).
int element_type_dim(std::int64_t type) {
  switch (type) {
    case 15:
      return 0;
    case 1:
    case 8:
    case 26:
    case 27:
    case 28:
      return 1;
    case 2:
    case 3:
    case 9:
    case 10:
    case 16:
    case 20:
    case 21:
    case 22:
    case 23:
    case 24:
    case 25:
      return 2;
    default:
      return 3;
  }
}

struct RawElement {
  std::int64_t tag;
  int line;
  int nodes;                       // 4 or 10
  std::array<std::int64_t, 10> n;  // node TAGS, gmsh order
  std::int64_t group_key = 0;      // MSH 4.1: its volume entity's tag; MSH 2: its physical tag
};

using DimTag = std::pair<int, std::int64_t>;

// Physical groups as the file gives them, resolved to mesh nodes and elements in assemble().
struct RawGroups {
  std::map<DimTag, std::vector<std::int64_t>> entity_physicals;  // MSH 4.1 $Entities
  std::map<DimTag, std::string> names;                           // $PhysicalNames
  // per (dim < 3, physical tag): the node tags of its elements, and the corner pairs of its
  // linear lines, triangles and quadrangles (whose mid-edge nodes a TET4 promotion adds)
  std::map<DimTag, std::vector<std::int64_t>> node_tags;
  std::map<DimTag, std::vector<std::array<std::int64_t, 2>>> edges;

  // The physical tags of an element: its entity's (MSH 4.1) or its own (MSH 2, 0 = none).
  std::vector<std::int64_t> physicals(bool v2, int dim, std::int64_t key) const {
    if (v2) return key != 0 ? std::vector<std::int64_t>{key} : std::vector<std::int64_t>{};
    const auto it = entity_physicals.find({dim, key});
    return it == entity_physicals.end() ? std::vector<std::int64_t>{} : it->second;
  }
  // Records a lower-dimensional element of the groups `phys` (node tags in gmsh order).
  void add_element(int dim, std::int64_t type, const std::vector<std::int64_t>& phys,
                   const std::int64_t* tags, int count) {
    static constexpr int kLine[2][2] = {{0, 1}, {1, 0}};
    static constexpr int kTri[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    static constexpr int kQuad[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    for (std::int64_t p : phys) {
      auto& nodes = node_tags[{dim, p}];
      nodes.insert(nodes.end(), tags, tags + count);
      auto& e = edges[{dim, p}];
      const int(*pairs)[2] = type == 1 ? kLine : type == 2 ? kTri : type == 3 ? kQuad : nullptr;
      const int n = type == 1 ? 1 : type == 2 ? 3 : type == 3 ? 4 : 0;
      for (int i = 0; i < n; ++i) e.push_back({tags[pairs[i][0]], tags[pairs[i][1]]});
    }
  }
};

struct RawMesh {
  std::vector<std::int64_t> node_tags;
  std::vector<Vec3> coords;
  int nodes_line = 0;  // line of $Nodes
  bool have_nodes = false;
  std::vector<RawElement> tets;
  int elements_line = 0;  // line of $Elements
  bool have_elements = false;
  std::int64_t ignored = 0;
  bool v2 = false;
  RawGroups groups;
};

// Reads the node list of a tetrahedron from the current line into e.
void read_tet_nodes(Reader& r, int type, RawElement& e) {
  e.nodes = type == kTypeTet4 ? 4 : 10;
  for (int i = 0; i < e.nodes; ++i) e.n[i] = r.integer("node tag of the tetrahedron");
  r.expect_end_of_line();
}

void read_nodes_v2(Reader& r, RawMesh& m) {
  r.require_line("the number of nodes");
  const std::int64_t n = r.count("number of nodes");
  r.expect_end_of_line();
  m.node_tags.reserve(static_cast<std::size_t>(std::min<std::int64_t>(n, 1 << 26)));
  m.coords.reserve(m.node_tags.capacity());
  for (std::int64_t i = 0; i < n; ++i) {
    r.require_line("node " + std::to_string(i + 1) + " of " + std::to_string(n));
    const std::int64_t tag = r.integer("node tag");
    Vec3 x;
    x[0] = r.real("x");
    x[1] = r.real("y");
    x[2] = r.real("z");
    r.expect_end_of_line();
    m.node_tags.push_back(tag);
    m.coords.push_back(x);
  }
  r.require_line("$EndNodes");
  r.expect_exact("$EndNodes");
}

void read_nodes_v41(Reader& r, RawMesh& m) {
  r.require_line("the $Nodes header");
  const std::int64_t blocks = r.count("number of entity blocks");
  const std::int64_t total = r.count("number of nodes");
  r.integer("minimum node tag");
  r.integer("maximum node tag");
  r.expect_end_of_line();
  const std::size_t cap = static_cast<std::size_t>(std::min<std::int64_t>(total, 1 << 26));
  m.node_tags.reserve(cap);
  m.coords.reserve(cap);
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    r.require_line("a node block header");
    const std::int64_t dim = r.integer("entity dimension");
    r.integer("entity tag");
    const std::int64_t parametric = r.integer("parametric flag");
    const std::int64_t n = r.count("number of nodes in the block");
    r.expect_end_of_line();
    if (dim < 0 || dim > 3) r.fail("entity dimension must be 0..3");
    if (seen + n > total)
      r.fail("node blocks hold more than the " + std::to_string(total) + " nodes announced");
    const std::size_t first = m.node_tags.size();
    for (std::int64_t i = 0; i < n; ++i) {
      if (i == 0) r.require_line("node tags");
      m.node_tags.push_back(r.integer_any_line("node tag", "$Nodes"));
    }
    if (n > 0) r.expect_end_of_line();
    for (std::int64_t i = 0; i < n; ++i) {
      r.require_line("coordinates of node tag " + std::to_string(m.node_tags[first + i]));
      Vec3 x;
      x[0] = r.real("x");
      x[1] = r.real("y");
      x[2] = r.real("z");
      if (parametric) {
        for (std::int64_t k = 0; k < dim; ++k) r.real("parametric coordinate");
      }
      r.expect_end_of_line();
      m.coords.push_back(x);
    }
    seen += n;
  }
  r.require_line("$EndNodes");
  if (seen != total && r.trimmed() == "$EndNodes")
    r.fail("$Nodes announced " + std::to_string(total) + " nodes but its blocks hold " +
           std::to_string(seen));
  r.expect_exact("$EndNodes");
}

void read_elements_v2(Reader& r, RawMesh& m) {
  r.require_line("the number of elements");
  const std::int64_t n = r.count("number of elements");
  r.expect_end_of_line();
  for (std::int64_t i = 0; i < n; ++i) {
    r.require_line("element " + std::to_string(i + 1) + " of " + std::to_string(n));
    RawElement e{};
    e.tag = r.integer("element tag");
    e.line = r.line_no();
    const std::int64_t type = r.integer("element type");
    const std::int64_t ntags = r.count("number of tags");
    const int dim = element_type_dim(type);
    if (type != kTypeTet4 && type != kTypeTet10 && dim == 3) {
      ++m.ignored;
      continue;
    }
    for (std::int64_t k = 0; k < ntags; ++k) {
      const std::int64_t t = r.integer("element tag (physical/elementary)");
      if (k == 0) e.group_key = t;  // the physical tag (0: none)
    }
    if (dim < 3) {
      ++m.ignored;
      const int nodes = element_type_nodes(type);
      if (e.group_key == 0 || nodes == 0) continue;
      std::vector<std::int64_t> tags(static_cast<std::size_t>(nodes));
      for (auto& t : tags) t = r.integer("node tag");
      r.expect_end_of_line();
      m.groups.add_element(dim, type, {e.group_key}, tags.data(), nodes);
      continue;
    }
    read_tet_nodes(r, static_cast<int>(type), e);
    m.tets.push_back(e);
  }
  r.require_line("$EndElements");
  r.expect_exact("$EndElements");
}

void read_elements_v41(Reader& r, RawMesh& m) {
  r.require_line("the $Elements header");
  const std::int64_t blocks = r.count("number of entity blocks");
  const std::int64_t total = r.count("number of elements");
  r.integer("minimum element tag");
  r.integer("maximum element tag");
  r.expect_end_of_line();
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    r.require_line("an element block header");
    const std::int64_t dim = r.integer("entity dimension");
    const std::int64_t entity = r.integer("entity tag");
    const std::int64_t type = r.integer("element type");
    const std::int64_t n = r.count("number of elements in the block");
    r.expect_end_of_line();
    if (seen + n > total)
      r.fail("element blocks hold more than the " + std::to_string(total) + " elements announced");
    const bool tet = type == kTypeTet4 || type == kTypeTet10;
    const int type_dim = element_type_dim(type);
    const int nodes = element_type_nodes(type);
    // a point, line or surface element of a physical group: its nodes form a node set
    const std::vector<std::int64_t> phys = !tet && type_dim < 3 && nodes > 0
                                               ? m.groups.physicals(false, type_dim, entity)
                                               : std::vector<std::int64_t>{};
    std::vector<std::int64_t> tags(static_cast<std::size_t>(nodes));
    for (std::int64_t i = 0; i < n; ++i) {
      r.require_line("element " + std::to_string(i + 1) + " of a block of " + std::to_string(n));
      if (!tet) {
        ++m.ignored;
        if (phys.empty()) continue;
        r.integer("element tag");
        for (auto& t : tags) t = r.integer("node tag");
        r.expect_end_of_line();
        m.groups.add_element(type_dim, type, phys, tags.data(), nodes);
        continue;
      }
      RawElement e{};
      e.tag = r.integer("element tag");
      e.line = r.line_no();
      e.group_key = entity;
      read_tet_nodes(r, static_cast<int>(type), e);
      m.tets.push_back(e);
    }
    (void)dim;
    seen += n;
  }
  r.require_line("$EndElements");
  if (seen != total && r.trimmed() == "$EndElements")
    r.fail("$Elements announced " + std::to_string(total) + " elements but its blocks hold " +
           std::to_string(seen));
  r.expect_exact("$EndElements");
}

// ---------------------------------------------------------------------------------------------
// Binary MSH (file type 1, data size 8): the section headers, the counts of MSH 2 sections and
// $PhysicalNames are text; nodes and elements are packed ints, size_ts and doubles.

void read_nodes_v2_binary(Reader& r, RawMesh& m) {
  r.require_line("the number of nodes");
  const std::int64_t n = r.count("number of nodes");
  r.expect_end_of_line();
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t tag = r.binary<std::int32_t>("node tag");
    Vec3 x;
    x[0] = r.binary_real("x");
    x[1] = r.binary_real("y");
    x[2] = r.binary_real("z");
    m.node_tags.push_back(tag);
    m.coords.push_back(x);
  }
  r.end_binary("$Nodes");
  r.require_line("$EndNodes");
  r.expect_exact("$EndNodes");
}

void read_nodes_v41_binary(Reader& r, RawMesh& m) {
  const std::int64_t blocks = r.binary_size("number of entity blocks");
  const std::int64_t total = r.binary_size("number of nodes");
  r.binary_size("minimum node tag");
  r.binary_size("maximum node tag");
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::int64_t dim = r.binary<std::int32_t>("entity dimension");
    r.binary<std::int32_t>("entity tag");
    const std::int64_t parametric = r.binary<std::int32_t>("parametric flag");
    const std::int64_t n = r.binary_size("number of nodes in the block");
    if (dim < 0 || dim > 3) r.fail_binary("entity dimension must be 0..3");
    if (n > total - seen)
      r.fail_binary("node blocks hold more than the " + std::to_string(total) + " nodes announced");
    for (std::int64_t i = 0; i < n; ++i) m.node_tags.push_back(r.binary_size("node tag"));
    for (std::int64_t i = 0; i < n; ++i) {
      Vec3 x;
      x[0] = r.binary_real("x");
      x[1] = r.binary_real("y");
      x[2] = r.binary_real("z");
      if (parametric) {
        for (std::int64_t k = 0; k < dim; ++k) r.binary<double>("parametric coordinate");
      }
      m.coords.push_back(x);
    }
    seen += n;
  }
  if (seen != total)
    r.fail_binary("$Nodes announced " + std::to_string(total) + " nodes but its blocks hold " +
                  std::to_string(seen));
  r.end_binary("$Nodes");
  r.require_line("$EndNodes");
  r.expect_exact("$EndNodes");
}

// One element's node tags (binary) into e, for a tetrahedron; others are stepped over.
template <class Tag>
void read_binary_element(Reader& r, RawMesh& m, std::int64_t type, std::int64_t tag, int line,
                         std::int64_t group_key) {
  const int nodes = element_type_nodes(type);
  if (type != kTypeTet4 && type != kTypeTet10) {
    std::array<std::int64_t, 128> tags{};
    for (int k = 0; k < nodes; ++k) {
      const auto t = static_cast<std::int64_t>(r.binary<Tag>("node tag"));
      if (k < static_cast<int>(tags.size())) tags[static_cast<std::size_t>(k)] = t;
    }
    ++m.ignored;
    const int dim = element_type_dim(type);
    if (dim < 3 && nodes <= static_cast<int>(tags.size())) {
      const auto phys = m.groups.physicals(m.v2, dim, group_key);
      if (!phys.empty()) m.groups.add_element(dim, type, phys, tags.data(), nodes);
    }
    return;
  }
  RawElement e{};
  e.tag = tag;
  e.line = line;
  e.group_key = group_key;
  e.nodes = nodes;
  for (int k = 0; k < nodes; ++k) e.n[static_cast<std::size_t>(k)] = r.binary<Tag>("node tag");
  m.tets.push_back(e);
}

void check_element_type(Reader& r, std::int64_t type) {
  if (element_type_nodes(type) == 0)
    r.fail_binary("element type " + std::to_string(type) +
                  " has a node count this reader does not know, so binary data past it cannot "
                  "be read; save the mesh as ASCII (gmsh option Mesh.Binary = 0)");
}

void read_elements_v2_binary(Reader& r, RawMesh& m) {
  r.require_line("the number of elements");
  const std::int64_t n = r.count("number of elements");
  r.expect_end_of_line();
  const int line = r.line_no();
  std::int64_t seen = 0;
  while (seen < n) {
    const std::int64_t type = r.binary<std::int32_t>("element type");
    const std::int64_t follow = r.binary_count("number of elements that follow");
    const std::int64_t ntags = r.binary_count("number of tags");
    check_element_type(r, type);
    if (follow > n - seen)
      r.fail_binary("element blocks hold more than the " + std::to_string(n) +
                    " elements announced");
    if (follow == 0) r.fail_binary("an element block of no elements");
    for (std::int64_t i = 0; i < follow; ++i) {
      const std::int64_t tag = r.binary<std::int32_t>("element tag");
      std::int64_t physical = 0;
      for (std::int64_t k = 0; k < ntags; ++k) {
        const std::int64_t t = r.binary<std::int32_t>("element tag (physical)");
        if (k == 0) physical = t;
      }
      read_binary_element<std::int32_t>(r, m, type, tag, line, physical);
    }
    seen += follow;
  }
  r.end_binary("$Elements");
  r.require_line("$EndElements");
  r.expect_exact("$EndElements");
}

void read_elements_v41_binary(Reader& r, RawMesh& m) {
  const int line = r.line_no();
  const std::int64_t blocks = r.binary_size("number of entity blocks");
  const std::int64_t total = r.binary_size("number of elements");
  r.binary_size("minimum element tag");
  r.binary_size("maximum element tag");
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    r.binary<std::int32_t>("entity dimension");
    const std::int64_t entity = r.binary<std::int32_t>("entity tag");
    const std::int64_t type = r.binary<std::int32_t>("element type");
    const std::int64_t n = r.binary_size("number of elements in the block");
    check_element_type(r, type);
    if (n > total - seen)
      r.fail_binary("element blocks hold more than the " + std::to_string(total) +
                    " elements announced");
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t tag = r.binary_size("element tag");
      read_binary_element<std::uint64_t>(r, m, type, tag, line, entity);
    }
    seen += n;
  }
  if (seen != total)
    r.fail_binary("$Elements announced " + std::to_string(total) +
                  " elements but its blocks hold " + std::to_string(seen));
  r.end_binary("$Elements");
  r.require_line("$EndElements");
  r.expect_exact("$EndElements");
}

// $PhysicalNames (text in ASCII and binary files alike): "dim tag \"name\"" per line.
void read_physical_names(Reader& r, RawGroups& g) {
  r.require_line("the number of physical names");
  const std::int64_t n = r.count("number of physical names");
  r.expect_end_of_line();
  for (std::int64_t i = 0; i < n; ++i) {
    r.require_line("physical name " + std::to_string(i + 1) + " of " + std::to_string(n));
    const std::int64_t dim = r.integer("physical dimension");
    const std::int64_t tag = r.integer("physical tag");
    if (dim < 0 || dim > 3) r.fail("physical dimension must be 0..3");
    std::string_view rest = r.trimmed();
    // the rest of the line after the two numbers: the quoted name
    const std::size_t q0 = rest.find('"'), q1 = rest.rfind('"');
    if (q0 == std::string_view::npos || q1 == q0)
      r.fail("expected a quoted physical name after the dimension and the tag");
    g.names[{static_cast<int>(dim), tag}] = std::string(rest.substr(q0 + 1, q1 - q0 - 1));
  }
  r.require_line("$EndPhysicalNames");
  r.expect_exact("$EndPhysicalNames");
}

// $Entities of MSH 4.1: which physical groups each point, curve, surface and volume belongs to
// (their boxes and bounding entities are read past).
void read_entities(Reader& r, RawGroups& g, bool binary) {
  std::array<std::int64_t, 4> counts{};
  if (binary) {
    for (auto& c : counts) c = r.binary_size("number of entities");
  } else {
    r.require_line("the entity counts");
    for (auto& c : counts) c = r.count("number of entities");
    r.expect_end_of_line();
  }
  for (int dim = 0; dim < 4; ++dim) {
    for (std::int64_t i = 0; i < counts[static_cast<std::size_t>(dim)]; ++i) {
      std::vector<std::int64_t> phys;
      if (binary) {
        const std::int64_t tag = r.binary<std::int32_t>("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) r.binary<double>("entity box");
        const std::int64_t np = r.binary_size("number of physical tags");
        if (np > 1 << 20) r.fail_binary("number of physical tags is out of range");
        for (std::int64_t k = 0; k < np; ++k)
          phys.push_back(r.binary<std::int32_t>("physical tag"));
        if (dim > 0) {
          const std::int64_t nb = r.binary_size("number of bounding entities");
          if (nb > 1 << 24) r.fail_binary("number of bounding entities is out of range");
          for (std::int64_t k = 0; k < nb; ++k) r.binary<std::int32_t>("bounding entity tag");
        }
        if (!phys.empty()) g.entity_physicals[{dim, tag}] = std::move(phys);
      } else {
        r.require_line("an entity");
        const std::int64_t tag = r.integer("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) r.real("entity box");
        const std::int64_t np = r.count("number of physical tags");
        for (std::int64_t k = 0; k < np; ++k) phys.push_back(r.integer("physical tag"));
        if (dim > 0) {
          const std::int64_t nb = r.count("number of bounding entities");
          for (std::int64_t k = 0; k < nb; ++k) r.integer("bounding entity tag");
        }
        r.expect_end_of_line();
        if (!phys.empty()) g.entity_physicals[{dim, tag}] = std::move(phys);
      }
    }
  }
  if (binary) r.end_binary("$Entities");
  r.require_line("$EndEntities");
  r.expect_exact("$EndEntities");
}

// The physical groups resolved to the assembled mesh: volumes to elements, the others to the
// nodes the tetrahedra use (after a TET4 promotion, with the mid-edge nodes of their edges).
std::vector<GmshPhysicalGroup> resolve_groups(
    const RawMesh& raw, const Tet10Mesh& mesh,
    const std::unordered_map<std::int64_t, std::int32_t>& index_of,
    const std::vector<std::int32_t>& compact, bool promoted) {
  std::map<DimTag, GmshPhysicalGroup> groups;
  auto group = [&](int dim, std::int64_t tag) -> GmshPhysicalGroup& {
    GmshPhysicalGroup& g = groups[{dim, tag}];
    g.dim = dim;
    g.tag = tag;
    const auto it = raw.groups.names.find({dim, tag});
    if (it != raw.groups.names.end()) g.name = it->second;
    return g;
  };
  for (std::size_t e = 0; e < raw.tets.size(); ++e)
    for (std::int64_t p : raw.groups.physicals(raw.v2, 3, raw.tets[e].group_key))
      group(3, p).elements.push_back(static_cast<std::int32_t>(e));
  auto mesh_node = [&](std::int64_t tag) -> std::int32_t {
    const auto it = index_of.find(tag);
    return it == index_of.end() ? -1 : compact[static_cast<std::size_t>(it->second)];
  };
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> mid;  // corner pair -> mid node
  if (promoted) {
    for (const Tet10& el : mesh.elements)
      for (int i = 0; i < 6; ++i)
        mid[std::minmax(el[kTet10Edges[i][0]], el[kTet10Edges[i][1]])] = el[4 + i];
  }
  for (const auto& [key, tags] : raw.groups.node_tags) {
    GmshPhysicalGroup& g = group(key.first, key.second);
    for (std::int64_t t : tags)
      if (const std::int32_t n = mesh_node(t); n >= 0) g.nodes.push_back(n);
    if (promoted) {
      const auto ed = raw.groups.edges.find(key);
      if (ed != raw.groups.edges.end())
        for (const auto& [a, b] : ed->second) {
          const std::int32_t na = mesh_node(a), nb = mesh_node(b);
          if (na < 0 || nb < 0) continue;
          const auto it = mid.find(std::minmax(na, nb));
          if (it != mid.end()) g.nodes.push_back(it->second);
        }
    }
    std::sort(g.nodes.begin(), g.nodes.end());
    g.nodes.erase(std::unique(g.nodes.begin(), g.nodes.end()), g.nodes.end());
  }
  // named groups that no element of the file belongs to are still listed (empty)
  for (const auto& [key, name] : raw.groups.names) group(key.first, key.second);
  std::vector<GmshPhysicalGroup> out;
  for (auto& [key, g] : groups) out.push_back(std::move(g));
  return out;
}

std::string read_file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open the mesh file", path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Tet10Mesh assemble(const Reader& r, RawMesh& raw, GmshReadInfo& info) {
  const std::string& path = r.path();
  if (!raw.have_nodes) r.fail_at("no $Nodes section", r.line_no() + 1);
  if (!raw.have_elements) r.fail_at("no $Elements section", r.line_no() + 1);
  if (raw.tets.empty())
    r.fail_at("no tetrahedra (element types 4 or 11) in $Elements; a volume mesh is needed",
              raw.elements_line);

  // Tag -> file node index.
  std::unordered_map<std::int64_t, std::int32_t> index_of;
  index_of.reserve(raw.node_tags.size() * 2);
  for (std::size_t i = 0; i < raw.node_tags.size(); ++i) {
    if (!index_of.emplace(raw.node_tags[i], static_cast<std::int32_t>(i)).second)
      r.fail_at("node tag " + std::to_string(raw.node_tags[i]) + " is defined twice",
                raw.nodes_line);
  }

  // Resolve tags, mark used nodes.
  std::vector<std::int32_t> compact(raw.node_tags.size(), -1);
  std::vector<std::array<std::int32_t, 10>> file_nodes(raw.tets.size());
  for (std::size_t e = 0; e < raw.tets.size(); ++e) {
    const RawElement& t = raw.tets[e];
    for (int i = 0; i < t.nodes; ++i) {
      const auto it = index_of.find(t.n[i]);
      if (it == index_of.end())
        r.fail_at("element " + std::to_string(t.tag) + " refers to node tag " +
                      std::to_string(t.n[i]) + ", which is not in $Nodes",
                  t.line);
      file_nodes[e][i] = it->second;
      for (int j = 0; j < i; ++j)
        if (file_nodes[e][j] == it->second)
          r.fail_at("element " + std::to_string(t.tag) + " uses node tag " +
                        std::to_string(t.n[i]) + " twice",
                    t.line);
      compact[it->second] = 0;
    }
  }
  Tet10Mesh mesh;
  for (std::size_t i = 0; i < compact.size(); ++i) {
    if (compact[i] < 0) {
      ++info.unused_nodes;
      continue;
    }
    compact[i] = static_cast<std::int32_t>(mesh.nodes.size());
    mesh.nodes.push_back(raw.coords[i]);
  }
  if (mesh.nodes.size() + 6 * raw.tets.size() > static_cast<std::size_t>(INT32_MAX))
    r.fail_at("mesh too large", raw.elements_line);

  // Elements in our node order; TET4 elements get their mid-edge nodes below (shared with any
  // TET10 element on the same edge).
  mesh.elements.resize(raw.tets.size());
  for (std::size_t e = 0; e < raw.tets.size(); ++e) {
    const RawElement& t = raw.tets[e];
    Tet10& el = mesh.elements[e];
    if (t.nodes == 10) {
      ++info.tet10;
      for (int i = 0; i < 10; ++i) el[kGmshToOurs[i]] = compact[file_nodes[e][i]];
    } else {
      ++info.tet4;
      for (int i = 0; i < 4; ++i) el[i] = compact[file_nodes[e][i]];
      for (int i = 4; i < 10; ++i) el[i] = -1;
    }
  }
  if (info.tet4 > 0) {
    add_mid_edge_nodes(mesh);
    info.notes.push_back(std::to_string(info.tet4) + " TET4 element(s) promoted to TET10");
  }
  info.groups = resolve_groups(raw, mesh, index_of, compact, info.tet4 > 0);

  // Orientation and degeneracy.
  std::vector<double> vol(mesh.elements.size());
  double sum_abs = 0.0;
  std::int64_t npos = 0, nneg = 0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const Tet10& el = mesh.elements[e];
    vol[e] = tet_signed_volume(mesh.nodes[el[0]], mesh.nodes[el[1]], mesh.nodes[el[2]],
                               mesh.nodes[el[3]]);
    sum_abs += std::abs(vol[e]);
  }
  const double mean = sum_abs / static_cast<double>(vol.size());
  for (std::size_t e = 0; e < vol.size(); ++e) {
    if (!(std::abs(vol[e]) > 1e-10 * mean)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "is degenerate (volume %.3g, mean element volume %.3g)",
                    vol[e], mean);
      r.fail_at("element " + std::to_string(raw.tets[e].tag) + " " + buf, raw.tets[e].line);
    }
    (vol[e] > 0 ? npos : nneg)++;
  }
  if (npos > 0 && nneg > 0) {
    const bool bad_sign_negative = npos >= nneg;
    for (std::size_t e = 0; e < vol.size(); ++e)
      if ((vol[e] < 0) == bad_sign_negative)
        r.fail_at("element " + std::to_string(raw.tets[e].tag) +
                      " is inverted: its orientation is opposite to " +
                      std::to_string(std::max(npos, nneg)) + " of the " +
                      std::to_string(vol.size()) + " tetrahedra",
                  raw.tets[e].line);
  }
  if (nneg > 0) {
    // Swap corners 1 and 2: edges 0-1 <-> 0-2 (4 <-> 6), 1-3 <-> 2-3 (8 <-> 9).
    for (Tet10& el : mesh.elements) {
      std::swap(el[1], el[2]);
      std::swap(el[4], el[6]);
      std::swap(el[8], el[9]);
    }
    info.flipped = true;
    info.notes.push_back("all tetrahedra were negatively oriented and have been flipped");
  }
  if (info.tet10 > 0) {
    for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
      if (raw.tets[e].nodes != 10) continue;
      const double sj = tet10_min_scaled_jacobian(mesh, e);
      if (!(sj > 0.0)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.3g", sj);
        r.fail_at("element " + std::to_string(raw.tets[e].tag) +
                      " is folded: its mid-edge nodes give a scaled Jacobian of " + buf,
                  raw.tets[e].line);
      }
    }
  }
  if (info.unused_nodes > 0)
    info.notes.push_back(std::to_string(info.unused_nodes) +
                         " node(s) not used by any tetrahedron dropped");
  if (info.ignored_elements > 0)
    info.notes.push_back(std::to_string(info.ignored_elements) +
                         " non-tetrahedral element(s) ignored");
  (void)path;
  return mesh;
}

}  // namespace

Tet10Mesh read_gmsh(const std::string& path, GmshReadInfo* info_out) {
  Reader r(path, read_file_text(path));
  GmshReadInfo info;

  if (!r.next_nonblank_line()) throw InputError("empty file; expected a gmsh MSH file", path, 1);
  if (r.trimmed() != "$MeshFormat")
    r.fail("not a gmsh MSH file: expected $MeshFormat on the first line");
  r.require_line("the format line (version file-type data-size)");
  const std::string_view version = r.token();
  const std::string vs(version);
  if (vs.empty()) r.fail("missing MSH version");
  int major = 0;
  if (vs == "4.1") {
    major = 4;
  } else if (vs == "2" || vs == "2.0" || vs == "2.1" || vs == "2.2") {
    major = 2;
  } else {
    r.fail("unsupported MSH version '" + vs + "'; save the mesh as MSH 4.1 or 2.2", 1);
  }
  info.version = vs;
  const std::int64_t file_type = r.integer("file type");
  if (file_type != 0 && file_type != 1) r.fail("file type must be 0 (ASCII) or 1 (binary)");
  const bool binary = file_type == 1;
  const std::int64_t data_size = r.integer("data size");
  r.expect_end_of_line();
  if (binary) {
    if (data_size != 8)
      r.fail("binary MSH with data size " + std::to_string(data_size) +
             "; only 8-byte size_t (what gmsh writes on 64-bit machines) is read");
    // the int 1 that says the byte order, then a line break
    if (r.binary<std::int32_t>("the byte-order mark (the int 1)") != 1)
      r.fail_binary(
          "the byte-order mark is not 1: the file was written on a machine of the "
          "other byte order");
    r.end_binary("$MeshFormat");
  }
  r.require_line("$EndMeshFormat");
  r.expect_exact("$EndMeshFormat");

  RawMesh raw;
  raw.v2 = major == 2;
  while (r.next_nonblank_line()) {
    const std::string_view head = r.trimmed();
    if (head.empty() || head.front() != '$')
      r.fail("expected a section header such as $Nodes, got '" + std::string(head) + "'");
    if (head == "$Nodes") {
      if (raw.have_nodes) r.fail("second $Nodes section");
      raw.have_nodes = true;
      raw.nodes_line = r.line_no();
      if (major == 4)
        binary ? read_nodes_v41_binary(r, raw) : read_nodes_v41(r, raw);
      else
        binary ? read_nodes_v2_binary(r, raw) : read_nodes_v2(r, raw);
    } else if (head == "$PhysicalNames") {
      read_physical_names(r, raw.groups);
    } else if (head == "$Entities" && major == 4) {
      if (raw.have_elements) r.fail("$Entities after $Elements");
      read_entities(r, raw.groups, binary);
    } else if (head == "$Elements") {
      if (raw.have_elements) r.fail("second $Elements section");
      if (!raw.have_nodes) r.fail("$Elements before $Nodes");
      raw.have_elements = true;
      raw.elements_line = r.line_no();
      if (major == 4)
        binary ? read_elements_v41_binary(r, raw) : read_elements_v41(r, raw);
      else
        binary ? read_elements_v2_binary(r, raw) : read_elements_v2(r, raw);
    } else {
      // Skip any other section up to its end marker.
      const std::string name(head.substr(1));
      const std::string end = "$End" + name;
      const int start = r.line_no();
      bool closed = false;
      while (r.next_line())
        if (r.trimmed() == end) {
          closed = true;
          break;
        }
      if (!closed)
        throw InputError("unexpected end of file: section $" + name + " opened on line " +
                             std::to_string(start) + " has no " + end + " (truncated file?)",
                         path, r.line_no() + 1);
    }
  }
  info.ignored_elements = raw.ignored;
  Tet10Mesh mesh = assemble(r, raw, info);
  if (info_out) *info_out = std::move(info);
  return mesh;
}

GmshBody gmsh_body(Tet10Mesh mesh, const GmshReadInfo& info, const std::string& volume) {
  GmshBody body;
  std::vector<std::int32_t> new_index;  // file mesh node -> body node (-1: not in the body)
  if (volume.empty()) {
    body.mesh = std::move(mesh);
  } else {
    const GmshPhysicalGroup* g = nullptr;
    for (const GmshPhysicalGroup& c : info.groups)
      if (c.dim == 3 && c.label() == volume) g = &c;
    if (!g || g->elements.empty())
      throw std::invalid_argument("no physical volume '" + volume + "' with tetrahedra");
    new_index.assign(mesh.nodes.size(), -1);
    std::vector<char> used(mesh.nodes.size(), 0);
    for (std::int32_t e : g->elements)
      for (std::int32_t n : mesh.elements[static_cast<std::size_t>(e)])
        used[static_cast<std::size_t>(n)] = 1;
    for (std::size_t n = 0; n < used.size(); ++n)
      if (used[n]) {
        new_index[n] = static_cast<std::int32_t>(body.mesh.nodes.size());
        body.mesh.nodes.push_back(mesh.nodes[n]);
      }
    for (std::int32_t e : g->elements) {
      Tet10 el = mesh.elements[static_cast<std::size_t>(e)];
      for (std::int32_t& n : el) n = new_index[static_cast<std::size_t>(n)];
      body.mesh.elements.push_back(el);
    }
  }
  for (const GmshPhysicalGroup& c : info.groups) {
    if (c.dim == 3) continue;
    std::vector<std::int32_t> nodes;
    for (std::int32_t n : c.nodes) {
      const std::int32_t b = new_index.empty() ? n : new_index[static_cast<std::size_t>(n)];
      if (b >= 0) nodes.push_back(b);
    }
    std::sort(nodes.begin(), nodes.end());
    if (!nodes.empty()) body.node_sets.emplace_back(c.label(), std::move(nodes));
  }
  return body;
}

std::string gmsh_text(const Tet10Mesh& mesh, const std::string& physical_volume) {
  std::string out;
  out.reserve(mesh.nodes.size() * 64 + mesh.elements.size() * 96 + 512);
  char buf[64];
  auto put_double = [&](double v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
  };
  auto put_int = [&](std::int64_t v) {
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
  };
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  if (!mesh.nodes.empty()) {
    lo = hi = mesh.nodes[0];
    for (const Vec3& x : mesh.nodes) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  const auto nn = static_cast<std::int64_t>(mesh.nodes.size());
  const auto ne = static_cast<std::int64_t>(mesh.elements.size());
  const bool physical = !physical_volume.empty();
  out += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  if (physical) out += "$PhysicalNames\n1\n3 1 \"" + physical_volume + "\"\n$EndPhysicalNames\n";
  out += "$Entities\n0 0 0 1\n1";
  for (int k = 0; k < 3; ++k) out += ' ', put_double(lo[k]);
  for (int k = 0; k < 3; ++k) out += ' ', put_double(hi[k]);
  out += physical ? " 1 1 0\n$EndEntities\n$Nodes\n" : " 0 0\n$EndEntities\n$Nodes\n";
  out += "1 ", put_int(nn), out += " 1 ", put_int(nn), out += '\n';
  out += "3 1 0 ", put_int(nn), out += '\n';
  for (std::int64_t i = 1; i <= nn; ++i) put_int(i), out += '\n';
  for (const Vec3& x : mesh.nodes) {
    put_double(x[0]), out += ' ', put_double(x[1]), out += ' ', put_double(x[2]);
    out += '\n';
  }
  out += "$EndNodes\n$Elements\n";
  out += "1 ", put_int(ne), out += " 1 ", put_int(ne), out += '\n';
  out += "3 1 11 ", put_int(ne), out += '\n';
  for (std::int64_t e = 0; e < ne; ++e) {
    put_int(e + 1);
    const Tet10& el = mesh.elements[static_cast<std::size_t>(e)];
    for (int i = 0; i < 10; ++i) out += ' ', put_int(std::int64_t{el[kGmshToOurs[i]]} + 1);
    out += '\n';
  }
  out += "$EndElements\n";

  return out;
}

void write_gmsh(const Tet10Mesh& mesh, const std::string& path,
                const std::string& physical_volume) {
  // Atomically, so that a killed `femdem mesh` or two sweep jobs filling the mesh cache at once
  // never leave a half-written file under the final name.
  write_file_atomically(path, gmsh_text(mesh, physical_volume));
}

}  // namespace femdem
