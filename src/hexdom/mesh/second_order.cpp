#include "hexdom/mesh/second_order.h"

#include <string>
#include <unordered_map>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/edge_key.h"

namespace hexdom::mesh {

Mesh add_mid_edge_nodes(const Mesh& linear) {
  require_first_order(linear, "adding mid-edge nodes");
  const int nc = linear.num_cells(), nv = linear.num_nodes();
  Mesh m = linear;
  m.mid = MidMatrix::Constant(nc, 12, -1);
  std::unordered_map<EdgeKey, int> node_of;
  node_of.reserve(static_cast<size_t>(nc) * 4);
  std::vector<std::array<int, 2>> ends;
  for (int c = 0; c < nc; ++c) {
    const CellType t = linear.type(c);
    if (!is_volume(t))
      throw GeometryError("cell " + std::to_string(c + 1) + " is a " + type_name(t) +
                          ": only volume cells get mid-edge nodes");
    const auto [edges, ne] = cell_edges(t);
    for (int e = 0; e < ne; ++e) {
      const int a = linear.cells(c, edges[e][0]), b = linear.cells(c, edges[e][1]);
      const auto [it, added] = node_of.emplace(undirected_edge(a, b), nv + static_cast<int>(ends.size()));
      if (added) ends.push_back({a, b});
      m.mid(c, e) = it->second;
    }
  }
  m.V.conservativeResize(nv + static_cast<Eigen::Index>(ends.size()), 3);
  for (size_t k = 0; k < ends.size(); ++k)
    m.V.row(nv + static_cast<Eigen::Index>(k)) = 0.5 * (linear.V.row(ends[k][0]) + linear.V.row(ends[k][1]));
  return m;
}

std::vector<std::array<int, 2>> mid_edge_ends(const Mesh& m) {
  std::vector<std::array<int, 2>> ends(m.num_nodes(), {-1, -1});
  if (!m.second_order()) return ends;
  for (int c = 0; c < m.num_cells(); ++c) {
    const auto [edges, ne] = cell_edges(m.type(c));
    for (int e = 0; e < ne; ++e) {
      int a = m.cells(c, edges[e][0]), b = m.cells(c, edges[e][1]);
      if (a > b) std::swap(a, b);
      std::array<int, 2>& x = ends[m.mid(c, e)];
      if (x[0] < 0) x = {a, b};
      else if (x[0] != a || x[1] != b)
        throw GeometryError("mid-edge node " + std::to_string(m.mid(c, e) + 1) + " lies on edge (" + std::to_string(x[0] + 1) +
                            ", " + std::to_string(x[1] + 1) + ") in one cell and on (" + std::to_string(a + 1) + ", " +
                            std::to_string(b + 1) + ") in cell " + std::to_string(c + 1));
    }
  }
  return ends;
}

int second_order_points(const Mesh& m, int c, double (*p)[3]) {
  const CellType t = m.type(c);
  const int n = node_count(t), ne = edge_count(t);
  for (int i = 0; i < n + ne; ++i) {
    const int v = i < n ? m.cells(c, i) : m.mid(c, i - n);
    for (int k = 0; k < 3; ++k) p[i][k] = m.V(v, k);
  }
  return n + ne;
}

}  // namespace hexdom::mesh
