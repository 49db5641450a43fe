#include "hexdom/io/msh.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/io/cell_assembly.h"
#include "hexdom/io/gmsh_orders.h"
#include "hexdom/io/text.h"

namespace hexdom::io {

namespace {

// ---- Gmsh element types ----

struct GmshType {
  int nodes = 0, dim = -1;  // dim -1: a type this reader does not know
  int vtk = 0;              // the VTK type it is read as; 0: not read
  const char* name = "";
};

GmshType gmsh_type(long t) {
  switch (t) {
    case 1: return {2, 1, 0, "2-node line"};
    case 2: return {3, 2, 5, "3-node triangle"};
    case 3: return {4, 2, 9, "4-node quadrangle"};
    case 4: return {4, 3, 10, "4-node tetrahedron"};
    case 5: return {8, 3, 12, "8-node hexahedron"};
    case 6: return {6, 3, 13, "6-node prism"};
    case 7: return {5, 3, 0, "5-node pyramid"};
    case 8: return {3, 1, 0, "3-node line"};
    case 9: return {6, 2, 0, "6-node triangle"};
    case 10: return {9, 2, 0, "9-node quadrangle"};
    case 11: return {10, 3, 24, "10-node tetrahedron"};
    case 12: return {27, 3, 0, "27-node hexahedron"};
    case 13: return {18, 3, 0, "18-node prism"};
    case 14: return {14, 3, 0, "14-node pyramid"};
    case 15: return {1, 0, 0, "point"};
    case 16: return {8, 2, 0, "8-node quadrangle"};
    case 17: return {20, 3, 25, "20-node hexahedron"};
    case 18: return {15, 3, 26, "15-node prism"};
    case 19: return {13, 3, 0, "13-node pyramid"};
    case 20: return {9, 2, 0, "9-node triangle"};
    case 21: return {10, 2, 0, "10-node triangle"};
    case 22: return {12, 2, 0, "12-node triangle"};
    case 23: return {15, 2, 0, "15-node triangle"};
    case 24: return {15, 2, 0, "15-node incomplete triangle"};
    case 25: return {21, 2, 0, "21-node triangle"};
    case 26: return {4, 1, 0, "4-node line"};
    case 27: return {5, 1, 0, "5-node line"};
    case 28: return {6, 1, 0, "6-node line"};
    case 29: return {20, 3, 0, "20-node tetrahedron"};
    case 30: return {35, 3, 0, "35-node tetrahedron"};
    case 31: return {56, 3, 0, "56-node tetrahedron"};
    case 92: return {64, 3, 0, "64-node hexahedron"};
    case 93: return {125, 3, 0, "125-node hexahedron"};
    default: return {};
  }
}

// ---- node tags ----

// Node tags of the file to node indices: sparse tags, in any order; duplicates are an error.
class NodeIndex {
 public:
  void add(uint64_t tag, long line) {
    tags_.push_back(tag);
    lines_.push_back(line);
  }
  size_t size() const { return tags_.size(); }

  // Sorts the tags; a dense table when they are nearly contiguous. Throws for a repeated tag.
  void finish(const std::string& path) {
    sorted_.resize(tags_.size());
    for (size_t i = 0; i < tags_.size(); ++i) sorted_[i] = {tags_[i], static_cast<int>(i)};
    std::sort(sorted_.begin(), sorted_.end());
    for (size_t i = 1; i < sorted_.size(); ++i)
      if (sorted_[i].first == sorted_[i - 1].first)
        throw InputError(path, lines_[sorted_[i].second],
                         "node tag " + std::to_string(sorted_[i].first) + " is given twice (first on line " +
                             std::to_string(lines_[sorted_[i - 1].second]) + ")");
    dense_.clear();
    if (!sorted_.empty() && sorted_.back().first - sorted_.front().first < 2 * sorted_.size() + 1024) {
      lo_ = sorted_.front().first;
      dense_.assign(sorted_.back().first - lo_ + 1, -1);
      for (const auto& [tag, i] : sorted_) dense_[tag - lo_] = i;
      sorted_.clear();
    }
    tags_.clear();
    lines_.clear();
  }

  // Index of a tag, -1 when the file has no such node.
  int find(uint64_t tag) const {
    if (!dense_.empty()) return tag >= lo_ && tag - lo_ < dense_.size() ? dense_[tag - lo_] : -1;
    auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair(tag, INT_MIN));
    return it != sorted_.end() && it->first == tag ? it->second : -1;
  }

 private:
  std::vector<uint64_t> tags_;
  std::vector<long> lines_;
  std::vector<std::pair<uint64_t, int>> sorted_;
  std::vector<int> dense_;
  uint64_t lo_ = 0;
};

// Text of a token for a message: at most 40 characters, non-printable bytes as '?'.
std::string shown(std::string_view t) {
  std::string r(t.substr(0, 40));
  for (char& c : r)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return t.size() > 40 ? r + "..." : r;
}

// ---- the reader ----

class MshReader {
 public:
  MshReader(const std::string& path, const std::string& text)
      : path_(path), s_(text), volume_(path, "element"), surface_(path, "element") {}

  mesh::Mesh read() {
    read_format();
    while (true) {
      skip_space();
      if (pos_ >= s_.size()) break;
      const long line = line_;
      const std::string tok(raw_token());
      if (tok[0] != '$') fail_at(line, "expected a section ($Name), found '" + shown(tok) + "'");
      const std::string name = tok.substr(1);
      if (name.rfind("End", 0) == 0) fail_at(line, "'" + shown(tok) + "' closes a section that was not opened");
      if (name == "MeshFormat") fail_at(line, "a second $MeshFormat section");
      if (name == "Entities" && v41_) read_entities(line);
      else if (name == "Nodes") read_nodes(line);
      else if (name == "Elements") read_elements(line);
      else skip_section(name, line);
    }
    return build();
  }

 private:
  // ---- low level: position, lines, tokens and binary values ----

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, line_, what); }
  [[noreturn]] void fail_at(long line, const std::string& what) const { throw InputError(path_, line, what); }
  size_t left() const { return s_.size() - pos_; }

  // Line of the file's last non-blank byte (where a file that ends too early ends).
  long last_line() const {
    size_t e = s_.size();
    while (e > 0 && std::isspace(static_cast<unsigned char>(s_[e - 1]))) --e;
    return 1 + static_cast<long>(std::count(s_.begin(), s_.begin() + static_cast<long>(e), '\n'));
  }

  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  // Next blank-separated token ("" at the end of the file); tok_line_ is its line.
  std::string_view raw_token() {
    skip_space();
    tok_line_ = line_;
    const size_t b = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return std::string_view(s_).substr(b, pos_ - b);
  }

  // A data token: a section line instead means the section holds less than its header says.
  std::string_view token(const char* what) {
    std::string_view t = raw_token();
    if (t.empty()) fail_at(last_line(), std::string("file ends where ") + what + " was expected (truncated?)");
    if (t[0] == '$')
      fail_at(tok_line_, "found '" + shown(t) + "' where " + what + " was expected (the section holds less than its header says)");
    return t;
  }

  // Ends the line of a section keyword or header: only blanks may follow before the newline.
  void end_line(const char* after) {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
    if (pos_ >= s_.size()) return;
    if (s_[pos_] != '\n') fail(std::string("unexpected '") + shown(s_.substr(pos_, 1)) + "' after " + after);
    ++pos_;
    ++line_;
  }

  // n raw bytes of binary data, little-endian value of them (byte-swapped for a big-endian file).
  uint64_t raw(size_t w, const char* what) {
    if (w > left())
      fail(std::string("file ends inside ") + what + ": " + std::to_string(w) + " bytes needed, " +
           std::to_string(left()) + " left (truncated?)");
    const unsigned char* p = reinterpret_cast<const unsigned char*>(s_.data() + pos_);
    uint64_t u = 0;
    for (size_t i = 0; i < w; ++i) u |= static_cast<uint64_t>(p[swap_ ? w - 1 - i : i]) << (8 * i);
    line_ += std::count(p, p + w, '\n');
    pos_ += w;
    return u;
  }

  // Line of the next value: the current line in binary data, else the next token's.
  long here(bool text = false) {
    if (!binary_ || text) skip_space();
    return line_;
  }

  // A 32-bit int: binary int, or a token.
  long get_int(const char* what, bool text = false) {
    if (binary_ && !text) return static_cast<int32_t>(static_cast<uint32_t>(raw(4, what)));
    std::string_view t = token(what);
    long v;
    if (!parse_int(t, v) || v < INT32_MIN || v > INT32_MAX)
      fail_at(tok_line_, std::string(what) + ": '" + shown(t) + "' is not a 32-bit integer");
    return v;
  }

  // A non-negative integer: a binary size_t (4.1) or int (2.2), or a token (`text`: even in a
  // binary file, as 2.2 gives its counts).
  uint64_t get_size(const char* what, bool text = false) {
    if (binary_ && !text) {
      if (v41_) return raw(size_w_, what);
      const long v = static_cast<int32_t>(static_cast<uint32_t>(raw(4, what)));
      if (v < 0) fail(std::string(what) + " " + std::to_string(v) + " is negative");
      return static_cast<uint64_t>(v);
    }
    std::string_view t = token(what);
    long v;
    if (!parse_int(t, v) || v < 0) fail_at(tok_line_, std::string(what) + ": '" + shown(t) + "' is not a non-negative integer");
    return static_cast<uint64_t>(v);
  }

  double get_double(const char* what) {
    double d;
    if (binary_) {
      const uint64_t u = raw(8, what);
      std::memcpy(&d, &u, 8);
      if (!std::isfinite(d)) fail(std::string(what) + " is not a finite number");
      return d;
    }
    std::string_view t = token(what);
    if (!parse_double(t, d)) fail_at(tok_line_, std::string(what) + ": '" + shown(t) + "' is not a finite number");
    return d;
  }

  // A count of a header, checked against the bytes left: each item takes at least `ascii` bytes
  // (`binary` in a binary file), so a larger count is corrupt and must not be allocated for.
  uint64_t get_count(const char* what, size_t ascii, size_t binary, bool text = false) {
    const long line = here(text);
    const uint64_t n = get_size(what, text);
    check_count(n, what, binary_ && !text ? binary : ascii, line);
    return n;
  }

  void check_count(uint64_t n, const char* what, size_t item, long line) const {
    if (n > left() / std::max<size_t>(item, 1))
      fail_at(line, std::string(what) + " " + std::to_string(n) + " is larger than the file can hold (truncated? corrupt header?)");
  }

  // The "$End<name>" line that closes a section.
  void expect_end(const std::string& name) {
    const std::string want = "$End" + name;
    std::string_view t = raw_token();
    if (t.empty()) fail_at(last_line(), "file ends before " + want + " (truncated?)");
    if (t != want)
      fail_at(tok_line_, "expected " + want + ", found '" + shown(t) + "' (the section holds more than its header says?)");
  }

  // Skips a section up to the line "$End<name>" (found by search, as in binary data).
  void skip_section(const std::string& name, long start) {
    const std::string marker = "\n$End" + name;
    size_t at = pos_;
    while (true) {
      at = s_.find(marker, at);
      if (at == std::string::npos)
        fail_at(start, "section $" + shown(name) + " has no $End" + shown(name) + " line (truncated?)");
      const size_t after = at + marker.size();
      if (after >= s_.size() || std::isspace(static_cast<unsigned char>(s_[after]))) break;
      at = after;
    }
    line_ += std::count(s_.begin() + static_cast<long>(pos_), s_.begin() + static_cast<long>(at) + 1, '\n');
    pos_ = at + marker.size();
  }

  // ---- sections ----

  void read_format() {
    std::string_view t = raw_token();
    if (t != "$MeshFormat") fail_at(tok_line_ ? tok_line_ : 1, "not a Gmsh mesh file (it must start with $MeshFormat)");
    end_line("$MeshFormat");
    std::string_view v = token("the format version");
    double version = 0;
    parse_double(v, version);
    if (version == 4.1) v41_ = true;
    else if (version != 2.2)
      fail_at(tok_line_, "MSH version '" + shown(v) + "' is not supported (HexDom reads versions 4.1 and 2.2)");
    const long type = get_int("the file type");
    if (type != 0 && type != 1) fail_at(tok_line_, "file type " + std::to_string(type) + " must be 0 (ASCII) or 1 (binary)");
    const long size = get_int("the data size");
    if (size != 8 && !(v41_ && size == 4))
      fail_at(tok_line_, "data size " + std::to_string(size) + " is not supported (" + (v41_ ? "8 or 4" : "8") + ")");
    size_w_ = static_cast<size_t>(size);
    end_line("the format line");
    if (type == 1) {
      binary_ = true;
      const uint64_t one = raw(4, "the binary check int");
      if (one == 0x01000000u) swap_ = true;
      else if (one != 1) fail("the binary check int after the format line is " + std::to_string(one) + ", not 1");
    }
    expect_end("MeshFormat");
  }

  // $Entities (4.1): the first physical tag of each surface and volume.
  void read_entities(long start) {
    if (have_nodes_ || have_elements_) fail_at(start, "$Entities must come before $Nodes and $Elements");
    end_line("$Entities");
    uint64_t count[4];
    for (auto& c : count) c = get_count("entity count", 2, 28 + size_w_);
    for (int dim = 0; dim < 4; ++dim) {
      for (uint64_t i = 0; i < count[dim]; ++i) {
        const long tag = get_int("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) get_double("entity bounding box");
        const uint64_t nphys = get_count("physical tag count", 2, 4);
        for (uint64_t k = 0; k < nphys; ++k) {
          const long p = get_int("physical tag");
          if (k == 0 && dim >= 2) physical_[{dim, tag}] = static_cast<int>(p);
        }
        if (dim == 0) continue;
        const uint64_t nbound = get_count("bounding entity count", 2, 4);
        for (uint64_t k = 0; k < nbound; ++k) get_int("bounding entity tag");
      }
    }
    expect_end("Entities");
  }

  void read_nodes(long start) {
    if (have_nodes_) fail_at(start, "a second $Nodes section");
    if (have_elements_) fail_at(start, "$Nodes must come before $Elements");
    have_nodes_ = true;
    end_line("$Nodes");
    if (v41_) read_nodes41();
    else read_nodes22();
    expect_end("Nodes");
    if (nodes_.size() > static_cast<size_t>(INT_MAX)) fail_at(start, "too many nodes");
    nodes_.finish(path_);
  }

  void read_nodes41() {
    const long header = here();
    const uint64_t nblocks = get_count("node block count", 8, 12 + size_w_);
    const uint64_t total = get_count("node count", 8, 24 + size_w_);
    get_size("minimum node tag");
    get_size("maximum node tag");
    xyz_.reserve(3 * total);
    uint64_t read = 0;
    for (uint64_t b = 0; b < nblocks; ++b) {
      const long bline = here();
      const long dim = get_int("entity dimension");
      get_int("entity tag");
      const long param = get_int("parametric flag");
      const uint64_t n = get_count("block node count", 8, 24 + size_w_);
      if (dim < 0 || dim > 3) fail_at(bline, "node block: entity dimension " + std::to_string(dim) + " is not 0..3");
      if (param != 0 && param != 1) fail_at(bline, "node block: parametric flag " + std::to_string(param) + " is not 0 or 1");
      if (n > total - read)
        fail_at(bline, "node blocks hold more than the " + std::to_string(total) + " nodes of the $Nodes header");
      read += n;
      for (uint64_t i = 0; i < n; ++i) {
        const long l = here();
        nodes_.add(get_size("node tag"), l);
      }
      for (uint64_t i = 0; i < n * (3 + (param ? dim : 0)); ++i) {
        const double x = get_double("node coordinate");
        if (i % (3 + (param ? dim : 0)) < 3) xyz_.push_back(x);
      }
    }
    if (read != total)
      fail_at(header, "the $Nodes header gives " + std::to_string(total) +
                                                            " nodes, its blocks " + std::to_string(read));
  }

  void read_nodes22() {
    const uint64_t n = get_count("node count", 8, 28, true);
    if (binary_) end_line("the node count");
    xyz_.reserve(3 * n);
    for (uint64_t i = 0; i < n; ++i) {
      const long l = here();
      nodes_.add(get_size("node tag"), l);
      for (int k = 0; k < 3; ++k) xyz_.push_back(get_double("node coordinate"));
    }
  }

  void read_elements(long start) {
    if (have_elements_) fail_at(start, "a second $Elements section");
    if (!have_nodes_) fail_at(start, "$Elements comes before $Nodes");
    have_elements_ = true;
    elements_line_ = start;
    end_line("$Elements");
    if (v41_) read_elements41();
    else read_elements22();
    expect_end("Elements");
  }

  void read_elements41() {
    const long header = here();
    const uint64_t nblocks = get_count("element block count", 8, 12 + size_w_);
    const uint64_t total = get_count("element count", 4, 2 * size_w_);
    get_size("minimum element tag");
    get_size("maximum element tag");
    uint64_t read = 0;
    std::vector<uint64_t> tags;
    for (uint64_t b = 0; b < nblocks; ++b) {
      const long bline = here();
      const long dim = get_int("entity dimension");
      const long entity = get_int("entity tag");
      const long type = get_int("element type");
      const GmshType info = gmsh_type(type);
      if (info.dim < 0) fail_at(bline, "element block: unknown Gmsh element type " + std::to_string(type));
      const uint64_t n = get_count("block element count", 2 * (1 + info.nodes), size_w_ * (1 + info.nodes));
      if (n > total - read)
        fail_at(bline, "element blocks hold more than the " + std::to_string(total) + " elements of the $Elements header");
      read += n;
      auto it = physical_.find({static_cast<int>(dim), entity});
      const int region = it != physical_.end() ? it->second : static_cast<int>(entity);
      tags.resize(info.nodes);
      for (uint64_t e = 0; e < n; ++e) {
        const long eline = here();
        const uint64_t id = get_size("element tag");
        for (auto& t : tags) t = get_size("element node tag");
        add_element(type, info, tags.data(), region, static_cast<long>(id), eline);
      }
    }
    if (read != total)
      fail_at(header, "the $Elements header gives " + std::to_string(total) + " elements, its blocks " +
                                std::to_string(read));
  }

  void read_elements22() {
    const uint64_t total = get_count("element count", 8, 12, true);
    if (binary_) end_line("the element count");
    std::vector<uint64_t> nodes;
    std::vector<long> tags;
    uint64_t read = 0;
    long type = 0, ntags = 0;
    uint64_t in_block = 0;  // binary: elements left in the current header's block
    GmshType info;
    while (read < total) {
      long eline = here();
      if (binary_ && in_block == 0) {
        type = get_int("element type");
        in_block = get_size("element count of the block");
        ntags = get_int("tag count");
        info = gmsh_type(type);
        if (info.dim < 0) fail_at(eline, "element block: unknown Gmsh element type " + std::to_string(type));
        if (in_block == 0 || in_block > total - read)
          fail_at(eline, "element block of " + std::to_string(in_block) + " elements: 1.." + std::to_string(total - read) + " expected");
        check_tags(ntags, eline);
        eline = line_;
      }
      const long id = get_int("element number");
      if (!binary_) {
        type = get_int("element type");
        info = gmsh_type(type);
        if (info.dim < 0) fail_at(eline, "element " + std::to_string(id) + ": unknown Gmsh element type " + std::to_string(type));
        ntags = get_int("tag count");
        check_tags(ntags, eline);
      }
      tags.resize(ntags);
      for (auto& t : tags) t = get_int("element tag");
      nodes.resize(info.nodes);
      for (auto& n : nodes) n = get_size("element node");
      ++read;
      if (binary_) --in_block;
      // Gmsh writes an element of several physical groups once per group.
      if (ntags >= 2 && type == last_type_ && tags[1] == last_entity_ && nodes == last_nodes_) continue;
      last_type_ = type;
      last_entity_ = ntags >= 2 ? tags[1] : LONG_MIN;
      last_nodes_ = nodes;
      const long region = ntags >= 1 && tags[0] != 0 ? tags[0] : ntags >= 2 ? tags[1] : 0;
      add_element(type, info, nodes.data(), static_cast<int>(region), id, eline);
    }
  }

  // A 2.2 tag count: each tag takes at least 2 bytes (4 in binary).
  void check_tags(long ntags, long line) const {
    if (ntags < 0 || static_cast<uint64_t>(ntags) > left() / (binary_ ? 4 : 2))
      fail_at(line, "element tag count " + std::to_string(ntags) + " is negative or larger than the file can hold");
  }

  // One element: a volume or surface cell, or skipped (points, lines, other 2D types).
  void add_element(long type, const GmshType& info, const uint64_t* tags, int region, long id, long line) {
    if (info.vtk == 0) {
      if (info.dim == 3)
        fail_at(line, "element " + std::to_string(id) + ": Gmsh element type " + std::to_string(type) + " (" + info.name +
                          ") is not supported (volume types read: 4 tetrahedron, 5 hexahedron, 6 prism, "
                          "11 10-node tetrahedron, 17 20-node hexahedron, 18 15-node prism)");
      if (info.dim == 2 && bad_surface_line_ == 0) {
        bad_surface_line_ = line;
        bad_surface_ = "element " + std::to_string(id) + ": Gmsh element type " + std::to_string(type) + " (" +
                       info.name + ") is not supported in a surface mesh (surface types read: 2 triangle, 3 quadrangle)";
      }
      return;
    }
    const int* order = orders_.of(type);
    int64_t idx[20];
    for (int i = 0; i < info.nodes; ++i) {
      const int k = nodes_.find(tags[order[i]]);
      if (k < 0)
        fail_at(line, "element " + std::to_string(id) + " refers to node tag " + std::to_string(tags[order[i]]) +
                          ", which $Nodes does not give");
      idx[i] = k;
    }
    (info.dim == 3 ? volume_ : surface_).add(info.vtk, idx, info.nodes, region, id, line);
  }

  mesh::Mesh build() {
    if (!have_nodes_) fail_at(0, "no $Nodes section");
    if (!have_elements_) fail_at(0, "no $Elements section");
    const long n = static_cast<long>(xyz_.size() / 3);
    Eigen::MatrixXd V(n, 3);
    for (long i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) V(i, k) = xyz_[3 * i + k];
    if (volume_.size() > 0) return volume_.finish(std::move(V));
    if (bad_surface_line_) fail_at(bad_surface_line_, bad_surface_);
    if (surface_.size() == 0)
      fail_at(elements_line_, "no volume or surface elements (tetrahedra, hexahedra, prisms, triangles, quadrangles)");
    return surface_.finish(std::move(V));
  }

  const std::string& path_;
  const std::string& s_;
  size_t pos_ = 0;
  long line_ = 1, tok_line_ = 1, elements_line_ = 0;
  bool v41_ = false, binary_ = false, swap_ = false;
  size_t size_w_ = 8;
  bool have_nodes_ = false, have_elements_ = false;
  std::map<std::pair<int, long>, int> physical_;  // (dim, entity tag) -> first physical tag
  NodeIndex nodes_;
  std::vector<double> xyz_;
  const GmshNodeOrders orders_;
  CellAssembly volume_, surface_;
  std::string bad_surface_;  // the first 2D element of a type not read, for a surface mesh
  long bad_surface_line_ = 0;
  long last_type_ = 0, last_entity_ = LONG_MIN;  // the 2.2 element before, to skip its repetition
  std::vector<uint64_t> last_nodes_;
};

}  // namespace

mesh::Mesh read_msh(const std::string& path) {
  const std::string text = load_file(path);
  return MshReader(path, text).read();
}

}  // namespace hexdom::io
