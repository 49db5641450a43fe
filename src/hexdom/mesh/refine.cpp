#include "hexdom/mesh/refine.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "hexdom/mesh/adjacency.h"

namespace hexdom::mesh {

const int kCubeCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

namespace {

int corner_index(int x, int y, int z) {
  for (int b = 0; b < 8; ++b)
    if (kCubeCorner[b][0] == x && kCubeCorner[b][1] == y && kCubeCorner[b][2] == z) return b;
  return -1;
}

Hex12 extrude(const std::array<P12, 4>& a, const std::array<P12, 4>& b) {
  return {a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]};
}

// Corner template: corner (0,0,0) marked. The small cube there, and three hexes joining its
// three inner faces to the cube's three far faces.
std::vector<Hex12> corner_template() {
  std::vector<Hex12> h;
  h.push_back(extrude({P12{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}, {P12{0, 0, 4}, {4, 0, 4}, {4, 4, 4}, {0, 4, 4}}));
  h.push_back(extrude({P12{4, 0, 0}, {4, 4, 0}, {4, 4, 4}, {4, 0, 4}}, {P12{12, 0, 0}, {12, 12, 0}, {12, 12, 12}, {12, 0, 12}}));
  h.push_back(extrude({P12{0, 4, 0}, {4, 4, 0}, {4, 4, 4}, {0, 4, 4}}, {P12{0, 12, 0}, {12, 12, 0}, {12, 12, 12}, {0, 12, 12}}));
  h.push_back(extrude({P12{0, 0, 4}, {4, 0, 4}, {4, 4, 4}, {0, 4, 4}}, {P12{0, 0, 12}, {12, 0, 12}, {12, 12, 12}, {0, 12, 12}}));
  return h;
}

// Edge template: corners (0,0,0) and (1,0,0) marked. Three small cubes along the edge; the rest of
// the (v, w) section is the corner template's two quads A (towards v = 1) and B (towards w = 1),
// each swept along u by the 2D 3-to-1 template (4 quads: a row of 3 edges to 1).
std::vector<Hex12> edge_template() {
  std::vector<Hex12> h;
  for (int i = 0; i < 3; ++i)
    h.push_back(extrude({P12{4 * i, 0, 0}, {4 * i + 4, 0, 0}, {4 * i + 4, 4, 0}, {4 * i, 4, 0}},
                        {P12{4 * i, 0, 4}, {4 * i + 4, 0, 4}, {4 * i + 4, 4, 4}, {4 * i, 4, 4}}));
  // 3-to-1 in (u, s), s from the small cubes (0) to the far face (1, in halves: 0, 1, 2).
  const std::array<std::array<int, 2>, 4> quads[4] = {{{{0, 0}, {4, 0}, {4, 1}, {0, 2}}},
                                                      {{{4, 0}, {8, 0}, {8, 1}, {4, 1}}},
                                                      {{{8, 0}, {12, 0}, {12, 2}, {8, 1}}},
                                                      {{{4, 1}, {8, 1}, {12, 2}, {0, 2}}}};
  // Section point (v, w) at s (halves) and t (0, 1) of quad A or B; every one a third.
  auto section = [](bool a, int s, int t) -> std::array<int, 2> {
    const int r = 4 + 4 * s;  // 4, 8, 12
    if (t == 1) return {r, r};
    return a ? std::array<int, 2>{r, 0} : std::array<int, 2>{0, r};
  };
  for (bool a : {true, false})
    for (const auto& q : quads) {
      std::array<P12, 4> lo, hi;
      for (int n = 0; n < 4; ++n) {
        const auto s0 = section(a, q[n][1], 0), s1 = section(a, q[n][1], 1);
        lo[n] = {q[n][0], s0[0], s0[1]};
        hi[n] = {q[n][0], s1[0], s1[1]};
      }
      h.push_back(extrude(lo, hi));
    }
  return h;
}

// Face template: the corners of w = 0 marked. Nine small cubes on that face; above them 13 hexes
// take the 3 x 3 quads to the one quad of w = 1, each side face showing the 2D 3-to-1 template.
std::vector<Hex12> face_template() {
  std::vector<Hex12> h;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      h.push_back(extrude({P12{4 * i, 4 * j, 0}, {4 * i + 4, 4 * j, 0}, {4 * i + 4, 4 * j + 4, 0}, {4 * i, 4 * j + 4, 0}},
                          {P12{4 * i, 4 * j, 4}, {4 * i + 4, 4 * j, 4}, {4 * i + 4, 4 * j + 4, 4}, {4 * i, 4 * j + 4, 4}}));
  auto g = [](int i, int j) { return P12{4 * i, 4 * j, 4}; };
  const P12 a{4, 0, 8}, b{8, 0, 8}, ay{4, 12, 8}, by{8, 12, 8}, a1{0, 4, 8}, a2{0, 8, 8}, b1{12, 4, 8}, b2{12, 8, 8};
  const P12 c{4, 4, 6}, d{8, 4, 6}, e{8, 8, 6}, f{4, 8, 6};
  const P12 q0{0, 0, 12}, q1{12, 0, 12}, q2{12, 12, 12}, q3{0, 12, 12};
  h.push_back(extrude({g(0, 0), g(1, 0), g(1, 1), g(0, 1)}, {q0, a, c, a1}));
  h.push_back(extrude({g(2, 0), g(3, 0), g(3, 1), g(2, 1)}, {b, q1, b1, d}));
  h.push_back(extrude({g(2, 2), g(3, 2), g(3, 3), g(2, 3)}, {e, b2, q2, by}));
  h.push_back(extrude({g(0, 2), g(1, 2), g(1, 3), g(0, 3)}, {a2, f, ay, q3}));
  h.push_back(extrude({g(1, 0), g(2, 0), g(2, 1), g(1, 1)}, {a, b, d, c}));
  h.push_back(extrude({g(2, 1), g(3, 1), g(3, 2), g(2, 2)}, {d, b1, b2, e}));
  h.push_back(extrude({g(1, 2), g(2, 2), g(2, 3), g(1, 3)}, {f, e, by, ay}));
  h.push_back(extrude({g(0, 1), g(1, 1), g(1, 2), g(0, 2)}, {a1, c, f, a2}));
  h.push_back(extrude({g(1, 1), g(2, 1), g(2, 2), g(1, 2)}, {c, d, e, f}));
  h.push_back(extrude({a, b, d, c}, {q0, q1, b1, a1}));
  h.push_back(extrude({f, e, by, ay}, {a2, b2, q2, q3}));
  h.push_back(extrude({c, d, e, f}, {a1, b1, b2, a2}));
  h.push_back(extrude({a1, b1, b2, a2}, {q0, q1, q2, q3}));
  return h;
}

// The 27 cubes of a cell split by thirds.
std::vector<Hex12> split_template() {
  std::vector<Hex12> h;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        Hex12 c;
        for (int b = 0; b < 8; ++b)
          c[b] = {4 * (i + kCubeCorner[b][0]), 4 * (j + kCubeCorner[b][1]), 4 * (k + kCubeCorner[b][2])};
        h.push_back(c);
      }
  return h;
}

// Sign of a template hex's volume in twelfths: its corner-0 Jacobian (every template hex is valid,
// so all its corners agree).
bool positive(const Hex12& h) {
  auto d = [&](int a, int b) { return std::array<long, 3>{h[b][0] - h[a][0], h[b][1] - h[a][1], h[b][2] - h[a][2]}; };
  const auto u = d(0, 1), v = d(0, 3), w = d(0, 4);
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]) > 0;
}

}  // namespace

P12 CubeSymmetry::apply(const P12& y) const {
  P12 x;
  for (int a = 0; a < 3; ++a) x[a] = flip[a] ? 12 - y[perm[a]] : y[perm[a]];
  return x;
}

RefinementTemplates::RefinementTemplates() {
  hexes[0] = split_template();
  hexes[1] = corner_template();
  hexes[2] = edge_template();
  hexes[3] = face_template();
  std::fill(kind, kind + 256, -1);
  kind[0] = 0;
  kind[255] = 0;
  const int canonical[4] = {0, 1 << 0, (1 << 0) | (1 << 1), 0x0F};
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int fl = 0; fl < 8; ++fl) {
      CubeSymmetry s;
      s.perm = perm;
      for (int a = 0; a < 3; ++a) s.flip[a] = (fl >> a) & 1;
      for (int t = 1; t <= 3; ++t) {
        int mask = 0;
        for (int b = 0; b < 8; ++b)
          if (canonical[t] & (1 << b)) {
            const P12 x = s.apply({12 * kCubeCorner[b][0], 12 * kCubeCorner[b][1], 12 * kCubeCorner[b][2]});
            mask |= 1 << corner_index(x[0] / 12, x[1] / 12, x[2] / 12);
          }
        if (kind[mask] < 0) {
          kind[mask] = t;
          sym[mask] = s;
        }
      }
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  for (int m = 0; m < 256; ++m) {
    int best = 0;
    for (int v = 0; v < 256; ++v)
      if (kind[v] >= 0 && (v & ~m) == 0 && std::bitset<8>(v).count() > std::bitset<8>(best).count()) best = v;
    largest_valid_subset[m] = best;
  }
}

std::vector<Hex12> RefinementTemplates::cells_for(int mask) const {
  if (mask <= 0 || mask > 255 || kind[mask] < 0) throw std::logic_error("cells_for: not a valid mask of marked corners");
  if (mask == 255) return hexes[0];
  std::vector<Hex12> out;
  for (const Hex12& h : hexes[kind[mask]]) {
    Hex12 x;
    for (int n = 0; n < 8; ++n) x[n] = sym[mask].apply(h[n]);
    if (!positive(x)) std::rotate(x.begin(), x.begin() + 4, x.end());  // a reflection: top and bottom swapped
    out.push_back(x);
  }
  return out;
}

const RefinementTemplates& refinement_templates() {
  static const RefinementTemplates t;
  return t;
}

Refinement refine_by_thirds(const Mesh& m, std::vector<char> marked, const std::vector<char>* fixed_nodes) {
  require_first_order(m, "refinement by thirds");
  if (static_cast<int>(marked.size()) != m.num_nodes())
    throw std::invalid_argument("refine_by_thirds: one mark per node expected");
  const RefinementTemplates& tt = refinement_templates();
  const int nc = m.num_cells();
  if (fixed_nodes && static_cast<int>(fixed_nodes->size()) != m.num_nodes())
    throw std::invalid_argument("refine_by_thirds: one fixed flag per node expected");
  // Nodes that may not be marked: the fixed ones and those of the cells that are not hexahedra.
  std::vector<char> fixed = fixed_nodes ? *fixed_nodes : std::vector<char>(m.num_nodes(), 0);
  for (int c = 0; c < nc; ++c)
    if (m.type(c) != CellType::Hex)
      for (int i = 0; i < node_count(m.type(c)); ++i) fixed[m.cells(c, i)] = 1;
  const NodeCells cells_of = node_cells(m);
  for (int v = 0; v < m.num_nodes(); ++v)
    if (fixed[v]) marked[v] = 0;
  auto mask_of = [&](int c) {
    if (m.type(c) != CellType::Hex) return 0;
    int mask = 0;
    for (int b = 0; b < 8; ++b)
      if (marked[m.cells(c, b)]) mask |= 1 << b;
    return mask;
  };
  settle_marks(
      nc, mask_of,
      [&](int c) {
        for (int b = 0; b < 8; ++b)
          if (fixed[m.cells(c, b)]) return false;
        return true;
      },
      [&](int c, int b) {
        char& x = marked[m.cells(c, b)];
        const bool was = x != 0;
        x = 1;
        return !was;
      },
      [&](int c, int b) { marked[m.cells(c, b)] = 0; },
      [&](int c, int b, std::vector<int>& out) {
        const NodeCells::Range around = cells_of[m.cells(c, b)];
        out.insert(out.end(), around.begin(), around.end());
      });
  Refinement out;
  for (char x : marked) out.marked += x != 0;
  // Nodes: the old ones, then the new, each keyed by the parent nodes it is a combination of (in
  // 27ths, sorted by node): the same key, and the same point, from every cell around it.
  std::vector<Eigen::Vector3d> pts;
  pts.reserve(m.num_nodes());
  for (int v = 0; v < m.num_nodes(); ++v) pts.push_back(m.V.row(v).transpose());
  std::map<std::vector<std::pair<int, int>>, int> shared;
  MeshBuilder mb;
  for (int c = 0; c < nc; ++c) {
    const int mask = mask_of(c);
    if (mask == 0) {
      mb.add(m.type(c), m.cells.row(c).data(), m.region(c));
      out.parent.push_back(c);
      out.plain.push_back(1);
      continue;
    }
    if (mask == 255) ++out.split; else ++out.templates;
    std::unordered_map<int, int> own;  // the template's interior nodes, by twelfths
    for (const Hex12& h : tt.cells_for(mask)) {
      std::array<int, 8> v;
      for (int n = 0; n < 8; ++n) {
        const P12& x = h[n];
        if (x[0] % 4 == 0 && x[1] % 4 == 0 && x[2] % 4 == 0) {
          std::vector<std::pair<int, int>> key;
          for (int b = 0; b < 8; ++b) {
            int w = 1;
            for (int a = 0; a < 3; ++a) w *= kCubeCorner[b][a] ? x[a] / 4 : 3 - x[a] / 4;
            if (w > 0) key.emplace_back(m.cells(c, b), w);
          }
          std::sort(key.begin(), key.end());
          if (key.size() == 1) {
            v[n] = key[0].first;
            continue;
          }
          auto [it, added] = shared.emplace(key, static_cast<int>(pts.size()));
          if (added) {
            Eigen::Vector3d p = Eigen::Vector3d::Zero();
            for (const auto& [node, w] : key) p += (w / 27.0) * m.V.row(node).transpose();
            pts.push_back(p);
          }
          v[n] = it->second;
        } else {
          if (x[0] % 12 == 0 || x[1] % 12 == 0 || x[2] % 12 == 0)
            throw std::logic_error("refine_by_thirds: a template's own node on the cell's boundary");
          auto [it, added] = own.emplace(x[0] + 13 * (x[1] + 13 * x[2]), static_cast<int>(pts.size()));
          if (added) {
            Eigen::Vector3d p = Eigen::Vector3d::Zero();
            for (int b = 0; b < 8; ++b) {
              double w = 1;
              for (int a = 0; a < 3; ++a) w *= kCubeCorner[b][a] ? x[a] / 12.0 : 1 - x[a] / 12.0;
              p += w * m.V.row(m.cells(c, b)).transpose();
            }
            pts.push_back(p);
          }
          v[n] = it->second;
        }
      }
      mb.add(CellType::Hex, v.data(), m.region(c));
      out.parent.push_back(c);
      out.plain.push_back(mask == 255 ? 1 : 0);
    }
  }
  Eigen::MatrixXd V(static_cast<int>(pts.size()), 3);
  for (size_t n = 0; n < pts.size(); ++n) V.row(static_cast<int>(n)) = pts[n].transpose();
  out.mesh = mb.finish(V);
  return out;
}

}  // namespace hexdom::mesh
