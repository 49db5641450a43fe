#include "hexdom/overlay/octree.h"

#include <algorithm>
#include <array>
#include <bitset>
#include <queue>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::overlay {

namespace {

// Template points in twelfths of the cell (0..12 per axis); a multiple of 4 is a third, a node of
// the next level's lattice, shared with the neighbours; others are the template's own.
using P12 = std::array<int, 3>;
using Hex12 = std::array<P12, 8>;

// VTK corner b of a unit cube.
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

int corner_index(int x, int y, int z) {
  for (int b = 0; b < 8; ++b)
    if (kCorner[b][0] == x && kCorner[b][1] == y && kCorner[b][2] == z) return b;
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

// A symmetry of the cube: x[a] = flip[a] ? 12 - y[perm[a]] : y[perm[a]].
struct Symmetry {
  std::array<int, 3> perm{0, 1, 2};
  std::array<bool, 3> flip{false, false, false};
  P12 apply(const P12& y) const {
    P12 x;
    for (int a = 0; a < 3; ++a) x[a] = flip[a] ? 12 - y[perm[a]] : y[perm[a]];
    return x;
  }
};

// Per mask of marked corners: which template (0 none or whole cell, 1 corner, 2 edge, 3 face, -1
// not valid) and the symmetry taking the canonical template onto it.
struct TemplateTable {
  int kind[256];
  Symmetry sym[256];
  int largest_valid_subset[256];
  std::vector<Hex12> hexes[4];
  TemplateTable() {
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
        Symmetry s;
        s.perm = perm;
        for (int a = 0; a < 3; ++a) s.flip[a] = (fl >> a) & 1;
        for (int t = 1; t <= 3; ++t) {
          int mask = 0;
          for (int b = 0; b < 8; ++b)
            if (canonical[t] & (1 << b)) {
              const P12 x = s.apply({12 * kCorner[b][0], 12 * kCorner[b][1], 12 * kCorner[b][2]});
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
};

const TemplateTable& table() {
  static const TemplateTable t;
  return t;
}

uint64_t pack(int64_t i, int64_t j, int64_t k) {
  return uint64_t(i) | (uint64_t(j) << 21) | (uint64_t(k) << 42);
}

}  // namespace

Eigen::Vector3d octree_cell_size(const Grid& grid, const OctreeCell& c) { return grid.h / std::pow(3.0, c.level); }

Eigen::Vector3d octree_cell_origin(const Grid& grid, const OctreeCell& c) {
  return grid.origin + octree_cell_size(grid, c).cwiseProduct(Eigen::Vector3d(c.i, c.j, c.k));
}

namespace {

// The mesh of the octree's leaves (each a cell and its mask of marked corners) into `out`: a node
// on the finest lattice any leaf reaches is shared; a template's own node is not.
void build_mesh(const Grid& grid, const std::vector<std::pair<OctreeCell, int>>& leaves, OctreeMesh& out) {
  const TemplateTable& tt = table();
  int top = 0;  // the finest lattice any node is on: a template's nodes are on the next level's
  for (const auto& [c, m] : leaves) top = std::max(top, c.level + (tt.kind[m] > 0 ? 1 : 0));
  out.levels = top;
  const double fine = std::pow(3.0, top);
  std::unordered_map<uint64_t, int> node_of;
  std::vector<Eigen::Vector3d> pts;
  auto lattice_node = [&](int64_t I, int64_t J, int64_t K) {
    auto [it, added] = node_of.emplace(pack(I, J, K), static_cast<int>(pts.size()));
    if (added) pts.push_back(grid.origin + grid.h.cwiseProduct(Eigen::Vector3d(I, J, K)) / fine);
    return it->second;
  };
  mesh::MeshBuilder mb;
  auto add_hex = [&](std::array<int, 8> v, int level, bool plain) {
    quality::CellPoints P = quality::CellPoints::Zero();
    for (int n = 0; n < 8; ++n) P.row(n) = pts[v[n]].transpose();
    if (quality::volume(mesh::CellType::Hex, P) < 0) std::rotate(v.begin(), v.begin() + 4, v.end());
    mb.add(mesh::CellType::Hex, v.data(), 1);
    out.level.push_back(level);
    out.plain.push_back(plain ? 1 : 0);
  };
  for (const auto& [c, m] : leaves) {
    const int64_t scale = static_cast<int64_t>(std::llround(std::pow(3.0, top - c.level)));
    if (tt.kind[m] == 0) {
      std::array<int, 8> v;
      for (int b = 0; b < 8; ++b)
        v[b] = lattice_node((c.i + kCorner[b][0]) * scale, (c.j + kCorner[b][1]) * scale, (c.k + kCorner[b][2]) * scale);
      add_hex(v, c.level, true);
      continue;
    }
    if (tt.kind[m] < 0) throw GeometryError(fmt("octree: a cell of level %.0f kept an invalid mark pattern", double(c.level)));
    ++out.templates;
    const Symmetry& s = tt.sym[m];
    const int64_t third = scale / 3;  // one third of this cell on the finest lattice
    std::unordered_map<int, int> own;  // the template's own nodes, by twelfths
    const Eigen::Vector3d lo = octree_cell_origin(grid, c), size = octree_cell_size(grid, c);
    for (const Hex12& h : tt.hexes[tt.kind[m]]) {
      std::array<int, 8> v;
      for (int n = 0; n < 8; ++n) {
        const P12 x = s.apply(h[n]);
        if (x[0] % 4 == 0 && x[1] % 4 == 0 && x[2] % 4 == 0) {
          v[n] = lattice_node(c.i * scale + x[0] / 4 * third, c.j * scale + x[1] / 4 * third, c.k * scale + x[2] / 4 * third);
        } else {
          auto [it, added] = own.emplace(x[0] + 13 * (x[1] + 13 * x[2]), static_cast<int>(pts.size()));
          if (added) pts.push_back(lo + size.cwiseProduct(Eigen::Vector3d(x[0], x[1], x[2])) / 12.0);
          v[n] = it->second;
        }
      }
      add_hex(v, c.level, false);
    }
  }
  Eigen::MatrixXd V(static_cast<int>(pts.size()), 3);
  for (size_t n = 0; n < pts.size(); ++n) V.row(static_cast<int>(n)) = pts[n].transpose();
  out.mesh = mb.finish(V);
}

}  // namespace

OctreeMesh octree_mesh(const Grid& grid, int max_level, const std::function<bool(const OctreeCell&)>& refine) {
  const TemplateTable& tt = table();
  const int longest = std::max({grid.nx, grid.ny, grid.nz}) + 1;
  while (max_level > 0 && double(longest) * std::pow(3.0, max_level) >= double(1 << 21)) --max_level;
  OctreeMesh out;
  // Cells of each level (index by key), and per level the marks (node keys of that level).
  std::vector<OctreeCell> cells;
  for (int k = 0; k < grid.nz; ++k)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) cells.push_back({0, i, j, k});
  std::vector<std::pair<OctreeCell, int>> leaves;  // cell and its mask of marked corners
  for (int level = 0; !cells.empty(); ++level) {
    std::unordered_map<uint64_t, int> index;
    index.reserve(cells.size() * 2);
    for (size_t c = 0; c < cells.size(); ++c) index.emplace(pack(cells[c].i, cells[c].j, cells[c].k), static_cast<int>(c));
    std::unordered_set<uint64_t> marked;
    auto corner_key = [&](const OctreeCell& c, int b) {
      return pack(c.i + kCorner[b][0], c.j + kCorner[b][1], c.k + kCorner[b][2]);
    };
    // A node of a level > 0 may be marked only when the 8 cells of this level around it exist.
    auto may_mark = [&](const OctreeCell& c, int b) {
      if (level == 0) return true;
      const int64_t I = c.i + kCorner[b][0], J = c.j + kCorner[b][1], K = c.k + kCorner[b][2];
      for (int d = 0; d < 8; ++d)
        if (I - 1 + kCorner[d][0] < 0 || J - 1 + kCorner[d][1] < 0 || K - 1 + kCorner[d][2] < 0 ||
            !index.count(pack(I - 1 + kCorner[d][0], J - 1 + kCorner[d][1], K - 1 + kCorner[d][2])))
          return false;
      return true;
    };
    auto mask_of = [&](const OctreeCell& c) {
      int m = 0;
      for (int b = 0; b < 8; ++b)
        if (marked.count(corner_key(c, b))) m |= 1 << b;
      return m;
    };
    // The cells of this level around node key n (to look at again when its mark changes).
    std::vector<int> work;
    auto around = [&](uint64_t n) {
      const int64_t I = n & 0x1FFFFF, J = (n >> 21) & 0x1FFFFF, K = n >> 42;
      for (int d = 0; d < 8; ++d) {
        const int64_t i = I - 1 + kCorner[d][0], j = J - 1 + kCorner[d][1], k = K - 1 + kCorner[d][2];
        if (i < 0 || j < 0 || k < 0) continue;
        auto it = index.find(pack(i, j, k));
        if (it != index.end()) work.push_back(it->second);
      }
    };
    if (level < max_level)
      for (const OctreeCell& c : cells)
        if (refine(c))
          for (int b = 0; b < 8; ++b)
            if (may_mark(c, b)) marked.insert(corner_key(c, b));
    // Marks made valid: completed where a cell may have all 8, then cut to the largest valid subset.
    // `fix` is called for each cell whose marks are not a valid pattern, until none is left to look at.
    auto settle = [&](auto&& fix) {
      for (size_t c = 0; c < cells.size(); ++c) work.push_back(static_cast<int>(c));
      while (!work.empty()) {
        const OctreeCell c = cells[work.back()];
        work.pop_back();
        const int m = mask_of(c);
        if (tt.kind[m] < 0) fix(c, m);
      }
    };
    // Completion, the cells with the most marks first: a cell in a concavity of the marked region
    // (marked on several sides) is split before one beside its staircase, which sees marks on one
    // face only and would, split first, grow the region outwards cell by cell without end.
    {
      std::priority_queue<std::pair<int, int>> heap;  // (marks, -cell): most marks, then lowest index
      auto push = [&](int c) {
        const int m = mask_of(cells[c]);
        if (tt.kind[m] < 0) heap.emplace(static_cast<int>(std::bitset<8>(m).count()), -c);
      };
      for (size_t c = 0; c < cells.size(); ++c) push(static_cast<int>(c));
      while (!heap.empty()) {
        const auto [count, neg] = heap.top();
        heap.pop();
        const OctreeCell c = cells[-neg];
        const int m = mask_of(c);
        if (tt.kind[m] >= 0) continue;
        if (static_cast<int>(std::bitset<8>(m).count()) != count) {  // marked since: in its place again
          heap.emplace(static_cast<int>(std::bitset<8>(m).count()), neg);
          continue;
        }
        bool all = true;
        for (int b = 0; b < 8 && all; ++b) all = may_mark(c, b);
        if (!all) continue;  // left to the cut below
        for (int b = 0; b < 8; ++b)
          if (marked.insert(corner_key(c, b)).second) around(corner_key(c, b));
        for (int w : work) push(w);
        work.clear();
      }
    }
    settle([&](const OctreeCell& c, int m) {
      const int keep = tt.largest_valid_subset[m];
      for (int b = 0; b < 8; ++b)
        if ((m & ~keep) & (1 << b)) {
          marked.erase(corner_key(c, b));
          around(corner_key(c, b));
        }
    });
    std::vector<OctreeCell> next;
    for (const OctreeCell& c : cells) {
      const int m = mask_of(c);
      if (m == 255) {
        for (int d = 0; d < 27; ++d) next.push_back({level + 1, 3 * c.i + d % 3, 3 * c.j + (d / 3) % 3, 3 * c.k + d / 9});
      } else {
        leaves.emplace_back(c, m);
      }
    }
    cells = std::move(next);
  }
  build_mesh(grid, leaves, out);
  return out;
}

}  // namespace hexdom::overlay
