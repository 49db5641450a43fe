#include "hexdom/io/inp.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>
#include <ostream>
#include <set>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/io/cell_assembly.h"
#include "hexdom/io/text.h"
#include "hexdom/mesh/cell_faces.h"

namespace hexdom::io {

using mesh::CellType;

namespace {

// Abaqus's face n (S1, S2, ...) of an element type as its 1-based corners, the element's nodes in
// .inp order (C3D8 / C3D20, C3D6 / C3D15, C3D4 / C3D10 share them).
const std::vector<std::vector<int>>& abaqus_faces(CellType t) {
  static const std::vector<std::vector<int>> hex = {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2},
                                                    {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}};
  static const std::vector<std::vector<int>> wedge = {{1, 2, 3}, {4, 6, 5}, {1, 4, 5, 2}, {2, 5, 6, 3}, {3, 6, 4, 1}};
  static const std::vector<std::vector<int>> tet = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
  return t == CellType::Hex ? hex : t == CellType::Wedge ? wedge : tet;
}

// The .inp corner j of a cell is VTK corner kInpCorner(t)[j] (the prism's first face reversed).
const int* inp_corners(CellType t) {
  static const int identity[8] = {0, 1, 2, 3, 4, 5, 6, 7}, wedge[6] = {0, 2, 1, 3, 5, 4};
  return t == CellType::Wedge ? wedge : identity;
}

// Abaqus's face number (1-based) of boundary face f of its cell; 0 when no face has its corners.
int abaqus_face(const mesh::Mesh& m, const mesh::BoundaryFace& f) {
  const CellType t = m.type(f.cell);
  if (!mesh::is_volume(t)) return 0;
  std::vector<int> want(f.v.begin(), f.v.begin() + f.n);
  std::sort(want.begin(), want.end());
  const auto& faces = abaqus_faces(t);
  const int* corner = inp_corners(t);
  for (size_t k = 0; k < faces.size(); ++k) {
    if (static_cast<int>(faces[k].size()) != f.n) continue;
    std::vector<int> have;
    for (int j : faces[k]) have.push_back(m.cells(f.cell, corner[j - 1]));
    std::sort(have.begin(), have.end());
    if (have == want) return static_cast<int>(k) + 1;
  }
  return 0;
}

// *NSET and *SURFACE per tag of `sets` (see write_inp).
void write_face_sets(std::ostream& out, const mesh::Mesh& m, const FaceSets& sets) {
  for (const auto& [tag, faces] : sets.by_tag()) {
    const std::vector<int> nodes = set_nodes(m, sets, tag);
    out << "*NSET, NSET=Face" << tag << "\n";
    for (size_t i = 0; i < nodes.size(); ++i)
      out << nodes[i] + 1 << ((i + 1) % 16 == 0 || i + 1 == nodes.size() ? "\n" : ", ");
    out << "*SURFACE, NAME=Face" << tag << ", TYPE=ELEMENT\n";
    for (size_t i : faces) {
      const int s = abaqus_face(m, sets.faces[i]);
      if (s > 0) out << sets.faces[i].cell + 1 << ", S" << s << "\n";
    }
  }
}

}  // namespace

void write_inp(const std::string& path, const mesh::Mesh& m, const FaceSets* sets) {
  write_atomically(path, false, [&](std::ostream& out) {
    char buf[256];
    out << "*HEADING\nHexDom mesh (" << m.count(CellType::Hex) << " hex, "
        << m.count(CellType::Wedge) << " prism, " << m.count(CellType::Tet) << " tet)\n*NODE\n";
    for (int i = 0; i < m.num_nodes(); ++i) {
      std::snprintf(buf, sizeof buf, "%d, %.17g, %.17g, %.17g\n", i + 1, m.V(i, 0), m.V(i, 1), m.V(i, 2));
      out << buf;
    }
    struct Block { CellType type; const char* name; std::vector<int> order; };
    // Second order: the VTK node lists (corners, then mid-edge nodes in cell_edges order); C3D20
    // and C3D10 number theirs the same way, C3D15 follows its reversed corners.
    const std::vector<Block> blocks =
        m.second_order()
            ? std::vector<Block>{{CellType::Hex, "C3D20", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19}},
                                 {CellType::Wedge, "C3D15", {0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13}},
                                 {CellType::Tet, "C3D10", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}}}
            : std::vector<Block>{{CellType::Hex, "C3D8", {0, 1, 2, 3, 4, 5, 6, 7}},
                                 {CellType::Wedge, "C3D6", {0, 2, 1, 3, 5, 4}},
                                 {CellType::Tet, "C3D4", {0, 1, 2, 3}},
                                 {CellType::Quad, "S4", {0, 1, 2, 3}},
                                 {CellType::Triangle, "S3", {0, 1, 2}}};
    int nodes[20];
    std::map<int, std::vector<int>> regions;
    std::vector<int> volume;
    for (const Block& b : blocks) {
      if (m.count(b.type) == 0) continue;
      out << "*ELEMENT, TYPE=" << b.name << "\n";
      for (int c = 0; c < m.num_cells(); ++c) {
        if (m.type(c) != b.type) continue;
        mesh::cell_nodes(m, c, nodes);
        out << c + 1;
        for (size_t j = 0; j < b.order.size(); ++j)  // Abaqus: at most 16 entries on a data line
          out << (j == 15 ? ",\n" : ", ") << nodes[b.order[j]] + 1;
        out << '\n';
        regions[m.region(c)].push_back(c + 1);
        if (mesh::is_volume(b.type)) volume.push_back(c + 1);
      }
    }
    auto write_set = [&](const std::string& name, const std::vector<int>& ids) {
      out << "*ELSET, ELSET=" << name << "\n";
      for (size_t i = 0; i < ids.size(); ++i)
        out << ids[i] << ((i + 1) % 16 == 0 || i + 1 == ids.size() ? "\n" : ", ");
    };
    for (const auto& [r, ids] : regions) write_set("REGION_" + std::to_string(r), ids);
    if (!volume.empty()) write_set("EALL", volume);
    if (sets) write_face_sets(out, m, *sets);
  });
}

}  // namespace hexdom::io

namespace hexdom::io {

namespace {

// "*KEYWORD, PARAM=VALUE, FLAG" split into the keyword (upper case, no star) and its parameters.
struct Keyword {
  std::string name;
  std::map<std::string, std::string> params;  // upper-case names; values as written (trimmed)
};

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

Keyword parse_keyword(std::string_view line) {
  Keyword k;
  auto fields = split_commas(line.substr(1));
  k.name = upper(fields.empty() ? std::string_view() : fields[0]);
  for (size_t i = 1; i < fields.size(); ++i) {
    const size_t eq = fields[i].find('=');
    if (eq == std::string_view::npos) k.params[upper(trim(fields[i]))] = "";
    else k.params[upper(trim(fields[i].substr(0, eq)))] = std::string(trim(fields[i].substr(eq + 1)));
  }
  return k;
}

// An element type: its VTK type, node count and the VTK position of each .inp node.
struct InpType {
  int vtk = 0;
  std::vector<int> to_vtk;  // vtk[to_vtk[j]] = inp node j
  bool solid() const { return vtk != 5 && vtk != 9; }
};

// The element type of a TYPE= value (prefix and any letter suffix), or vtk 0 when unsupported.
InpType inp_type(const std::string& name) {
  struct Entry { const char* prefix; int vtk; std::vector<int> to_vtk; };
  static const std::vector<Entry> table = {
      {"C3D20", 25, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19}},
      {"C3D15", 26, {0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13}},
      {"C3D10", 24, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}},
      {"C3D8", 12, {0, 1, 2, 3, 4, 5, 6, 7}},
      {"C3D6", 13, {0, 2, 1, 3, 5, 4}},
      {"C3D4", 10, {0, 1, 2, 3}},
      {"S4", 9, {0, 1, 2, 3}},
      {"S3", 5, {0, 1, 2}}};
  for (const Entry& e : table) {
    const size_t n = std::strlen(e.prefix);
    if (name.compare(0, n, e.prefix) != 0) continue;
    bool letters = true;  // C3D8R, C3D10M, S4R: letters only after the base name
    for (size_t i = n; i < name.size(); ++i) letters = letters && std::isalpha(static_cast<unsigned char>(name[i]));
    if (letters) return {e.vtk, e.to_vtk};
  }
  return {};
}

struct PendingElement {
  long id, line;
  int type;            // index into InpReader::types_
  int set;             // index into InpReader::set_names_ of its *ELEMENT ELSET=, or -1
  size_t first;        // its node ids: nodes_[first .. first + count)
};

class InpReader {
 public:
  InpReader(const std::string& path, std::string_view text) : cur_(path, text), path_(path) {}

  mesh::Mesh read() {
    std::string_view line;
    bool have = cur_.next(line);
    while (have) {
      line = trim(line);
      if (line.empty() || line.substr(0, 2) == "**") { have = cur_.next(line); continue; }
      if (line[0] != '*') cur_.fail("data line outside a keyword: '" + std::string(line.substr(0, 40)) + "'");
      const Keyword k = parse_keyword(line);
      if (k.name == "NODE") have = read_nodes(line);
      else if (k.name == "ELEMENT") have = read_elements(k, line);
      else if (k.name == "NSET" || k.name == "ELSET") have = read_set(k, line);
      else if (k.name == "INCLUDE") cur_.fail("*INCLUDE is not supported: put the included file's lines in this one");
      else have = skip_data(line);
    }
    return assemble();
  }

 private:
  // Next non-comment line into `line`; false at the end of the file or at a keyword line (left in `line`).
  bool next_data(std::string_view& line, bool& at_keyword) {
    at_keyword = false;
    while (cur_.next(line)) {
      line = trim(line);
      if (line.empty() || line.substr(0, 2) == "**") continue;
      if (line[0] == '*') { at_keyword = true; return false; }
      return true;
    }
    return false;
  }

  bool skip_data(std::string_view& line) {
    bool kw;
    while (next_data(line, kw)) {}
    return kw;
  }

  long need_id(std::string_view field, const char* what) {
    long v;
    if (!parse_int(field, v) || v <= 0)
      cur_.fail(std::string(what) + " '" + std::string(field.substr(0, 30)) + "' is not a positive integer");
    return v;
  }

  bool read_nodes(std::string_view& line) {
    bool kw;
    while (next_data(line, kw)) {
      auto f = split_commas(line);
      if (f.size() < 2 || f.size() > 4) cur_.fail("a *NODE line is 'id, x, y, z', found " + std::to_string(f.size()) + " fields");
      const long id = need_id(f[0], "node id");
      double x[3] = {0, 0, 0};
      for (size_t k = 1; k < f.size(); ++k)
        if (!parse_double(f[k], x[k - 1])) cur_.fail("node " + std::to_string(id) + ": '" + std::string(f[k].substr(0, 30)) + "' is not a finite number");
      if (!node_index_.emplace(id, static_cast<int>(points_.size() / 3)).second)
        cur_.fail("node " + std::to_string(id) + " is defined twice");
      points_.insert(points_.end(), x, x + 3);
    }
    return kw;
  }

  bool read_elements(const Keyword& k, std::string_view& line) {
    auto t = k.params.find("TYPE");
    if (t == k.params.end()) cur_.fail("*ELEMENT without TYPE=");
    InpType type = inp_type(upper(t->second));
    if (type.vtk == 0)
      cur_.fail("element type " + t->second + " is not supported (supported: C3D8, C3D6, C3D4, C3D20, C3D15, C3D10 "
                "with any suffix, S3, S4)");
    types_.push_back(type);
    int set = -1;
    auto e = k.params.find("ELSET");
    if (e != k.params.end()) set = set_index(e->second);
    const size_t count = type.to_vtk.size();
    bool kw;
    while (next_data(line, kw)) {
      auto f = split_commas(line);
      if (!f.empty() && f.back().empty()) f.pop_back();  // a line ending with a comma continues
      if (f.empty()) cur_.fail("empty element line");
      PendingElement el{need_id(f[0], "element id"), cur_.line(), static_cast<int>(types_.size() - 1), set, nodes_.size()};
      if (!element_ids_.insert(el.id).second) cur_.fail("element " + std::to_string(el.id) + " is defined twice");
      for (size_t j = 1; j < f.size(); ++j) nodes_.push_back(need_id(f[j], "node id"));
      while (nodes_.size() - el.first < count) {
        bool kw2;
        if (!next_data(line, kw2))
          cur_.fail("element " + std::to_string(el.id) + " (" + t->second + ") has " + std::to_string(nodes_.size() - el.first) +
                    " nodes, expected " + std::to_string(count));
        auto g = split_commas(line);
        if (!g.empty() && g.back().empty()) g.pop_back();
        for (auto& field : g) nodes_.push_back(need_id(field, "node id"));
      }
      if (nodes_.size() - el.first != count)
        cur_.fail("element " + std::to_string(el.id) + " (" + t->second + ") has " + std::to_string(nodes_.size() - el.first) +
                  " nodes, expected " + std::to_string(count));
      elements_.push_back(el);
      if (set >= 0) set_elements_[set].push_back(el.id);
    }
    return kw;
  }

  // Index of the element set `name` (from *ELEMENT ELSET= or *ELSET), or -1 when no such set exists.
  int find_set(const std::string& name) const {
    auto it = std::find(set_names_.begin(), set_names_.end(), upper(name));
    return it == set_names_.end() ? -1 : static_cast<int>(it - set_names_.begin());
  }

  int set_index(const std::string& name) {
    const int s = find_set(name);
    if (s >= 0) return s;
    set_names_.push_back(upper(name));
    set_elements_.emplace_back();
    return static_cast<int>(set_names_.size() - 1);
  }

  // *NSET / *ELSET: ids (or set names), or GENERATE ranges "first, last [, step]". Members are
  // checked at the end, once every node and element is known.
  bool read_set(const Keyword& k, std::string_view& line) {
    const bool nodes = k.name == "NSET";
    auto n = k.params.find(nodes ? "NSET" : "ELSET");
    if (n == k.params.end() || n->second.empty()) cur_.fail("*" + k.name + " without " + k.name + "=");
    const bool generate = k.params.count("GENERATE") > 0;
    const int members = nodes ? -1 : set_index(n->second);
    bool kw;
    while (next_data(line, kw)) {
      auto f = split_commas(line);
      if (!f.empty() && f.back().empty()) f.pop_back();
      if (generate) {
        if (f.size() < 2 || f.size() > 3) cur_.fail("a GENERATE line is 'first, last [, step]'");
        const long a = need_id(f[0], "first id"), b = need_id(f[1], "last id"), s = f.size() == 3 ? need_id(f[2], "step") : 1;
        if (b < a || (b - a) / s > 100000000) cur_.fail("GENERATE range " + std::to_string(a) + ".." + std::to_string(b) + " is empty or too long");
        for (long v = a; v <= b; v += s) set_members_.push_back({nodes, v, cur_.line(), members});
        continue;
      }
      for (auto& field : f) {
        long v;
        if (parse_int(field, v)) {
          if (v <= 0) cur_.fail("set member '" + std::string(field) + "' is not a positive id");
          set_members_.push_back({nodes, v, cur_.line(), members});
        } else if (nodes ? nset_names_.count(upper(field)) > 0 : find_set(std::string(field)) >= 0) {
          if (!nodes) set_includes_.push_back({members, find_set(std::string(field))});
        } else {
          cur_.fail("*" + k.name + " " + n->second + ": '" + std::string(field.substr(0, 40)) + "' is neither an id nor a set defined above");
        }
      }
    }
    if (nodes) nset_names_.insert(upper(n->second));
    return kw;
  }

  mesh::Mesh assemble();

  struct Member { bool node; long id, line; int elset; };  // elset: index of the element set, or -1
  LineCursor cur_;
  std::string path_;
  std::vector<double> points_;
  std::unordered_map<long, int> node_index_;
  std::unordered_set<long> element_ids_;
  std::vector<InpType> types_;
  std::vector<PendingElement> elements_;
  std::vector<long> nodes_;  // node ids of every element, in file order
  std::vector<std::string> set_names_;  // element sets (upper case)
  std::vector<std::vector<long>> set_elements_;
  std::set<std::string> nset_names_;
  std::vector<std::pair<int, int>> set_includes_;  // (element set, element set named among its members), in file order
  std::vector<Member> set_members_;
};

mesh::Mesh InpReader::assemble() {
  if (points_.empty()) throw InputError(path_, 0, "no *NODE data: the file holds no mesh");
  if (elements_.empty()) throw InputError(path_, 0, "no *ELEMENT data: the file holds no mesh");
  for (const Member& m : set_members_) {
    if (m.node ? !node_index_.count(m.id) : !element_ids_.count(m.id))
      throw InputError(path_, m.line, std::string(m.node ? "node " : "element ") + std::to_string(m.id) +
                                          " of a set is not defined in the file");
    if (m.elset >= 0) set_elements_[m.elset].push_back(m.id);
  }
  for (auto [to, from] : set_includes_)
    if (to != from) set_elements_[to].insert(set_elements_[to].end(), set_elements_[from].begin(), set_elements_[from].end());
  // Region of each element id: REGION_<n> sets when present, else the *ELEMENT sets numbered 1, 2, ...
  std::unordered_map<long, int> region;
  bool numbered = false;
  for (size_t s = 0; s < set_names_.size(); ++s) {
    long n;
    if (set_names_[s].rfind("REGION_", 0) != 0 || !parse_int(std::string_view(set_names_[s]).substr(7), n)) continue;
    numbered = true;
    for (long id : set_elements_[s]) region[id] = static_cast<int>(n);
  }
  std::stable_sort(elements_.begin(), elements_.end(),
                   [](const PendingElement& a, const PendingElement& b) { return a.id < b.id; });
  bool solids = false;
  for (const PendingElement& e : elements_) solids = solids || types_[e.type].solid();
  CellAssembly cells(path_, "element");
  int64_t vtk[20];
  for (const PendingElement& e : elements_) {
    const InpType& t = types_[e.type];
    if (solids && !t.solid()) continue;
    for (size_t j = 0; j < t.to_vtk.size(); ++j) {
      auto it = node_index_.find(nodes_[e.first + j]);
      if (it == node_index_.end())
        throw InputError(path_, e.line, "element " + std::to_string(e.id) + " refers to node " +
                                            std::to_string(nodes_[e.first + j]) + ", which the file does not define");
      vtk[t.to_vtk[j]] = it->second;
    }
    int r = 0;
    if (numbered) {
      auto it = region.find(e.id);
      if (it != region.end()) r = it->second;
    } else if (e.set >= 0 && set_names_[e.set] != "EALL") {
      r = e.set + 1;
    }
    cells.add(t.vtk, vtk, static_cast<int>(t.to_vtk.size()), r, e.id, e.line);
  }
  const long n = static_cast<long>(points_.size() / 3);
  Eigen::MatrixXd V(n, 3);
  for (long i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) V(i, k) = points_[3 * i + k];
  return cells.finish(std::move(V));
}

}  // namespace

mesh::Mesh read_inp(const std::string& path) {
  const std::string text = load_file(path);
  return InpReader(path, text).read();
}

}  // namespace hexdom::io
