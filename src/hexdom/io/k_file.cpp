#include "hexdom/io/k_file.h"

#include <climits>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <unordered_map>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/io/cell_assembly.h"
#include "hexdom/io/text.h"

namespace hexdom::io {

using mesh::CellType;

namespace {

// LS-DYNA keyword families we accept and skip (their cards carry nothing a mesh needs).
const char* const kSkippedFamilies[] = {
    "PART", "SECTION", "MAT", "CONTROL", "DATABASE", "TITLE", "SET", "BOUNDARY", "LOAD",
    "INITIAL", "DEFINE", "CONSTRAINED", "CONTACT", "COMMENT", "HOURGLASS", "EOS", "ELEMENT_",
    "INCLUDE", "PARAMETER", "NODE_", "INTEGRATION", "RIGIDWALL", "TERMINATION", "DAMPING",
    "FREQUENCY", "INTERFACE", "AIRBAG", "USER"};

enum class Section { None, Node, Shell, Solid, SolidH20, Skip };

// Fields of a data line: comma-separated, blank-separated, or fixed width when blanks give fewer
// than `min_fields` (numbers that fill their columns run together).
std::vector<std::string_view> fields(std::string_view line, size_t min_fields,
                                     const std::vector<int>& widths) {
  if (line.find(',') != std::string_view::npos) return split_commas(line);
  auto f = split_ws(line);
  if (f.size() >= min_fields) return f;
  std::vector<std::string_view> fixed;
  size_t pos = 0;
  for (int w : widths) {
    if (pos >= line.size()) break;
    auto part = trim(line.substr(pos, w));
    if (!part.empty()) fixed.push_back(part);
    pos += w;
  }
  return fixed.size() > f.size() ? fixed : f;
}

// Ids are kept as int (KFile::node_ids, element_ids, region).
bool fits_int(long v) { return v >= INT_MIN && v <= INT_MAX; }

struct PendingElement {
  long line;
  long eid;
  long pid;
  bool solid;
  long n[20];
  int count = 8;  ///< nodes: 8 (a solid, maybe collapsed), 4 (a shell), 10 (a 10-node tet), 20 (a 20-node hex)
};

// Node ids of a card of an element whose first card was read: `want` integers, as many as the card has.
void node_card(LineCursor& cur, std::string_view data, PendingElement& e, int from, int want) {
  auto f = fields(data, want, std::vector<int>(want, 8));
  if (static_cast<int>(f.size()) < want)
    cur.fail("element " + std::to_string(e.eid) + ": a card of " + std::to_string(want) + " node ids expected, found " +
             std::to_string(f.size()) + " fields");
  for (int k = 0; k < want; ++k)
    if (!parse_int(f[k], e.n[from + k]))
      cur.fail("element " + std::to_string(e.eid) + ": node '" + std::string(f[k]) + "' is not an integer");
}

// One element of an *ELEMENT_SHELL, *ELEMENT_SOLID or *ELEMENT_SOLID_H20 section, from its first
// card `data` (the cursor on it) and, for the 20-node hex and the ten-node format, the node cards
// after it.
PendingElement read_element(LineCursor& cur, std::string_view data, Section section) {
  const bool solid = section != Section::Shell, h20 = section == Section::SolidH20;
  const size_t need = h20 ? 2 : solid ? 10 : 5;
  auto f = fields(data, need, std::vector<int>(10, 8));
  // *ELEMENT_SOLID's ten-node format: "eid pid" on a card of its own, the nodes on the next.
  const bool ten = section == Section::Solid && f.size() == 2;
  if (f.size() < need && !ten)
    cur.fail(std::string(h20     ? "*ELEMENT_SOLID_H20 expects an element id and a part id"
                         : solid ? "*ELEMENT_SOLID expects 10 fields (or 2, for its ten-node format)"
                                 : "*ELEMENT_SHELL expects at least 5 fields") +
             ", found " + std::to_string(f.size()));
  PendingElement e{cur.line(), 0, 0, solid, {}};
  if (!parse_int(f[0], e.eid) || !parse_int(f[1], e.pid)) cur.fail("element id and part id must be integers");
  if (!fits_int(e.eid) || !fits_int(e.pid)) cur.fail("element id and part id must be 32-bit integers");
  if (h20 || ten) {
    // The node cards: 10 ids each, two for the 20-node hex. A ten-node card whose last two ids are
    // 0 holds an 8-node solid.
    for (int card = 0; card < (h20 ? 2 : 1); ++card) {
      std::string_view next;
      do {
        if (!cur.next(next)) cur.fail("element " + std::to_string(e.eid) + ": the file ends before its node card");
      } while (next.empty() || next[0] == '$' || trim(next).empty());
      if (trim(next)[0] == '*') cur.fail("element " + std::to_string(e.eid) + ": a keyword where its node card should be");
      node_card(cur, next.substr(0, next.find_last_not_of(" \t\r") + 1), e, 10 * card, 10);
    }
    e.count = h20 ? 20 : (e.n[8] == 0 && e.n[9] == 0) ? 8 : 10;
    return e;
  }
  const int nn = solid ? 8 : 4;
  for (int k = 0; k < nn; ++k) {
    if (2 + k >= static_cast<int>(f.size())) continue;  // a missing node id is 0
    if (!parse_int(f[2 + k], e.n[k]))
      cur.fail("element " + std::to_string(e.eid) + ": node '" + std::string(f[2 + k]) + "' is not an integer");
  }
  return e;
}

// The index in the *NODE order of node `id`, which element `e` refers to; an InputError at the
// element's line when no *NODE defines it.
int node_of(const std::string& path, const std::unordered_map<long, int>& node_index,
            const PendingElement& e, long id) {
  auto it = node_index.find(id);
  if (it == node_index.end())
    throw InputError(path, e.line, "element " + std::to_string(e.eid) + " refers to node " + std::to_string(id) +
                                       ", which no *NODE defines");
  return it->second;
}

// The mesh of `elements` (some with 10 or 20 nodes) on `points` through io::CellAssembly; `eids`
// receives their ids.
mesh::Mesh second_order_mesh(const std::string& path, const std::vector<PendingElement>& elements,
                             const std::unordered_map<long, int>& node_index, Eigen::MatrixXd points,
                             std::vector<int>& eids) {
  CellAssembly cells(path, "element");
  for (const auto& e : elements) {
    int64_t n[20];
    const int count = e.solid ? e.count : 4;
    for (int k = 0; k < count; ++k) n[k] = node_of(path, node_index, e, e.n[k]);
    const int vtk = !e.solid ? 9 : e.count == 20 ? 25 : e.count == 10 ? 24 : 12;
    cells.add(vtk, n, count, static_cast<int>(e.pid), e.eid, e.line);
    eids.push_back(static_cast<int>(e.eid));
  }
  return cells.finish(std::move(points));
}

}  // namespace

KFile read_k(const std::string& path) {
  const std::string text = load_file(path);
  LineCursor cur(path, text);
  Section section = Section::None;
  std::vector<double> xyz;
  std::vector<long> node_ids;
  std::unordered_map<long, int> node_index;
  std::vector<long> node_lines;
  std::vector<PendingElement> elements;
  bool saw_keyword = false, saw_end = false;

  std::string_view raw;
  while (cur.next(raw)) {
    if (raw.empty() || raw[0] == '$') continue;
    std::string_view line = trim(raw);
    if (line.empty()) continue;
    // Fixed-width fields count columns from the start of the line: keep its leading blanks.
    std::string_view data = raw.substr(0, raw.find_last_not_of(" \t\r") + 1);
    if (saw_end) continue;  // anything after *END is ignored, as LS-DYNA does
    if (line[0] == '*') {
      std::string kw = lower(trim(line.substr(1)));
      size_t sp = kw.find_first_of(" \t");
      if (sp != std::string::npos) kw = kw.substr(0, sp);
      if (kw == "keyword") { saw_keyword = true; section = Section::None; }
      else if (kw == "node") section = Section::Node;
      else if (kw == "element_shell") section = Section::Shell;
      else if (kw == "element_solid") section = Section::Solid;
      else if (kw == "element_solid_h20") section = Section::SolidH20;
      else if (kw == "end") { section = Section::None; saw_end = true; }
      else {
        bool known = false;
        for (const char* fam : kSkippedFamilies) known = known || starts_with_ci(kw, fam);
        if (!known) cur.fail("unknown keyword *" + std::string(trim(line.substr(1))));
        section = Section::Skip;
      }
      continue;
    }
    switch (section) {
      case Section::None:
        cur.fail(saw_keyword ? "data line outside any keyword section"
                             : "not an LS-DYNA keyword file (no *KEYWORD before data)");
      case Section::Skip: break;
      case Section::Node: {
        auto f = fields(data, 4, {8, 16, 16, 16, 8, 8});
        if (f.size() < 4)
          cur.fail("*NODE expects an id and 3 coordinates, found " + std::to_string(f.size()) +
                   " fields");
        long id;
        double p[3];
        if (!parse_int(f[0], id)) cur.fail("*NODE id '" + std::string(f[0]) + "' is not an integer");
        if (!fits_int(id)) cur.fail("*NODE id " + std::string(f[0]) + " is not a 32-bit integer");
        for (int k = 0; k < 3; ++k)
          if (!parse_double(f[1 + k], p[k]))
            cur.fail("*NODE " + std::to_string(id) + ": coordinate '" + std::string(f[1 + k]) +
                     "' is not a finite number");
        if (!node_index.emplace(id, static_cast<int>(node_ids.size())).second)
          cur.fail("node id " + std::to_string(id) + " is defined twice (first on line " +
                   std::to_string(node_lines[node_index[id]]) + ")");
        node_ids.push_back(id);
        node_lines.push_back(cur.line());
        xyz.insert(xyz.end(), p, p + 3);
        break;
      }
      case Section::Shell:
      case Section::Solid:
      case Section::SolidH20: elements.push_back(read_element(cur, data, section)); break;
    }
  }
  if (node_ids.empty()) throw InputError(path, cur.line(), "no *NODE data: the file holds no nodes");
  if (elements.empty())
    throw InputError(path, cur.line(), "no *ELEMENT_SHELL or *ELEMENT_SOLID data: the file holds no elements");

  KFile out;
  const int nv = static_cast<int>(node_ids.size());
  out.mesh.V = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(xyz.data(), nv, 3);
  out.node_ids.resize(nv);
  for (int i = 0; i < nv; ++i) out.node_ids(i) = static_cast<int>(node_ids[i]);

  std::vector<int> eids;
  // Second-order solids (20-node hexes, 10-node tets) make a second-order mesh, with the checks of
  // the other readers (io::CellAssembly: one order for the whole mesh, shared mid-edge nodes).
  bool second = false;
  for (const auto& e : elements) second = second || e.count >= 10;
  if (second) {
    out.mesh = second_order_mesh(path, elements, node_index, std::move(out.mesh.V), eids);
    out.element_ids = Eigen::Map<Eigen::VectorXi>(eids.data(), static_cast<int>(eids.size()));
    return out;
  }
  mesh::MeshBuilder b;
  for (const auto& e : elements) {
    auto index = [&](long id) { return node_of(path, node_index, e, id); };
    if (e.solid) {
      std::array<int, 8> h;
      for (int k = 0; k < 8; ++k) h[k] = index(e.n[k]);
      mesh::DegenerateHex d;
      try {
        d = mesh::classify_hex_nodes(h);
      } catch (const std::invalid_argument&) {
        std::string ids;
        for (int k = 0; k < 8; ++k) ids += " " + std::to_string(e.n[k]);
        throw InputError(path, e.line, "solid " + std::to_string(e.eid) + " (nodes" + ids +
                                           ") is neither a hex, a prism (n1..n4,n5,n5,n6,n6 or "
                                           "n1,n2,n3,n3,n5..n7,n7) nor a tet (n1..n4,n4,n4,n4,n4)");
      }
      b.add(d.type, d.nodes.data(), static_cast<int>(e.pid));
    } else {
      int q[4] = {index(e.n[0]), index(e.n[1]), index(e.n[2]), 0};
      bool tri = e.n[3] == 0 || e.n[3] == e.n[2];
      if (!tri) q[3] = index(e.n[3]);
      int k = tri ? 3 : 4;
      for (int i = 0; i < k; ++i)
        for (int j = i + 1; j < k; ++j)
          if (q[i] == q[j])
            throw InputError(path, e.line, "shell " + std::to_string(e.eid) +
                                               " repeats node " + std::to_string(e.n[i]));
      b.add(tri ? CellType::Triangle : CellType::Quad, q, static_cast<int>(e.pid));
    }
    eids.push_back(static_cast<int>(e.eid));
  }
  out.mesh = b.finish(std::move(out.mesh.V));
  out.element_ids = Eigen::Map<Eigen::VectorXi>(eids.data(), static_cast<int>(eids.size()));
  return out;
}

void write_k(const std::string& path, const mesh::Mesh& m, const FaceSets* faces) {
  if (m.second_order()) {
    int wedges = 0, first = -1;
    for (int c = 0; c < m.num_cells(); ++c)
      if (m.type(c) == CellType::Wedge && wedges++ == 0) first = c;
    if (wedges > 0)
      throw InputError(path, 0, fmt("LS-DYNA's keyword has no 15-node pentahedron, and %.0f of the cells are ", double(wedges)) +
                                    fmt("15-node wedges (the first: cell %.0f); write .inp, .vtu, .vtk or .msh, or mesh with order 1",
                                        double(first + 1)));
  }
  write_atomically(path, false, [&](std::ostream& out) {
    char buf[160];
    out << "$# LS-DYNA keyword file written by HexDom " HEXDOM_VERSION "\n*KEYWORD\n";
    bool has_shell = false, has_solid = false;
    for (int c = 0; c < m.num_cells(); ++c) (mesh::is_volume(m.type(c)) ? has_solid : has_shell) = true;
    int eid = 0;
    if (has_shell) {
      out << "*ELEMENT_SHELL\n";
      for (int c = 0; c < m.num_cells(); ++c) {
        if (mesh::is_volume(m.type(c))) continue;
        const auto n = m.cells.row(c);
        int n4 = m.type(c) == CellType::Quad ? n(3) : n(2);
        std::snprintf(buf, sizeof buf, "%8d%8d%8d%8d%8d%8d\n", ++eid, m.region(c), n(0) + 1,
                      n(1) + 1, n(2) + 1, n4 + 1);
        out << buf;
      }
    }
    if (has_solid && m.second_order()) {
      // 20-node hexes (*ELEMENT_SOLID_H20) and 10-node tets (*ELEMENT_SOLID's ten-node format):
      // LS-DYNA's node orders are VTK's quadratic ones; a keyword per run of one type keeps the
      // cells' order. write_k refused 15-node wedges before.
      int nodes[20];
      for (int c = 0, previous = -1; c < m.num_cells(); ++c) {
        const CellType t = m.type(c);
        if (static_cast<int>(t) != previous)
          out << (t == CellType::Hex ? "*ELEMENT_SOLID_H20\n" : "*ELEMENT_SOLID (ten nodes format)\n");
        previous = static_cast<int>(t);
        const int n = mesh::cell_nodes(m, c, nodes);
        std::snprintf(buf, sizeof buf, "%8d%8d\n", ++eid, m.region(c));
        out << buf;
        for (int k = 0; k < n; ++k) {
          std::snprintf(buf, sizeof buf, "%8d", nodes[k] + 1);
          out << buf << (k % 10 == 9 || k == n - 1 ? "\n" : "");
        }
      }
    } else if (has_solid) {
      out << "*ELEMENT_SOLID\n";
      for (int c = 0; c < m.num_cells(); ++c) {
        if (!mesh::is_volume(m.type(c))) continue;
        auto h = mesh::to_hex_nodes(m.type(c), m.cells.row(c).data());
        std::snprintf(buf, sizeof buf, "%8d%8d%8d%8d%8d%8d%8d%8d%8d%8d\n", ++eid, m.region(c),
                      h[0] + 1, h[1] + 1, h[2] + 1, h[3] + 1, h[4] + 1, h[5] + 1, h[6] + 1,
                      h[7] + 1);
        out << buf;
      }
    }
    out << "*NODE\n";
    for (int i = 0; i < m.num_nodes(); ++i) {
      // Free (comma) format: a 16-character column would cut coordinates to 9 digits.
      double x = m.V(i, 0), y = m.V(i, 1), z = m.V(i, 2);
      std::snprintf(buf, sizeof buf, "%d,%.17g,%.17g,%.17g\n", i + 1, x, y, z);
      out << buf;
    }
    if (faces) {
      for (const auto& [tag, list] : faces->by_tag()) {
        std::snprintf(buf, sizeof buf, "*SET_SEGMENT_TITLE\nFace%d\n%10d\n", tag, tag);
        out << buf;
        for (size_t i : list) {
          const mesh::BoundaryFace& f = faces->faces[i];
          std::snprintf(buf, sizeof buf, "%10d%10d%10d%10d\n", f.v[0] + 1, f.v[1] + 1, f.v[2] + 1, f.v[f.n - 1] + 1);
          out << buf;
        }
      }
    }
    out << "*END\n";
  });
}

std::vector<CornerPoint> read_corner_points(const std::string& path) {
  const std::string text = load_file(path);
  LineCursor cur(path, text);
  std::vector<CornerPoint> pts;
  std::string_view line;
  while (cur.next(line)) {
    auto f = split_ws(line);
    if (f.empty()) continue;
    if (f.size() < 4) cur.fail("corner point expects 'vertex x y z', found " + std::to_string(f.size()) + " fields");
    CornerPoint c;
    long v;
    if (!parse_int(f[0], v) || v < 0) cur.fail("vertex index '" + std::string(f[0]) + "' is not a non-negative integer");
    c.vertex = static_cast<int>(v);
    for (int k = 0; k < 3; ++k)
      if (!parse_double(f[1 + k], c.p[k])) cur.fail("coordinate '" + std::string(f[1 + k]) + "' is not a finite number");
    pts.push_back(c);
  }
  if (pts.empty()) throw InputError(path, 0, "no corner points");
  return pts;
}

std::vector<int> read_sharp_nodes(const std::string& path) {
  const std::string text = load_file(path);
  LineCursor cur(path, text);
  std::vector<int> nodes;
  std::string_view line;
  while (cur.next(line)) {
    auto f = split_ws(line);
    if (f.empty()) continue;
    long v;
    if (!parse_int(f.back(), v) || v < 0) cur.fail("expected a 0-based node index at the end of the line");
    nodes.push_back(static_cast<int>(v));
  }
  return nodes;
}

}  // namespace hexdom::io
