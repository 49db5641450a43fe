#include "hexdom/io/vtk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <stdexcept>

#include "hexdom/common/error.h"
#include "hexdom/io/cell_assembly.h"
#include "hexdom/io/text.h"
#include "hexdom/mesh/second_order.h"

namespace hexdom::io {

using mesh::CellType;

namespace {

// Line of each value of one data section, stored compactly: the index of the first value on each
// new line. Binary sections have a single entry (the line where their bytes start).
struct LineIndex {
  std::vector<size_t> first;
  std::vector<long> line;
  void note(size_t i, long l) {
    if (line.empty() || line.back() != l) { first.push_back(i); line.push_back(l); }
  }
  long at(size_t i) const {
    if (first.empty()) return 0;
    size_t k = std::upper_bound(first.begin(), first.end(), i) - first.begin();
    return line[k ? k - 1 : 0];
  }
};

// Token and raw-byte reader over a legacy VTK buffer, keeping line numbers for messages.
class Scanner {
 public:
  Scanner(const std::string& path, const std::string& text) : path_(path), s_(text) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_, line_, what); }
  [[noreturn]] void fail_at(long line, const std::string& what) const { throw InputError(path_, line, what); }
  const std::string& path() const { return path_; }

  // Next blank-separated token; "" at end of file.
  std::string token() {
    skip_space();
    size_t b = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return s_.substr(b, pos_ - b);
  }
  std::string need_token(const char* what) {
    std::string t = token();
    if (t.empty()) fail(std::string("file ends where ") + what + " was expected (truncated?)");
    return t;
  }
  long need_int(const char* what) {
    std::string t = need_token(what);
    long v;
    if (!parse_int(t, v) || v < 0) fail(std::string(what) + " '" + t + "' is not a non-negative integer");
    return v;
  }
  // A count from a section header. Every value takes at least one byte, so a count larger than the
  // file is corrupt; refusing it here also keeps products of counts from overflowing.
  long need_count(const char* what) {
    long v = need_int(what);
    if (static_cast<unsigned long>(v) > s_.size())
      fail(std::string(what) + " " + std::to_string(v) + " is larger than the file can hold (corrupt header?)");
    return v;
  }
  // Rest of the current line (after the last token).
  std::string rest_of_line() {
    size_t b = pos_;
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    std::string r(s_.substr(b, pos_ - b));
    if (pos_ < s_.size()) { ++pos_; ++line_; }
    return std::string(trim(r));
  }
  std::string line() { return rest_of_line(); }
  long line_no() const { return line_; }
  bool at_end() { skip_space(); return pos_ >= s_.size(); }

  // Reads `n` numbers of VTK data type `type`, ASCII or big-endian binary; notes the line of each
  // value in `lines` when given.
  std::vector<double> numbers(size_t n, const std::string& type, bool binary, const char* what,
                              LineIndex* lines = nullptr) {
    const size_t w = binary ? type_size(type) : 0;  // ASCII numbers are read whatever their type
    const size_t left = s_.size() - std::min(pos_, s_.size());
    std::vector<double> out;
    if (!binary) {
      out.reserve(std::min(n, left / 2 + 1));  // a corrupt count must not allocate
      for (size_t i = 0; i < n; ++i) {
        std::string t = token();
        if (t.empty())
          fail(std::string(what) + ": file ends after " + std::to_string(i) + " of " +
               std::to_string(n) + " values (truncated?)");
        double d;
        if (!parse_double(t, d)) fail(std::string(what) + ": '" + t + "' is not a finite number");
        out.push_back(d);
        if (lines) lines->note(i, line_);
      }
      return out;
    }
    // Binary data starts right after the newline that ends the header line.
    if (n > left / w)
      fail(std::string(what) + ": binary data needs " + std::to_string(n) + " x " + std::to_string(w) +
           " bytes, " + std::to_string(left) + " left (truncated?)");
    out.resize(n);
    const unsigned char* p = reinterpret_cast<const unsigned char*>(s_.data() + pos_);
    for (size_t i = 0; i < n; ++i, p += w) out[i] = decode(p, w, type);
    pos_ += n * w;
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(out[i])) fail(std::string(what) + ": value " + std::to_string(i) + " is not finite");
    if (lines) lines->note(0, line_);
    return out;
  }

  // Like numbers(), for values that must be integers (counts, indices, cell types).
  std::vector<int64_t> integers(size_t n, const std::string& type, bool binary, const char* what,
                                LineIndex& lines) {
    auto v = numbers(n, type, binary, what, &lines);
    std::vector<int64_t> out(v.size());
    for (size_t i = 0; i < v.size(); ++i) {
      if (v[i] != std::floor(v[i]) || std::fabs(v[i]) > 9007199254740992.0) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", v[i]);
        fail_at(lines.at(i), std::string(what) + ": '" + buf + "' is not a valid integer");
      }
      out[i] = static_cast<int64_t>(v[i]);
    }
    return out;
  }

  // Skips a newline directly following binary data.
  void end_binary() {
    if (pos_ < s_.size() && s_[pos_] == '\n') { ++pos_; ++line_; }
  }

  size_t type_size(const std::string& type) const {
    std::string t = lower(type);
    if (t == "float" || t == "int" || t == "unsigned_int" || t == "vtktypeint32" || t == "vtktypeuint32") return 4;
    if (t == "double" || t == "long" || t == "unsigned_long" || t == "vtktypeint64" || t == "vtktypeuint64" || t == "vtkidtype") return 8;
    if (t == "short" || t == "unsigned_short") return 2;
    if (t == "char" || t == "signed_char" || t == "unsigned_char" || t == "bit") return 1;
    fail("unsupported data type '" + type + "'");
  }

 private:
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  double decode(const unsigned char* p, size_t w, const std::string& type) const {
    uint64_t u = 0;
    for (size_t i = 0; i < w; ++i) u = (u << 8) | p[i];
    std::string t = lower(type);
    if (t == "float") { uint32_t v = static_cast<uint32_t>(u); float f; std::memcpy(&f, &v, 4); return f; }
    if (t == "double") { double d; std::memcpy(&d, &u, 8); return d; }
    if (t.rfind("unsigned", 0) == 0 || t == "vtktypeuint32" || t == "vtktypeuint64" || t == "bit")
      return static_cast<double>(u);
    // signed integers: sign-extend
    int64_t v = static_cast<int64_t>(u << (64 - 8 * w)) >> (64 - 8 * w);
    return static_cast<double>(v);
  }

  std::string path_;
  const std::string& s_;
  size_t pos_ = 0;
  long line_ = 1;
};

/// Reads the header lines; returns whether the data is binary. Fails unless the file is a legacy
/// VTK UNSTRUCTURED_GRID or POLYDATA.
bool read_header(Scanner& sc) {
  std::string head = sc.line();
  if (!starts_with_ci(head, "# vtk DataFile"))
    sc.fail_at(1, "not a legacy VTK file (first line must be '# vtk DataFile Version ...')");
  sc.line();  // title
  std::string mode = lower(sc.line());
  if (mode != "ascii" && mode != "binary") sc.fail_at(3, "third line must be ASCII or BINARY, found '" + mode + "'");
  const bool binary = mode == "binary";
  std::string ds = sc.need_token("DATASET");
  if (lower(ds) != "dataset") sc.fail("expected DATASET, found '" + ds + "'");
  std::string kind = lower(sc.need_token("dataset type"));
  if (kind != "unstructured_grid" && kind != "polydata")
    sc.fail("only UNSTRUCTURED_GRID and POLYDATA datasets are supported, found " + kind);
  sc.rest_of_line();
  return binary;
}

// The sections of a legacy VTK file after its header, read one by one into points, cells, cell
// types and region ids, then checked and built into a mesh.
class VtkReader {
 public:
  VtkReader(Scanner& sc, bool binary) : sc(sc), binary(binary) {}

  // Reads every section to the end of the file.
  void read_sections() {
    while (!sc.at_end()) {
      std::string key = lower(sc.need_token("section keyword"));
      if (key == "points") {
        read_points();
      } else if (key == "cells" || key == "polygons") {
        read_cells(key);
      } else if (key == "cell_types") {
        read_cell_types();
      } else if (key == "cell_data" || key == "point_data") {
        read_attribute_header(key);
      } else if (key == "scalars" || key == "vectors" || key == "normals" || key == "tensors" ||
                 key == "texture_coordinates" || key == "color_scalars") {
        read_attribute(key);
      } else if (key == "lookup_table") {
        read_lookup_table();
      } else if (key == "field") {
        read_field();
      } else if (key == "metadata") {
        sc.rest_of_line();
        while (!sc.at_end() && !sc.line().empty()) {}
      } else if (key == "vertices" || key == "lines" || key == "triangle_strips") {
        sc.fail("POLYDATA " + key + " are not supported: only polygons (triangles, quads)");
      } else {
        sc.fail("unknown section '" + key + "'");
      }
    }
  }

  // The mesh of the sections read, after checking that they agree.
  mesh::Mesh build() {
    if (npts < 0) sc.fail("no POINTS section");
    if (offsets.empty()) sc.fail("no CELLS section");
    const long ncells = static_cast<long>(offsets.size()) - 1;
    if (types.size() != static_cast<size_t>(ncells))
      sc.fail_at(types_line ? types_line : sc.line_no(), "CELL_TYPES count " + std::to_string(types.size()) +
                                                             " differs from CELLS count " + std::to_string(ncells));
    if (!region.empty() && static_cast<long>(region.size()) != ncells) region.clear();
    CellAssembly cells(sc.path(), "cell");
    for (long c = 0; c < ncells; ++c) add_cell(cells, c);
    Eigen::MatrixXd V(npts, 3);
    for (long i = 0; i < npts; ++i)
      for (int k = 0; k < 3; ++k) V(i, k) = pts[3 * i + k];
    return cells.finish(std::move(V));
  }

 private:
  void read_points() {
    npts = sc.need_count("point count");
    std::string type = sc.need_token("point data type");
    if (binary) sc.type_size(type);  // an unknown binary type is the header line's error
    sc.rest_of_line();
    pts = sc.numbers(static_cast<size_t>(3 * npts), type, binary, "POINTS");
    if (binary) sc.end_binary();
  }

  // CELLS (or POLYGONS): the classic layout, a node count and the nodes per cell, or the 5.1 layout.
  void read_cells(const std::string& key) {
    long n = sc.need_count("cell count"), size = sc.need_count("cell list size");
    sc.rest_of_line();
    if (sc.at_end()) sc.fail("file ends after the CELLS header (truncated?)");
    // VTK 5.1 layout: "CELLS noffsets nconn" followed by OFFSETS and CONNECTIVITY arrays.
    {
      Scanner probe = sc;
      std::string t = lower(probe.token());
      if (t == "offsets") {
        read_offsets_layout(n, size);
        if (key == "polygons") types.assign(n - 1, -1);
        return;
      }
    }
    cell_lines = LineIndex();
    auto v = sc.integers(static_cast<size_t>(size), "int", binary, "CELLS", cell_lines);
    if (binary) sc.end_binary();
    offsets.assign(1, 0);
    conn.clear();
    classic_cells = true;
    size_t i = 0;
    for (long c = 0; c < n; ++c) {
      if (i >= v.size()) sc.fail("CELLS: list ends at cell " + std::to_string(c) + " of " + std::to_string(n));
      const int64_t k = v[i++];
      if (k < 0 || k > static_cast<int64_t>(v.size() - i))
        sc.fail_at(cell_lines.at(i - 1), "CELLS: cell " + std::to_string(c) + " claims " + std::to_string(k) +
                                             " nodes beyond the list");
      for (int64_t j = 0; j < k; ++j) conn.push_back(v[i++]);
      offsets.push_back(static_cast<int64_t>(conn.size()));
    }
    if (key == "polygons") types.assign(n, -1);
  }

  // The OFFSETS and CONNECTIVITY arrays of the 5.1 layout, in either order.
  void read_offsets_layout(long noff, long nconn) {
    const long header_line = sc.line_no();
    if (noff < 1) sc.fail("CELLS: the 5.1 layout needs at least one offset, found " + std::to_string(noff));
    for (int part = 0; part < 2; ++part) {
      std::string key = lower(sc.need_token("OFFSETS/CONNECTIVITY"));
      std::string type = sc.need_token("data type");
      long n = key == "offsets" ? noff : key == "connectivity" ? nconn : -1;
      if (n < 0) sc.fail("expected OFFSETS or CONNECTIVITY, found '" + key + "'");
      if (binary) sc.type_size(type);  // an unknown binary type is the header line's error
      sc.rest_of_line();
      auto& lines = key == "offsets" ? offset_lines : cell_lines;
      auto v = sc.integers(static_cast<size_t>(n), type, binary, key.c_str(), lines);
      if (binary) sc.end_binary();
      (key == "offsets" ? offsets : conn) = std::move(v);
    }
    classic_cells = false;
    // Offsets start at 0, never decrease and end at the connectivity size.
    for (size_t i = 0; i < offsets.size(); ++i) {
      const int64_t lo = i ? offsets[i - 1] : 0;
      if (offsets[i] < lo || offsets[i] > static_cast<int64_t>(conn.size()) || (i == 0 && offsets[0] != 0))
        sc.fail_at(offset_lines.at(i), "OFFSETS: offset " + std::to_string(i) + " is " + std::to_string(offsets[i]) +
                                           ", outside " + std::to_string(lo) + ".." + std::to_string(conn.size()));
    }
    if (offsets.back() != static_cast<int64_t>(conn.size()))
      sc.fail_at(header_line, "OFFSETS: the last offset is " + std::to_string(offsets.back()) + ", but CONNECTIVITY has " +
                                  std::to_string(conn.size()) + " entries");
  }

  void read_cell_types() {
    types_line = sc.line_no();
    long n = sc.need_count("cell type count");
    sc.rest_of_line();
    type_lines = LineIndex();
    types = sc.integers(static_cast<size_t>(n), "int", binary, "CELL_TYPES", type_lines);
    if (binary) sc.end_binary();
  }

  // CELL_DATA or POINT_DATA: the arrays that follow belong to the cells or to the points.
  void read_attribute_header(const std::string& key) {
    long n = sc.need_count("attribute count");
    attr = key == "cell_data" ? CellData : PointData;
    if (attr == CellData) ncell_data = n;
    else if (n != npts) sc.fail("POINT_DATA count " + std::to_string(n) + " differs from POINTS " + std::to_string(npts));
    sc.rest_of_line();
  }

  // An attribute array (SCALARS, VECTORS, ...); a one-component cell array with a region name is
  // kept as the region ids when its name ranks before the one kept so far.
  void read_attribute(const std::string& key) {
    if (attr == None) sc.fail(key + " outside CELL_DATA/POINT_DATA");
    std::string name = sc.need_token("array name");
    long ncomp = 1;
    std::string type = "float";
    if (key == "color_scalars") { ncomp = sc.need_count("component count"); type = binary ? "unsigned_char" : "float"; }
    else if (key == "texture_coordinates") { ncomp = sc.need_count("dimension"); type = sc.need_token("data type"); }
    else {
      type = sc.need_token("data type");
      if (key == "vectors" || key == "normals") ncomp = 3;
      if (key == "tensors") ncomp = 9;
    }
    if (binary) sc.type_size(type);  // an unknown binary type is the header line's error
    const long header_line = sc.line_no();
    std::string rest = sc.rest_of_line();
    if (key == "scalars" && !rest.empty()) {
      long c;
      if (!parse_int(rest, c) || c < 1 || c > 4) sc.fail_at(header_line, "SCALARS component count '" + rest + "' must be 1..4");
      ncomp = c;
    }
    if (key == "scalars") {
      // Optional LOOKUP_TABLE line.
      Scanner probe = sc;
      if (lower(probe.token()) == "lookup_table") { sc.token(); sc.rest_of_line(); }
    }
    long count = attr == CellData ? ncell_data : npts;
    LineIndex lines;
    auto v = sc.numbers(static_cast<size_t>(count * ncomp), type, binary, key.c_str(), &lines);
    if (binary) sc.end_binary();
    if (attr == CellData && ncomp == 1 && region_array_rank(name) < region_score) {
      region = std::move(v);
      region_lines = std::move(lines);
      region_score = region_array_rank(name);
    }
  }

  void read_lookup_table() {
    sc.need_token("table name");
    long n = sc.need_count("table size");
    sc.rest_of_line();
    sc.numbers(static_cast<size_t>(4 * n), binary ? "unsigned_char" : "float", binary, "LOOKUP_TABLE");
    if (binary) sc.end_binary();
  }

  // FIELD arrays; as in read_attribute, a one-component cell array with a region name may give
  // the region ids.
  void read_field() {
    sc.need_token("field name");
    long narr = sc.need_count("array count");
    sc.rest_of_line();
    for (long a = 0; a < narr; ++a) {
      std::string name = sc.need_token("array name");
      if (lower(name) == "null_array") continue;
      long ncomp = sc.need_count("component count"), ntup = sc.need_count("tuple count");
      std::string type = sc.need_token("data type");
      if (lower(type) == "string") sc.fail("string field arrays are not supported");
      if (binary) sc.type_size(type);  // an unknown binary type is the header line's error
      sc.rest_of_line();
      LineIndex lines;
      auto v = sc.numbers(static_cast<size_t>(ncomp * ntup), type, binary, name.c_str(), &lines);
      if (binary) sc.end_binary();
      if (attr == CellData && ncomp == 1 && ntup == ncell_data && region_array_rank(name) < region_score) {
        region = std::move(v);
        region_lines = std::move(lines);
        region_score = region_array_rank(name);
      }
      // VTK 9 may follow an array by a METADATA block ending at an empty line.
      Scanner probe = sc;
      if (lower(probe.token()) == "metadata") {
        sc.token();
        sc.rest_of_line();
        while (!sc.at_end() && !sc.line().empty()) {}
      }
    }
  }

  // Line of node j of cell c (j = -1: the cell's start).
  long cell_line(long c, long j) const {
    if (classic_cells) return cell_lines.at(static_cast<size_t>(offsets[c] + c + 1 + j));
    if (j < 0 || offsets[c] + j >= static_cast<int64_t>(conn.size())) return offset_lines.at(static_cast<size_t>(c + 1));
    return cell_lines.at(static_cast<size_t>(offsets[c] + j));
  }

  // Cell c into the assembly, after checking its nodes and region id.
  void add_cell(CellAssembly& cells, long c) {
    const long k = static_cast<long>(offsets[c + 1] - offsets[c]);
    if (k < 3 || k > 20) sc.fail_at(cell_line(c, -1), "cell " + std::to_string(c) + " has " + std::to_string(k) + " nodes");
    for (long j = 0; j < k; ++j) {
      int64_t v = conn[offsets[c] + j];
      if (v < 0 || v >= npts)
        sc.fail_at(cell_line(c, j), "cell " + std::to_string(c) + " refers to point " + std::to_string(v) +
                                        ", but there are " + std::to_string(npts) + " points");
    }
    const int64_t t64 = types[c];
    int t = static_cast<int>(std::clamp<int64_t>(t64, INT32_MIN, INT32_MAX));
    if (t == -1) t = k == 3 ? 5 : k == 4 ? 9 : 0;  // POLYDATA polygons
    int rid = 0;
    if (!region.empty()) {
      const double r = region[c];
      if (r != std::floor(r) || std::fabs(r) > 2147483647.0) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", r);
        sc.fail_at(region_lines.at(c), "cell " + std::to_string(c) + ": region id " + buf + " is not a 32-bit integer");
      }
      rid = static_cast<int>(r);
    }
    const long tline = type_lines.at(c) ? type_lines.at(c) : cell_line(c, -1);
    cells.add(t, &conn[offsets[c]], static_cast<int>(k), rid, c, cell_line(c, -1), tline);
  }

  Scanner& sc;
  const bool binary;
  std::vector<double> pts;
  long npts = -1;
  std::vector<int64_t> offsets, conn;  // cell i uses conn[offsets[i] .. offsets[i+1])
  std::vector<int64_t> types;
  std::vector<double> region;
  // Where the values came from, for messages: cell lists (classic layout: count, then nodes;
  // 5.1 layout: the connectivity array), offsets (5.1), cell types, region ids.
  LineIndex cell_lines, offset_lines, type_lines, region_lines;
  bool classic_cells = true;
  long types_line = 0;
  int region_score = 1000;
  long ncell_data = -1;
  enum { None, PointData, CellData } attr = None;
};

}  // namespace

mesh::Mesh read_vtk(const std::string& path) {
  const std::string text = load_file(path);
  Scanner sc(path, text);
  VtkReader reader(sc, read_header(sc));
  reader.read_sections();
  return reader.build();
}

namespace {

void put_be(std::ostream& out, const void* data, size_t w) {
  unsigned char b[8];
  std::memcpy(b, data, w);
  for (size_t i = 0; i < w; ++i) out.put(static_cast<char>(b[w - 1 - i]));
}

}  // namespace

void write_vtk(const std::string& path, const mesh::Mesh& m, bool binary) {
  write_atomically(path, binary, [&](std::ostream& out) {
    out << "# vtk DataFile Version 4.2\nHexDom mesh\n" << (binary ? "BINARY" : "ASCII")
        << "\nDATASET UNSTRUCTURED_GRID\n";
    out.precision(17);
    out << "POINTS " << m.num_nodes() << " double\n";
    for (int i = 0; i < m.num_nodes(); ++i) {
      if (binary) for (int k = 0; k < 3; ++k) put_be(out, &m.V(i, k), 8);
      else out << m.V(i, 0) << ' ' << m.V(i, 1) << ' ' << m.V(i, 2) << '\n';
    }
    if (binary) out << '\n';
    long size = 0;
    int nodes[20];
    for (int c = 0; c < m.num_cells(); ++c) size += 1 + mesh::cell_nodes(m, c, nodes);
    out << "CELLS " << m.num_cells() << ' ' << size << '\n';
    for (int c = 0; c < m.num_cells(); ++c) {
      int32_t k = mesh::cell_nodes(m, c, nodes);
      if (binary) {
        put_be(out, &k, 4);
        for (int j = 0; j < k; ++j) { int32_t v = nodes[j]; put_be(out, &v, 4); }
      } else {
        out << k;
        for (int j = 0; j < k; ++j) out << ' ' << nodes[j];
        out << '\n';
      }
    }
    if (binary) out << '\n';
    out << "CELL_TYPES " << m.num_cells() << '\n';
    for (int c = 0; c < m.num_cells(); ++c) {
      int32_t t = m.vtk_type(c);
      if (binary) put_be(out, &t, 4);
      else out << t << '\n';
    }
    if (binary) out << '\n';
    out << "CELL_DATA " << m.num_cells() << "\nSCALARS region int 1\nLOOKUP_TABLE default\n";
    for (int c = 0; c < m.num_cells(); ++c) {
      int32_t r = m.region(c);
      if (binary) put_be(out, &r, 4);
      else out << r << '\n';
    }
    if (binary) out << '\n';
  });
}

namespace {

std::string base64(const unsigned char* data, size_t n) {
  static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve(4 * ((n + 2) / 3));
  for (size_t i = 0; i < n; i += 3) {
    uint32_t v = static_cast<uint32_t>(data[i]) << 16;
    if (i + 1 < n) v |= static_cast<uint32_t>(data[i + 1]) << 8;
    if (i + 2 < n) v |= data[i + 2];
    out += tbl[(v >> 18) & 63];
    out += tbl[(v >> 12) & 63];
    out += i + 1 < n ? tbl[(v >> 6) & 63] : '=';
    out += i + 2 < n ? tbl[v & 63] : '=';
  }
  return out;
}

// One binary DataArray: a UInt64 byte count followed by the data, base64-encoded as one block.
template <class T>
void data_array(std::ostream& out, const char* vtk_type, const char* name, int ncomp,
                const std::vector<T>& values) {
  std::vector<unsigned char> bytes(8 + values.size() * sizeof(T));
  uint64_t nbytes = values.size() * sizeof(T);
  std::memcpy(bytes.data(), &nbytes, 8);
  if (!values.empty()) std::memcpy(bytes.data() + 8, values.data(), nbytes);
  out << "        <DataArray type=\"" << vtk_type << "\" Name=\"" << name
      << "\" NumberOfComponents=\"" << ncomp << "\" format=\"binary\">\n          "
      << base64(bytes.data(), bytes.size()) << "\n        </DataArray>\n";
}

}  // namespace

void write_vtu(const std::string& path, const mesh::Mesh& m, const FaceSets* faces) {
  const size_t nb = faces ? faces->faces.size() : 0;
  write_atomically(path, false, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << m.num_nodes() << "\" NumberOfCells=\"" << m.num_cells() + nb
        << "\">\n      <Points>\n";
    std::vector<double> pts(3 * static_cast<size_t>(m.num_nodes()));
    for (int i = 0; i < m.num_nodes(); ++i)
      for (int k = 0; k < 3; ++k) pts[3 * i + k] = m.V(i, k);
    data_array(out, "Float64", "Points", 3, pts);
    out << "      </Points>\n      <Cells>\n";
    std::vector<int64_t> conn, offsets;
    std::vector<uint8_t> types;
    int nodes[20];
    for (int c = 0; c < m.num_cells(); ++c) {
      const int k = mesh::cell_nodes(m, c, nodes);
      conn.insert(conn.end(), nodes, nodes + k);
      offsets.push_back(static_cast<int64_t>(conn.size()));
      types.push_back(static_cast<uint8_t>(m.vtk_type(c)));
    }
    for (size_t i = 0; i < nb; ++i) {
      const mesh::BoundaryFace& f = faces->faces[i];
      const std::vector<int> own = mesh::face_nodes(m, f);
      conn.insert(conn.end(), own.begin(), own.end());
      offsets.push_back(static_cast<int64_t>(conn.size()));
      types.push_back(static_cast<uint8_t>(f.n == 3 ? (m.second_order() ? 22 : 5) : (m.second_order() ? 23 : 9)));
    }
    data_array(out, "Int64", "connectivity", 1, conn);
    data_array(out, "Int64", "offsets", 1, offsets);
    data_array(out, "UInt8", "types", 1, types);
    out << "      </Cells>\n      <CellData Scalars=\"region\">\n";
    std::vector<int32_t> reg(m.region.data(), m.region.data() + m.num_cells());
    reg.resize(reg.size() + nb, 0);
    data_array(out, "Int32", "region", 1, reg);
    if (nb > 0) {
      std::vector<int32_t> face_id(static_cast<size_t>(m.num_cells()), 0);
      for (size_t i = 0; i < nb; ++i) face_id.push_back(i < faces->tag.size() ? faces->tag[i] : 0);
      data_array(out, "Int32", "face_id", 1, face_id);
    }
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace hexdom::io
