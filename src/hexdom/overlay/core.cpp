#include "hexdom/overlay/core.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "hexdom/common/disjoint_sets.h"
#include "hexdom/mesh/adjacency.h"
#include "hexdom/mesh/cell_faces.h"

namespace hexdom::overlay {

namespace {

// Whether the cells of a 2 x 2 x 2 block flagged in `mask` (bit dx + 2 dy + 4 dz) are
// face-connected among themselves (an empty set is).
bool connected(int mask) {
  if (mask == 0) return true;
  int seen = mask & -mask, frontier = seen;
  while (frontier) {
    int next = 0;
    for (int b = 0; b < 8; ++b)
      if (frontier & (1 << b))
        for (int flip : {1, 2, 4}) next |= 1 << (b ^ flip);
    next &= mask & ~seen;
    seen |= next;
    frontier = next;
  }
  return seen == mask;
}

struct ManifoldTable {
  bool ok[256];
  ManifoldTable() {
    for (int m = 0; m < 256; ++m) ok[m] = connected(m) && connected(~m & 255);
  }
};

}  // namespace

Core core_cells(const Grid& g, const NodeField& f, double margin) {
  std::vector<char> keep(g.num_cells(), 0);
  std::vector<double> safety(g.num_cells(), 0);  // smallest corner distance of a kept cell
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        double least = std::numeric_limits<double>::infinity();
        bool in = true;
        for (int64_t n : g.corners(i, j, k)) {
          if (!f.inside[n] || f.distance[n] < margin) {
            in = false;
            break;
          }
          least = std::min(least, f.distance[n]);
        }
        if (in) {
          keep[g.cell(i, j, k)] = 1;
          safety[g.cell(i, j, k)] = least;
        }
      }
  return manifold_core(g, std::move(keep), safety);
}

bool across_surface(const Eigen::Vector3d& a, double da, const Eigen::Vector3d& b, double db,
                    const mesh::TriangleProjector& surface) {
  const double l = (b - a).norm();
  if (!(da + db < l)) return false;
  int out = -1, in = -1;  // where the segment leaves the solid from a, and from b
  if (!std::isfinite(surface.ray_distance(a, b - a, 0, l, -1, &out))) return false;
  surface.ray_distance(b, a - b, 0, l, -1, &in);
  return in >= 0 && surface.normal(out).dot(surface.normal(in)) < -0.5;
}

Core core_cells_by_centres(const Grid& g, const NodeField& centres, double margin, const mesh::TriangleProjector* surface,
                           double band) {
  const Grid cg = cell_centres(g);
  std::vector<char> keep(g.num_cells(), 0);
  std::vector<double> safety(g.num_cells(), 0);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int64_t n = cg.node(i, j, k);
        if (!centres.inside[n] || centres.distance[n] < margin) continue;
        keep[g.cell(i, j, k)] = 1;
        safety[g.cell(i, j, k)] = centres.distance[n];
      }
  int parted = 0;
  if (surface) {
    // A centre without a distance is at least `band` inside.
    auto depth = [&](int64_t c) { return std::min(safety[c], std::max(band, margin)); };
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          const int64_t c = g.cell(i, j, k);
          if (!keep[c]) continue;
          const int nb[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
          for (const auto& q : nb) {
            if (q[0] >= g.nx || q[1] >= g.ny || q[2] >= g.nz) continue;
            const int64_t d = g.cell(q[0], q[1], q[2]);
            if (!keep[d] || !across_surface(cg.position(i, j, k), depth(c), cg.position(q[0], q[1], q[2]), depth(d), *surface))
              continue;
            keep[safety[d] < safety[c] ? d : c] = 0;
            ++parted;
            if (!keep[c]) break;
          }
        }
  }
  Core core = manifold_core(g, std::move(keep), safety);
  core.parted = parted;
  return core;
}

Core manifold_core(const Grid& g, std::vector<char> keep, const std::vector<double>& safety) {
  static const ManifoldTable table;
  Core c;
  c.keep = std::move(keep);
  // Nodes to check: every node at first, then the corners of each dropped cell.
  std::vector<std::array<int, 3>> work;
  for (int k = 1; k < g.nz; ++k)
    for (int j = 1; j < g.ny; ++j)
      for (int i = 1; i < g.nx; ++i) work.push_back({i, j, k});
  while (!work.empty()) {
    const auto [i, j, k] = work.back();
    work.pop_back();
    if (i <= 0 || j <= 0 || k <= 0 || i >= g.nx || j >= g.ny || k >= g.nz) continue;
    int mask = 0;
    for (int b = 0; b < 8; ++b)
      if (c.keep[g.cell(i - 1 + (b & 1), j - 1 + ((b >> 1) & 1), k - 1 + ((b >> 2) & 1))]) mask |= 1 << b;
    if (table.ok[mask]) continue;
    int worst = -1;
    for (int b = 0; b < 8; ++b)
      if (mask & (1 << b)) {
        const int64_t cb = g.cell(i - 1 + (b & 1), j - 1 + ((b >> 1) & 1), k - 1 + ((b >> 2) & 1));
        if (worst < 0 ||
            safety[cb] < safety[g.cell(i - 1 + (worst & 1), j - 1 + ((worst >> 1) & 1), k - 1 + ((worst >> 2) & 1))])
          worst = b;
      }
    const int ci = i - 1 + (worst & 1), cj = j - 1 + ((worst >> 1) & 1), ck = k - 1 + ((worst >> 2) & 1);
    c.keep[g.cell(ci, cj, ck)] = 0;
    ++c.dropped;
    for (int b = 0; b < 8; ++b) work.push_back({ci + (b & 1), cj + ((b >> 1) & 1), ck + ((b >> 2) & 1)});
  }
  // Components: the largest is kept. Each piece would get its own buffer layer, and where two
  // pieces lie close (across a neck thinner than the cells) their layers would reach the same surface.
  std::vector<int> label(g.num_cells(), -1), size;
  std::vector<int64_t> stack;
  for (int64_t s = 0; s < g.num_cells(); ++s) {
    if (!c.keep[s] || label[s] >= 0) continue;
    const int id = static_cast<int>(size.size());
    size.push_back(0);
    label[s] = id;
    stack.push_back(s);
    while (!stack.empty()) {
      const int64_t x = stack.back();
      stack.pop_back();
      ++size[id];
      const int i = static_cast<int>(x % g.nx), j = static_cast<int>((x / g.nx) % g.ny), k = static_cast<int>(x / (int64_t(g.nx) * g.ny));
      const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
      for (const auto& q : nb) {
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= g.nx || q[1] >= g.ny || q[2] >= g.nz) continue;
        const int64_t y = g.cell(q[0], q[1], q[2]);
        if (c.keep[y] && label[y] < 0) {
          label[y] = id;
          stack.push_back(y);
        }
      }
    }
  }
  c.components = static_cast<int>(size.size());
  if (size.empty()) return c;
  const int largest = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  for (int64_t s = 0; s < g.num_cells(); ++s)
    if (c.keep[s] && label[s] != largest) {
      c.keep[s] = 0;
      ++c.apart;
    }
  c.cells = size[largest];
  return c;
}

mesh::Mesh core_mesh(const Grid& g, const Core& core, std::vector<int64_t>* grid_node) {
  std::unordered_map<int64_t, int> index;
  std::vector<int64_t> nodes;
  mesh::MeshBuilder b;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        if (!core.keep[g.cell(i, j, k)]) continue;
        int v[8];
        const auto cs = g.corners(i, j, k);
        for (int a = 0; a < 8; ++a) {
          auto [it, added] = index.emplace(cs[a], static_cast<int>(nodes.size()));
          if (added) nodes.push_back(cs[a]);
          v[a] = it->second;
        }
        b.add(mesh::CellType::Hex, v, 1);
      }
  Eigen::MatrixXd V(static_cast<int>(nodes.size()), 3);
  for (size_t n = 0; n < nodes.size(); ++n) {
    const int64_t i = nodes[n] % (g.nx + 1), j = (nodes[n] / (g.nx + 1)) % (g.ny + 1), k = nodes[n] / (int64_t(g.nx + 1) * (g.ny + 1));
    V.row(static_cast<int>(n)) = g.position(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k)).transpose();
  }
  if (grid_node) *grid_node = nodes;
  return b.finish(V);
}

namespace {

int shared_nodes(const mesh::Mesh& m, int a, int b) {
  int n = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) n += m.cells(a, i) == m.cells(b, j);
  return n;
}

// Whether the cells `set` (of one node's star) are connected through shared faces.
bool star_connected(const mesh::Mesh& m, const std::vector<int>& set) {
  if (set.size() <= 1) return true;
  std::vector<char> seen(set.size(), 0);
  std::vector<size_t> stack{0};
  seen[0] = 1;
  size_t count = 1;
  while (!stack.empty()) {
    const size_t x = stack.back();
    stack.pop_back();
    for (size_t y = 0; y < set.size(); ++y)
      if (!seen[y] && shared_nodes(m, set[x], set[y]) >= 3) {
        seen[y] = 1;
        ++count;
        stack.push_back(y);
      }
  }
  return count == set.size();
}

}  // namespace

Core manifold_core(const mesh::Mesh& m, std::vector<char> keep, const std::vector<double>& safety) {
  Core c;
  c.keep = std::move(keep);
  const mesh::NodeCells nc = mesh::node_cells(m);
  std::vector<int> work;
  for (int v = 0; v < m.num_nodes(); ++v) work.push_back(v);
  std::vector<int> in, out;
  while (!work.empty()) {
    const int v = work.back();
    work.pop_back();
    in.clear();
    out.clear();
    for (int cell : nc[v]) (c.keep[cell] ? in : out).push_back(cell);
    if (in.empty() || out.empty() || (star_connected(m, in) && star_connected(m, out))) continue;
    int worst = in[0];
    for (int cell : in)
      if (safety[cell] < safety[worst]) worst = cell;
    c.keep[worst] = 0;
    ++c.dropped;
    for (int i = 0; i < 8; ++i) work.push_back(m.cells(worst, i));
  }
  // Face-connected pieces of the kept cells; the largest kept.
  DisjointSets pieces(m.num_cells());
  for (const auto& [x, y] : mesh::face_neighbours(m))
    if (c.keep[x] && c.keep[y]) pieces.unite(x, y);
  std::unordered_map<int, int> size;
  for (int x = 0; x < m.num_cells(); ++x)
    if (c.keep[x]) ++size[pieces.find(x)];
  c.components = static_cast<int>(size.size());
  if (size.empty()) return c;
  int largest = size.begin()->first;
  for (const auto& [root, k] : size)
    if (k > size[largest] || (k == size[largest] && root < largest)) largest = root;
  for (int x = 0; x < m.num_cells(); ++x)
    if (c.keep[x] && pieces.find(x) != largest) {
      c.keep[x] = 0;
      ++c.apart;
    }
  c.cells = size[largest];
  return c;
}

mesh::Mesh core_mesh(const mesh::Mesh& m, const Core& core) {
  std::vector<int> index(m.num_nodes(), -1);
  std::vector<int> nodes;
  mesh::MeshBuilder b;
  for (int x = 0; x < m.num_cells(); ++x) {
    if (!core.keep[x]) continue;
    int v[8];
    for (int i = 0; i < 8; ++i) {
      int& k = index[m.cells(x, i)];
      if (k < 0) {
        k = static_cast<int>(nodes.size());
        nodes.push_back(m.cells(x, i));
      }
      v[i] = k;
    }
    b.add(mesh::CellType::Hex, v, 1);
  }
  Eigen::MatrixXd V(static_cast<int>(nodes.size()), 3);
  for (size_t n = 0; n < nodes.size(); ++n) V.row(static_cast<int>(n)) = m.V.row(nodes[n]);
  return b.finish(V);
}

}  // namespace hexdom::overlay
