#include "hexdom/overlay/octree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/mesh/refine.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::overlay {

namespace {

using mesh::Hex12;
using mesh::kCubeCorner;
using mesh::P12;

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
  const mesh::RefinementTemplates& tt = mesh::refinement_templates();
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
        v[b] = lattice_node((c.i + kCubeCorner[b][0]) * scale, (c.j + kCubeCorner[b][1]) * scale, (c.k + kCubeCorner[b][2]) * scale);
      add_hex(v, c.level, true);
      continue;
    }
    if (tt.kind[m] < 0) throw GeometryError(fmt("octree: a cell of level %.0f kept an invalid mark pattern", double(c.level)));
    ++out.templates;
    const int64_t third = scale / 3;  // one third of this cell on the finest lattice
    std::unordered_map<int, int> own;  // the template's own nodes, by twelfths
    const Eigen::Vector3d lo = octree_cell_origin(grid, c), size = octree_cell_size(grid, c);
    for (const Hex12& h : tt.cells_for(m)) {
      std::array<int, 8> v;
      for (int n = 0; n < 8; ++n) {
        const P12& x = h[n];
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
      return pack(c.i + kCubeCorner[b][0], c.j + kCubeCorner[b][1], c.k + kCubeCorner[b][2]);
    };
    // A node of a level > 0 may be marked only when the 8 cells of this level around it exist.
    auto may_mark = [&](const OctreeCell& c, int b) {
      if (level == 0) return true;
      const int64_t I = c.i + kCubeCorner[b][0], J = c.j + kCubeCorner[b][1], K = c.k + kCubeCorner[b][2];
      for (int d = 0; d < 8; ++d)
        if (I - 1 + kCubeCorner[d][0] < 0 || J - 1 + kCubeCorner[d][1] < 0 || K - 1 + kCubeCorner[d][2] < 0 ||
            !index.count(pack(I - 1 + kCubeCorner[d][0], J - 1 + kCubeCorner[d][1], K - 1 + kCubeCorner[d][2])))
          return false;
      return true;
    };
    auto mask_of = [&](const OctreeCell& c) {
      int m = 0;
      for (int b = 0; b < 8; ++b)
        if (marked.count(corner_key(c, b))) m |= 1 << b;
      return m;
    };
    // The cells of this level around node key n (to look at again when its mark changes), into out.
    auto around = [&](uint64_t n, std::vector<int>& out) {
      const int64_t I = n & 0x1FFFFF, J = (n >> 21) & 0x1FFFFF, K = n >> 42;
      for (int d = 0; d < 8; ++d) {
        const int64_t i = I - 1 + kCubeCorner[d][0], j = J - 1 + kCubeCorner[d][1], k = K - 1 + kCubeCorner[d][2];
        if (i < 0 || j < 0 || k < 0) continue;
        auto it = index.find(pack(i, j, k));
        if (it != index.end()) out.push_back(it->second);
      }
    };
    if (level < max_level)
      for (const OctreeCell& c : cells)
        if (refine(c))
          for (int b = 0; b < 8; ++b)
            if (may_mark(c, b)) marked.insert(corner_key(c, b));
    // Marks made valid: completed where a cell may have all 8, then cut (mesh::settle_marks).
    mesh::settle_marks(
        static_cast<int>(cells.size()), [&](int c) { return mask_of(cells[c]); },
        [&](int c) {
          for (int b = 0; b < 8; ++b)
            if (!may_mark(cells[c], b)) return false;
          return true;
        },
        [&](int c, int b) { return marked.insert(corner_key(cells[c], b)).second; },
        [&](int c, int b) { marked.erase(corner_key(cells[c], b)); },
        [&](int c, int b, std::vector<int>& out) { around(corner_key(cells[c], b), out); });
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
