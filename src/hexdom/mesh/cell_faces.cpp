#include "hexdom/mesh/cell_faces.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <unordered_map>

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

struct FaceHash {
  size_t operator()(const std::array<int, 4>& k) const {
    size_t h = 1469598103934665603ull;
    for (int x : k) h = (h ^ static_cast<size_t>(x + 1)) * 1099511628211ull;
    return h;
  }
};
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
  std::unordered_map<std::array<int, 4>, std::pair<int, int>, FaceHash> seen;  // key -> (count, first)
  std::vector<BoundaryFace> all;
  seen.reserve(4 * static_cast<size_t>(m.num_cells()));
  for (int c = 0; c < m.num_cells(); ++c) {
    auto [lf, nf] = cell_faces(m.type(c));
    for (int f = 0; f < nf; ++f) {
      BoundaryFace b{c, f, lf[f].n, {-1, -1, -1, -1}};
      for (int i = 0; i < lf[f].n; ++i) b.v[i] = m.cells(c, lf[f].v[i]);
      std::array<int, 4> key = b.v;
      for (int i = 1; i < b.n; ++i)  // insertion sort of at most 4 ids
        for (int j = i; j > 0 && key[j] < key[j - 1]; --j) std::swap(key[j], key[j - 1]);
      auto [it, ins] = seen.try_emplace(key, 0, static_cast<int>(all.size()));
      if (++it->second.first > 2)
        throw GeometryError("face with nodes " + std::to_string(key[0] + 1) + " " + std::to_string(key[1] + 1) + " " +
                            std::to_string(key[2] + 1) + " is shared by more than two cells");
      if (ins) all.push_back(b);
    }
  }
  std::vector<BoundaryFace> out;
  for (const auto& [key, cf] : seen)
    if (cf.first == 1) out.push_back(all[cf.second]);
  std::sort(out.begin(), out.end(), [](const BoundaryFace& a, const BoundaryFace& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.local < b.local;
  });
  return out;
}

std::vector<std::array<int, 2>> face_neighbours(const Mesh& m) {
  std::unordered_map<std::array<int, 4>, int, FaceHash> first;  // key -> first cell, or -1 once paired
  first.reserve(4 * static_cast<size_t>(m.num_cells()));
  std::vector<std::array<int, 2>> pairs;
  for (int c = 0; c < m.num_cells(); ++c) {
    auto [lf, nf] = cell_faces(m.type(c));
    for (int f = 0; f < nf; ++f) {
      std::array<int, 4> key{-1, -1, -1, -1};
      for (int i = 0; i < lf[f].n; ++i) key[i] = m.cells(c, lf[f].v[i]);
      for (int i = 1; i < lf[f].n; ++i)
        for (int j = i; j > 0 && key[j] < key[j - 1]; --j) std::swap(key[j], key[j - 1]);
      auto [it, ins] = first.try_emplace(key, c);
      if (ins) continue;
      if (it->second < 0)
        throw GeometryError("face with nodes " + std::to_string(key[0] + 1) + " " + std::to_string(key[1] + 1) + " " +
                            std::to_string(key[2] + 1) + " is shared by more than two cells");
      pairs.push_back({std::min(it->second, c), std::max(it->second, c)});
      it->second = -1;
    }
  }
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
