#include "hexdom/mesh/cell_faces.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "hexdom/common/error.h"

namespace hexdom::mesh {

namespace {
const LocalFace kHex[6] = {{4, {0, 4, 7, 3}}, {4, {1, 2, 6, 5}}, {4, {0, 1, 5, 4}},
                           {4, {3, 7, 6, 2}}, {4, {0, 3, 2, 1}}, {4, {4, 5, 6, 7}}};
const LocalFace kWedge[5] = {{3, {0, 1, 2, -1}}, {3, {3, 5, 4, -1}}, {4, {0, 3, 4, 1}},
                             {4, {1, 4, 5, 2}}, {4, {2, 5, 3, 0}}};
const LocalFace kTet[4] = {{3, {0, 2, 1, -1}}, {3, {0, 1, 3, -1}}, {3, {1, 2, 3, -1}}, {3, {0, 3, 2, -1}}};

const std::array<int, 2> kHexEdges[12] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                          {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
const std::array<int, 2> kWedgeEdges[9] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
const std::array<int, 2> kTetEdges[6] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// Every cell face with its nodes sorted (the key; -1 after a triangle's three), sorted by key and
// then by (cell, local face): faces shared by cells come together, the lower cell first.
struct FaceRecord {
  std::array<int, 4> key;
  int cell, local;
  bool operator<(const FaceRecord& o) const {
    return key != o.key ? key < o.key : cell != o.cell ? cell < o.cell : local < o.local;
  }
};

std::vector<FaceRecord> sorted_faces(const Mesh& m) {
  // Calls add(record) for every cell face, cell by cell.
  auto each = [&](auto&& add) {
    for (int c = 0; c < m.num_cells(); ++c) {
      auto [lf, nf] = cell_faces(m.type(c));
      for (int f = 0; f < nf; ++f) {
        FaceRecord r{{-1, -1, -1, -1}, c, f};
        for (int i = 0; i < lf[f].n; ++i) r.key[i] = m.cells(c, lf[f].v[i]);
        for (int i = 1; i < lf[f].n; ++i)  // insertion sort of at most 4 ids
          for (int j = i; j > 0 && r.key[j] < r.key[j - 1]; --j) std::swap(r.key[j], r.key[j - 1]);
        add(r);
      }
    }
  };
  // Bucketed by the lowest node of the key (a counting sort), then each bucket (the faces around
  // one node: a few dozen at most) sorted: the order of one sort of them all, for a fraction of
  // the comparisons. Node ids outside the mesh's nodes: one sort of them all.
  const int nn = m.num_nodes();
  std::vector<size_t> start(static_cast<size_t>(nn) + 2, 0);
  bool in_range = true;
  each([&](const FaceRecord& r) {
    if (r.key[0] < 0 || r.key[0] >= nn) in_range = false;
    else ++start[r.key[0] + 2];
  });
  std::vector<FaceRecord> all;
  if (!in_range) {
    each([&](const FaceRecord& r) { all.push_back(r); });
    std::sort(all.begin(), all.end());
    return all;
  }
  for (int v = 0; v < nn; ++v) start[v + 2] += start[v + 1];
  all.resize(start[nn + 1]);
  each([&](const FaceRecord& r) { all[start[r.key[0] + 1]++] = r; });  // start[v + 1] ends at bucket v's end
  for (int v = 0; v < nn; ++v) std::sort(all.begin() + start[v], all.begin() + start[v + 1]);
  return all;
}

// Calls run(first, count) for each run of faces with one key in `all`; throws GeometryError for a
// key held by more than two cells (the lowest such key).
template <class Run>
void face_runs(const std::vector<FaceRecord>& all, Run&& run) {
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].key == all[i].key) ++j;
    if (j - i > 2) {
      const auto& key = all[i].key;
      throw GeometryError("face with nodes " + std::to_string(key[0] + 1) + " " + std::to_string(key[1] + 1) + " " +
                          std::to_string(key[2] + 1) + " is shared by more than two cells");
    }
    run(i, j - i);
    i = j;
  }
}
}  // namespace

std::pair<const LocalFace*, int> cell_faces(CellType t) {
  switch (t) {
    case CellType::Hex: return {kHex, 6};
    case CellType::Wedge: return {kWedge, 5};
    case CellType::Tet: return {kTet, 4};
    default: return {nullptr, 0};
  }
}

std::pair<const std::array<int, 2>*, int> cell_edges(CellType t) {
  switch (t) {
    case CellType::Hex: return {kHexEdges, 12};
    case CellType::Wedge: return {kWedgeEdges, 9};
    case CellType::Tet: return {kTetEdges, 6};
    default: return {nullptr, 0};
  }
}

std::vector<BoundaryFace> boundary_faces(const Mesh& m) {
  const std::vector<FaceRecord> all = sorted_faces(m);
  std::vector<BoundaryFace> out;
  face_runs(all, [&](size_t i, size_t n) {
    if (n != 1) return;
    const FaceRecord& r = all[i];
    const LocalFace& lf = cell_faces(m.type(r.cell)).first[r.local];
    BoundaryFace b{r.cell, r.local, lf.n, {-1, -1, -1, -1}};
    for (int k = 0; k < lf.n; ++k) b.v[k] = m.cells(r.cell, lf.v[k]);
    out.push_back(b);
  });
  std::sort(out.begin(), out.end(), [](const BoundaryFace& a, const BoundaryFace& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.local < b.local;
  });
  return out;
}

std::vector<std::array<int, 2>> face_neighbours(const Mesh& m) {
  const std::vector<FaceRecord> all = sorted_faces(m);
  std::vector<std::array<int, 2>> pairs;
  face_runs(all, [&](size_t i, size_t n) {
    if (n == 2) pairs.push_back({all[i].cell, all[i + 1].cell});
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<int> face_nodes(const Mesh& m, const BoundaryFace& f) {
  std::vector<int> nodes(f.v.begin(), f.v.begin() + f.n);
  if (!m.second_order()) return nodes;
  const auto [edges, ne] = cell_edges(m.type(f.cell));
  for (int k = 0; k < f.n; ++k) {
    const int a = f.v[k], b = f.v[(k + 1) % f.n];
    for (int e = 0; e < ne; ++e) {
      const int x = m.cells(f.cell, edges[e][0]), y = m.cells(f.cell, edges[e][1]);
      if ((x == a && y == b) || (x == b && y == a)) nodes.push_back(m.mid(f.cell, e));
    }
  }
  return nodes;
}

Eigen::Vector3d face_area_vector(const Mesh& m, const BoundaryFace& f) {
  using Vec = Eigen::Vector3d;
  Vec n = Vec::Zero();
  Vec c = Vec::Zero();
  for (int i = 0; i < f.n; ++i) c += m.V.row(f.v[i]).transpose();
  c /= f.n;
  for (int i = 0; i < f.n; ++i) {
    const Vec a = m.V.row(f.v[i]).transpose(), b = m.V.row(f.v[(i + 1) % f.n]).transpose();
    n += (a - c).cross(b - c);
  }
  return 0.5 * n;
}

}  // namespace hexdom::mesh
