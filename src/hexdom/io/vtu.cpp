// read_vtu (declared in vtk.h): a small XML scanner for the VTKFile layout, and the decoders of
// its DataArrays (ascii, base64, appended raw or base64, zlib blocks).
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>

#include "hexdom/common/error.h"
#include "hexdom/io/cell_assembly.h"
#include "hexdom/io/text.h"
#include "hexdom/io/vtk.h"

namespace hexdom::io {

namespace {

struct Tag {
  std::string name;
  std::map<std::string, std::string> attrs;
  bool closing = false, self_closing = false;
  size_t begin = 0, end = 0;  // '<' and one past '>'
  std::string attr(const std::string& key, const std::string& fallback = "") const {
    auto it = attrs.find(key);
    return it == attrs.end() ? fallback : it->second;
  }
};

// A DataArray of a Piece: where its data is and what it holds.
struct Array {
  std::string name, type, format;
  long ncomp = 1;
  size_t offset = 0;              // appended: offset into the appended data
  size_t text_begin = 0, text_end = 0;  // inline: its text
  size_t tag = 0;                 // position of its tag (for messages)
};

struct Piece {
  long npts = 0, ncells = 0;
  size_t tag = 0;
  Array points, connectivity, offsets, types, region;
  bool has_points = false, has_conn = false, has_offsets = false, has_types = false, has_region = false;
  int region_score = 1000;
};

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

int base64_value(unsigned char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

class VtuReader {
 public:
  VtuReader(const std::string& path, const std::string& text) : path_(path), s_(text) {}

  mesh::Mesh read() {
    scan();
    Cells cells{CellAssembly(path_, "cell"), CellAssembly(path_, "cell")};
    std::vector<double> pts;
    long base = 0;
    for (const Piece& p : pieces_) {
      add_piece(p, base, pts, cells);
      base += p.npts;
    }
    Eigen::MatrixXd V(base, 3);
    for (long i = 0; i < base; ++i)
      for (int k = 0; k < 3; ++k) V(i, k) = pts[3 * i + k];
    // Volume cells, with the boundary faces some writers add beside them (ours, with face ids) left
    // out; a surface only when there is no volume cell.
    if (cells.volumes.size() > 0) return cells.volumes.finish(std::move(V));
    if (cells.quadratic_faces > 0)
      throw InputError(path_, 0, "second-order triangles and quads (VTK types 22 and 23) are read only beside volume cells");
    return cells.surfaces.finish(std::move(V));
  }

 private:
  // Line of a position of the XML part.
  long line_of(size_t pos) const {
    const size_t end = std::min({pos, xml_end_, s_.size()});
    return 1 + static_cast<long>(std::count(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
  }
  [[noreturn]] void fail(size_t pos, const std::string& what) const { throw InputError(path_, line_of(pos), what); }

  // The next tag at or after `pos` (text between tags skipped; comments, <?...?> and <!...> too).
  bool next_tag(size_t& pos, Tag& t) {
    for (;;) {
      pos = s_.find('<', pos);
      if (pos == std::string::npos || pos >= xml_end_) return false;
      if (s_.compare(pos, 4, "<!--") == 0) {
        size_t e = s_.find("-->", pos);
        if (e == std::string::npos) fail(pos, "a comment is not closed");
        pos = e + 3;
        continue;
      }
      if (s_.compare(pos, 2, "<?") == 0 || s_.compare(pos, 2, "<!") == 0) {
        size_t e = s_.find('>', pos);
        if (e == std::string::npos) fail(pos, "a declaration is not closed");
        pos = e + 1;
        continue;
      }
      break;
    }
    t = Tag();
    t.begin = pos;
    size_t i = pos + 1;
    if (i < s_.size() && s_[i] == '/') { t.closing = true; ++i; }
    auto name_char = [&](size_t k) {
      return k < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[k])) || s_[k] == '_' || s_[k] == ':' || s_[k] == '-');
    };
    size_t b = i;
    while (name_char(i)) ++i;
    if (i == b) fail(pos, "malformed tag: '<' not followed by a name");
    t.name = s_.substr(b, i - b);
    for (;;) {
      while (i < s_.size() && std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
      if (i >= s_.size()) fail(pos, "tag <" + t.name + "> is not closed (truncated?)");
      if (s_[i] == '>') { ++i; break; }
      if (s_[i] == '/' && i + 1 < s_.size() && s_[i + 1] == '>') { t.self_closing = true; i += 2; break; }
      size_t a = i;
      while (name_char(i)) ++i;
      if (i == a) fail(pos, "tag <" + t.name + ">: unexpected character '" + std::string(1, s_[i]) + "'");
      std::string key = s_.substr(a, i - a);
      while (i < s_.size() && std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
      if (i >= s_.size() || s_[i] != '=') fail(pos, "tag <" + t.name + ">: attribute " + key + " has no value");
      ++i;
      while (i < s_.size() && std::isspace(static_cast<unsigned char>(s_[i]))) ++i;
      if (i >= s_.size() || (s_[i] != '"' && s_[i] != '\'')) fail(pos, "tag <" + t.name + ">: attribute " + key + " is not quoted");
      const char q = s_[i++];
      size_t e = s_.find(q, i);
      if (e == std::string::npos) fail(pos, "tag <" + t.name + ">: attribute " + key + " is not closed");
      t.attrs[key] = s_.substr(i, e - i);
      i = e + 1;
    }
    t.end = i;
    pos = i;
    return true;
  }

  long count_attr(const Tag& t, const char* key) {
    const std::string v = t.attr(key);
    long n;
    if (!parse_int(v, n) || n < 0) fail(t.begin, "<" + t.name + "> " + key + " '" + v + "' is not a non-negative integer");
    if (static_cast<unsigned long>(n) > s_.size()) fail(t.begin, "<" + t.name + "> " + key + " " + v + " is larger than the file can hold");
    return n;
  }

  // The XML part: the VTKFile element, its Pieces and their DataArrays, up to <AppendedData>.
  void scan();
  void data_array(const Tag& t, size_t& pos, const std::string& section);
  struct Cells {
    CellAssembly volumes, surfaces;
    long quadratic_faces = 0;  // VTK 22 and 23 cells seen (skipped)
  };
  void add_piece(const Piece& p, long base, std::vector<double>& pts, Cells& cells);
  std::vector<double> values(const Array& a, size_t count, const char* what);
  size_t appended_start(const Array& a) const;
  std::vector<unsigned char> bytes_of(const Array& a);
  std::vector<unsigned char> unpack(const Array& a, const unsigned char* p, size_t n, size_t want);
  uint64_t header_word(const unsigned char* p) const;

  std::string path_;
  const std::string& s_;
  size_t xml_end_ = std::string::npos;  // where <AppendedData>'s data starts (or the end)
  size_t appended_ = std::string::npos, appended_end_ = 0;
  bool appended_base64_ = false, big_endian_ = false, zlib_ = false;
  size_t header_size_ = 4;
  std::vector<Piece> pieces_;
  std::vector<size_t> appended_offsets_;  // every appended array's offset (base64: its extent)
};

void VtuReader::scan() {
  size_t pos = 0;
  Tag t;
  const bool tag = next_tag(pos, t);
  if (!tag || t.name != "VTKFile") fail(tag ? t.begin : 0, "not a VTK XML file (no <VTKFile> element)");
  if (t.attr("type") != "UnstructuredGrid") fail(t.begin, "only UnstructuredGrid files are supported, found type '" + t.attr("type") + "'");
  const std::string order = t.attr("byte_order", "LittleEndian"), header = t.attr("header_type", "UInt32");
  const std::string compressor = t.attr("compressor");
  if (order != "LittleEndian" && order != "BigEndian") fail(t.begin, "byte_order '" + order + "' is neither LittleEndian nor BigEndian");
  if (header != "UInt32" && header != "UInt64") fail(t.begin, "header_type '" + header + "' is neither UInt32 nor UInt64");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    fail(t.begin, "compressor " + compressor + " is not supported (write with vtkZLibDataCompressor or none)");
  big_endian_ = order == "BigEndian";
  header_size_ = header == "UInt64" ? 8 : 4;
  zlib_ = !compressor.empty();
  std::string section;
  bool closed = false;
  while (next_tag(pos, t)) {
    if (t.closing) {
      closed = closed || t.name == "VTKFile";
      if (t.name == "Piece" || t.name == "Points" || t.name == "Cells" || t.name == "CellData") section.clear();
      continue;
    }
    if (t.name == "Piece") {
      pieces_.emplace_back();
      pieces_.back().tag = t.begin;
      pieces_.back().npts = count_attr(t, "NumberOfPoints");
      pieces_.back().ncells = count_attr(t, "NumberOfCells");
      if (!t.self_closing) section = "Piece";
    } else if (t.name == "Points" || t.name == "Cells" || t.name == "CellData" || t.name == "PointData" ||
               t.name == "FieldData") {
      if (!t.self_closing) section = t.name;
    } else if (t.name == "DataArray") {
      data_array(t, pos, section);
    } else if (t.name == "AppendedData") {
      const std::string enc = t.attr("encoding", "raw");
      if (enc != "raw" && enc != "base64") fail(t.begin, "AppendedData encoding '" + enc + "' is neither raw nor base64");
      appended_base64_ = enc == "base64";
      size_t u = s_.find('_', t.end);
      if (u == std::string::npos) fail(t.begin, "AppendedData has no '_' before its data");
      appended_ = u + 1;
      xml_end_ = t.end;
      appended_end_ = s_.rfind("</AppendedData>");
      if (appended_end_ == std::string::npos || appended_end_ < appended_) fail(t.begin, "AppendedData is not closed (truncated?)");
      break;
    }
  }
  if (appended_ != std::string::npos ? s_.find("</VTKFile>", appended_end_) == std::string::npos : !closed)
    fail(s_.size(), "the file ends before </VTKFile> (truncated?)");
  if (pieces_.empty()) throw InputError(path_, 0, "no <Piece> in the file");
  std::sort(appended_offsets_.begin(), appended_offsets_.end());
}

void VtuReader::data_array(const Tag& t, size_t& pos, const std::string& section) {
  if (pieces_.empty() || section.empty() || section == "PointData" || section == "FieldData") {
    if (!t.self_closing) {  // skip its data
      size_t e = s_.find("</DataArray>", pos);
      if (e == std::string::npos) fail(t.begin, "DataArray is not closed (truncated?)");
      pos = e + 12;
    }
    if (t.attr("format") == "appended") appended_offsets_.push_back(count_attr(t, "offset"));
    return;
  }
  Array a;
  a.name = t.attr("Name", section);
  a.type = t.attr("type");
  a.format = t.attr("format", "ascii");
  a.tag = t.begin;
  a.ncomp = t.attrs.count("NumberOfComponents") ? count_attr(t, "NumberOfComponents") : 1;
  if (a.format == "appended") {
    a.offset = count_attr(t, "offset");
    appended_offsets_.push_back(a.offset);
  } else if (a.format == "ascii" || a.format == "binary") {
    if (t.self_closing) fail(t.begin, "DataArray " + a.name + " has no data");
    // The data is the text up to the next tag (VTK may follow it with <InformationKey> elements).
    a.text_begin = t.end;
    a.text_end = s_.find('<', t.end);
    const size_t close = s_.find("</DataArray>", t.end);
    if (a.text_end == std::string::npos || close == std::string::npos)
      fail(t.begin, "DataArray " + a.name + " is not closed (truncated?)");
    pos = close + 12;
  } else {
    fail(t.begin, "DataArray " + a.name + ": format '" + a.format + "' is not ascii, binary or appended");
  }
  Piece& p = pieces_.back();
  if (section == "Points") {
    if (a.ncomp != 3) fail(t.begin, "Points have " + std::to_string(a.ncomp) + " components, expected 3");
    p.points = a;
    p.has_points = true;
  } else if (section == "Cells") {
    if (a.name == "connectivity") { p.connectivity = a; p.has_conn = true; }
    else if (a.name == "offsets") { p.offsets = a; p.has_offsets = true; }
    else if (a.name == "types") { p.types = a; p.has_types = true; }
    else if (a.name == "faces" || a.name == "faceoffsets") fail(t.begin, "polyhedron cells (" + a.name + ") are not supported");
  } else if (section == "CellData" && a.ncomp == 1 && region_array_rank(a.name) < p.region_score) {
    p.region = a;
    p.has_region = true;
    p.region_score = region_array_rank(a.name);
  }
}

uint64_t VtuReader::header_word(const unsigned char* p) const {
  uint64_t v = 0;
  for (size_t k = 0; k < header_size_; ++k) {
    const size_t byte = big_endian_ ? header_size_ - 1 - k : k;
    v |= static_cast<uint64_t>(p[byte]) << (8 * k);
  }
  return v;
}

// Where an appended array starts in the file; fails when there is no appended data or the offset
// lies past it.
size_t VtuReader::appended_start(const Array& a) const {
  if (appended_ == std::string::npos) fail(a.tag, "DataArray " + a.name + " is appended, but the file has no AppendedData");
  if (a.offset > appended_end_ - appended_) fail(a.tag, "DataArray " + a.name + ": offset " + std::to_string(a.offset) + " is past the appended data");
  return appended_ + a.offset;
}

// The decoded bytes of a base64 array (binary, or appended in base64), header included.
std::vector<unsigned char> VtuReader::bytes_of(const Array& a) {
  size_t b = a.text_begin, e = a.text_end;
  if (a.format == "appended") {
    b = appended_start(a);
    e = appended_end_;
    auto next = std::upper_bound(appended_offsets_.begin(), appended_offsets_.end(), a.offset);
    if (next != appended_offsets_.end()) e = std::min(e, appended_ + *next);
  }
  // Base64, as VTK writes it: the header and the data may be encoded separately, so '=' padding
  // may end a group in the middle; whitespace is skipped.
  std::vector<unsigned char> out;
  out.reserve((e - b) / 4 * 3 + 3);
  uint32_t acc = 0;
  int n = 0;
  for (size_t i = b; i < e; ++i) {
    const unsigned char c = static_cast<unsigned char>(s_[i]);
    if (std::isspace(c)) continue;
    if (c == '=') {  // end of a group: flush what it holds
      if (n == 2) out.push_back(static_cast<unsigned char>(acc >> 4));
      if (n == 3) { out.push_back(static_cast<unsigned char>(acc >> 10)); out.push_back(static_cast<unsigned char>(acc >> 2)); }
      acc = 0;
      n = 0;
      continue;
    }
    const int v = base64_value(c);
    if (v < 0) fail(a.tag, "DataArray " + a.name + ": '" + std::string(1, static_cast<char>(c)) + "' is not base64");
    acc = (acc << 6) | static_cast<uint32_t>(v);
    if (++n == 4) {
      out.push_back(static_cast<unsigned char>(acc >> 16));
      out.push_back(static_cast<unsigned char>(acc >> 8));
      out.push_back(static_cast<unsigned char>(acc));
      acc = 0;
      n = 0;
    }
  }
  if (n == 1) fail(a.tag, "DataArray " + a.name + ": base64 data ends inside a group (truncated?)");
  if (n == 2) out.push_back(static_cast<unsigned char>(acc >> 4));
  if (n == 3) { out.push_back(static_cast<unsigned char>(acc >> 10)); out.push_back(static_cast<unsigned char>(acc >> 2)); }
  return out;
}

// The `want` data bytes of a binary array from its header and data at `p` (n bytes available).
std::vector<unsigned char> VtuReader::unpack(const Array& a, const unsigned char* p, size_t n, size_t want) {
  const std::string what = "DataArray " + a.name;
  const size_t h = header_size_;
  if (!zlib_) {
    if (n < h) fail(a.tag, what + ": data ends in its header (truncated?)");
    const uint64_t size = header_word(p);
    if (size != want) fail(a.tag, what + ": its header gives " + std::to_string(size) + " bytes, expected " + std::to_string(want));
    if (size > n - h) fail(a.tag, what + ": " + std::to_string(size) + " bytes announced, " + std::to_string(n - h) + " present (truncated?)");
    return std::vector<unsigned char>(p + h, p + h + size);
  }
  if (n < 3 * h) fail(a.tag, what + ": data ends in its compression header (truncated?)");
  const uint64_t blocks = header_word(p), block = header_word(p + h), last = header_word(p + 2 * h);
  if (blocks > (n - 3 * h) / h) fail(a.tag, what + ": " + std::to_string(blocks) + " compressed blocks do not fit the data");
  if (block == 0 && blocks > 0) fail(a.tag, what + ": block size 0");
  if (blocks > 0 && (blocks - 1 > want / block || last > block))  // before any product can overflow
    fail(a.tag, what + ": " + std::to_string(blocks) + " blocks of " + std::to_string(block) + " bytes do not hold " +
                    std::to_string(want) + " bytes");
  const uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block + (last ? last : block);
  if (total != want) fail(a.tag, what + ": its blocks hold " + std::to_string(total) + " bytes, expected " + std::to_string(want));
  std::vector<unsigned char> out(want);
  size_t at = 3 * h + blocks * h, done = 0;
  for (uint64_t k = 0; k < blocks; ++k) {
    const uint64_t csize = header_word(p + 3 * h + k * h);
    if (csize > n - at) fail(a.tag, what + ": compressed block " + std::to_string(k) + " runs past the data (truncated?)");
    uLongf len = static_cast<uLongf>(k + 1 == blocks && last ? last : block);
    if (len > want - done) fail(a.tag, what + ": compressed block " + std::to_string(k) + " holds more than the array");
    const uLongf expect = len;
    if (uncompress(out.data() + done, &len, p + at, static_cast<uLong>(csize)) != Z_OK || len != expect)
      fail(a.tag, what + ": compressed block " + std::to_string(k) + " does not inflate to " + std::to_string(expect) + " bytes");
    at += csize;
    done += len;
  }
  return out;
}

// `count` values of an array, as doubles.
std::vector<double> VtuReader::values(const Array& a, size_t count, const char* what) {
  std::vector<double> out;
  if (a.format == "ascii") {
    out.reserve(std::min(count, (a.text_end - a.text_begin) / 2 + 1));
    auto fields = split_ws(std::string_view(s_).substr(a.text_begin, a.text_end - a.text_begin));
    if (fields.size() != count)
      fail(a.tag, std::string(what) + ": " + std::to_string(fields.size()) + " values, expected " + std::to_string(count));
    for (auto f : fields) {
      double d;
      if (!parse_double(f, d)) fail(a.tag, std::string(what) + ": '" + std::string(f.substr(0, 30)) + "' is not a finite number");
      out.push_back(d);
    }
    return out;
  }
  static const std::map<std::string, std::pair<int, char>> types = {
      {"Int8", {1, 'i'}}, {"UInt8", {1, 'u'}}, {"Int16", {2, 'i'}}, {"UInt16", {2, 'u'}}, {"Int32", {4, 'i'}},
      {"UInt32", {4, 'u'}}, {"Int64", {8, 'i'}}, {"UInt64", {8, 'u'}}, {"Float32", {4, 'f'}}, {"Float64", {8, 'f'}}};
  auto t = types.find(a.type);
  if (t == types.end()) fail(a.tag, std::string(what) + ": data type '" + a.type + "' is not supported");
  const size_t w = static_cast<size_t>(t->second.first);
  if (count > s_.size() * 1032 / w) fail(a.tag, std::string(what) + ": " + std::to_string(count) + " values cannot be in this file");
  std::vector<unsigned char> raw;
  std::vector<unsigned char> data;
  if (a.format == "appended" && !appended_base64_) {
    const size_t b = appended_start(a);
    data = unpack(a, reinterpret_cast<const unsigned char*>(s_.data()) + b, appended_end_ - b, count * w);
  } else {
    raw = bytes_of(a);
    data = unpack(a, raw.data(), raw.size(), count * w);
  }
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    unsigned char b[8];
    for (size_t k = 0; k < w; ++k) b[k] = data[i * w + (big_endian_ ? w - 1 - k : k)];
    uint64_t u = 0;
    std::memcpy(&u, b, w);  // little-endian host
    double v;
    if (t->second.second == 'f') {
      if (w == 4) { float f; std::memcpy(&f, b, 4); v = f; }
      else { std::memcpy(&v, b, 8); }
      if (!std::isfinite(v)) fail(a.tag, std::string(what) + ": value " + std::to_string(i) + " is not finite");
    } else if (t->second.second == 'u') {
      v = static_cast<double>(u);
    } else {
      const int shift = static_cast<int>(64 - 8 * w);
      v = static_cast<double>(static_cast<int64_t>(u << shift) >> shift);
    }
    out[i] = v;
  }
  return out;
}

void VtuReader::add_piece(const Piece& p, long base, std::vector<double>& pts, Cells& cells) {
  if (!p.has_points && p.npts > 0) fail(p.tag, "Piece has no Points");
  if (p.ncells > 0 && !(p.has_conn && p.has_offsets && p.has_types))
    fail(p.tag, "Piece's Cells need connectivity, offsets and types arrays");
  if (p.npts > 0) {
    auto v = values(p.points, static_cast<size_t>(3 * p.npts), "Points");
    pts.insert(pts.end(), v.begin(), v.end());
  }
  if (p.ncells == 0) return;
  const size_t nc = static_cast<size_t>(p.ncells);
  auto off = values(p.offsets, nc, "offsets");
  auto types = values(p.types, nc, "types");
  for (size_t c = 0; c < nc; ++c) {
    const double lo = c ? off[c - 1] : 0;
    if (off[c] != std::floor(off[c]) || off[c] < lo || off[c] > lo + 20)
      fail(p.offsets.tag, "offsets: cell " + std::to_string(c) + " ends at " + std::to_string(off[c]) +
                              ", not within 0..20 entries after the previous cell");
  }
  auto conn = values(p.connectivity, static_cast<size_t>(off.back()), "connectivity");
  std::vector<double> region;
  if (p.has_region) region = values(p.region, nc, p.region.name.c_str());
  int64_t n[20];
  const long types_line = line_of(p.types.tag), cells_line = line_of(p.connectivity.tag);
  for (size_t c = 0; c < nc; ++c) {
    const size_t b = c ? static_cast<size_t>(off[c - 1]) : 0, e = static_cast<size_t>(off[c]);
    for (size_t j = b; j < e; ++j) {
      if (conn[j] != std::floor(conn[j]) || conn[j] < 0 || conn[j] >= p.npts)
        fail(p.connectivity.tag, "cell " + std::to_string(c) + " refers to point " + number(conn[j]) +
                                     ", but the piece has " + std::to_string(p.npts) + " points");
      n[j - b] = base + static_cast<int64_t>(conn[j]);
    }
    int r = 0;
    if (!region.empty()) {
      if (region[c] != std::floor(region[c]) || std::fabs(region[c]) > 2147483647.0)
        fail(p.region.tag, "cell " + std::to_string(c) + ": region id " + number(region[c]) + " is not a 32-bit integer");
      r = static_cast<int>(region[c]);
    }
    const double t = types[c];
    const int vt = t == std::floor(t) && t >= 0 && t < 256 ? static_cast<int>(t) : -1;
    if (vt == 22 || vt == 23) cells.quadratic_faces++;
    else (vt == 5 || vt == 9 ? cells.surfaces : cells.volumes).add(vt, n, static_cast<int>(e - b), r, static_cast<long>(c), cells_line, types_line);
  }
}

}  // namespace

mesh::Mesh read_vtu(const std::string& path) {
  const std::string text = load_file(path);
  return VtuReader(path, text).read();
}

}  // namespace hexdom::io
