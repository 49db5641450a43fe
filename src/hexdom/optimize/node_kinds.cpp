#include "hexdom/optimize/node_kinds.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "hexdom/common/disjoint_sets.h"

namespace hexdom::optimize {

using mesh::CellType;
using Vec = Eigen::Vector3d;

NodeKinds node_kinds(const mesh::Mesh& m, double feature_angle, const std::vector<char>* sharp) {
  NodeKinds t;
  const int nn = m.num_nodes();
  t.node_cells = mesh::node_cells(m);
  t.node_faces.assign(nn, {});
  t.edge_nbrs.assign(nn, {});
  {
    for (int c = 0; c < m.num_cells(); ++c) {
      const auto [e, ne] = mesh::cell_edges(m.type(c));
      for (int q = 0; q < ne; ++q) {
        const int a = m.cells(c, e[q][0]), b = m.cells(c, e[q][1]);
        t.edge_nbrs[a].push_back(b);
        t.edge_nbrs[b].push_back(a);
      }
    }
    for (auto& l : t.edge_nbrs) {
      std::sort(l.begin(), l.end());
      l.erase(std::unique(l.begin(), l.end()), l.end());
    }
  }
  t.faces = mesh::boundary_faces(m);
  for (int f = 0; f < static_cast<int>(t.faces.size()); ++f)
    for (int i = 0; i < t.faces[f].n; ++i) t.node_faces[t.faces[f].v[i]].push_back(f);
  // Boundary edges and their faces: (lower node, higher node, face) by edge, then face order.
  std::vector<std::array<int, 3>> edge_face;
  for (int f = 0; f < static_cast<int>(t.faces.size()); ++f)
    for (int i = 0; i < t.faces[f].n; ++i) {
      int a = t.faces[f].v[i], b = t.faces[f].v[(i + 1) % t.faces[f].n];
      edge_face.push_back({std::min(a, b), std::max(a, b), f});
    }
  std::sort(edge_face.begin(), edge_face.end());
  t.curve_nbrs.assign(nn, {});
  const double cos_limit = std::cos(feature_angle * M_PI / 180.0);
  std::vector<std::pair<int, int>> joined;  // faces on both sides of an edge that is not sharp
  std::vector<int> fs;
  for (size_t i = 0; i < edge_face.size();) {
    const std::pair<int, int> e(edge_face[i][0], edge_face[i][1]);
    fs.clear();
    for (; i < edge_face.size() && edge_face[i][0] == e.first && edge_face[i][1] == e.second; ++i) fs.push_back(edge_face[i][2]);
    bool sharp_edge;
    if (sharp) {
      sharp_edge = (*sharp)[e.first] && (*sharp)[e.second];
    } else {
      if (fs.size() != 2) { sharp_edge = true; }
      else {
        Vec n0 = mesh::face_area_vector(m, t.faces[fs[0]]).normalized(), n1 = mesh::face_area_vector(m, t.faces[fs[1]]).normalized();
        sharp_edge = n0.dot(n1) < cos_limit;
      }
    }
    if (sharp_edge) {
      t.curve_nbrs[e.first].push_back(e.second);
      t.curve_nbrs[e.second].push_back(e.first);
      if (fs.size() == 2) t.across_sharp.emplace_back(fs[0], fs[1]);
    } else if (fs.size() == 2) {
      joined.emplace_back(fs[0], fs[1]);
    }
  }
  {
    DisjointSets regions(static_cast<int>(t.faces.size()));
    for (const auto& [a, b] : joined) regions.unite(a, b);
    t.region.resize(t.faces.size());
    for (int f = 0; f < regions.size(); ++f) t.region[f] = regions.find(f);
  }
  t.kind.assign(nn, Interior);
  for (int v = 0; v < nn; ++v) {
    if (t.node_faces[v].empty()) continue;
    const size_t k = t.curve_nbrs[v].size();
    t.kind[v] = k == 0 ? Surface : k == 2 ? Curve : Corner;
  }
  return t;
}

BoundaryConstraints boundary_constraints(const mesh::Mesh& m, const NodeKinds& t, const mesh::SurfaceMesh& given) {
  BoundaryConstraints c;
  if (given.F.rows() > 0) {
    c.surface = mesh::TriangleProjector(given.V, given.F);
  } else {
    int nt = 0;
    for (const auto& f : t.faces) nt += f.n - 2;
    Eigen::MatrixXi F(nt, 3);
    int r = 0;
    for (const auto& f : t.faces)
      for (int i = 1; i + 1 < f.n; ++i) F.row(r++) << f.v[0], f.v[i], f.v[i + 1];
    c.surface = mesh::TriangleProjector(m.V, F);
  }
  std::vector<std::array<int, 2>> segs;
  for (int v = 0; v < static_cast<int>(t.curve_nbrs.size()); ++v)
    for (int u : t.curve_nbrs[v])
      if (u > v) segs.push_back({v, u});
  if (!segs.empty()) c.curves = mesh::segment_projector(m.V, segs);
  return c;
}

}  // namespace hexdom::optimize
