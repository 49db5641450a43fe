#include "hexdom/mesh/adjacency.h"

namespace hexdom::mesh {

NodeCells node_cells(const Mesh& m) {
  NodeCells A;
  const int nn = m.num_nodes(), nc = m.num_cells();
  const int* cn = m.cells.data();  // row-major
  const int stride = static_cast<int>(m.cells.cols());
  A.start.assign(nn + 1, 0);
  for (int c = 0; c < nc; ++c)
    for (int i = 0, k = node_count(m.type(c)); i < k; ++i) ++A.start[cn[c * stride + i] + 1];
  for (int v = 0; v < nn; ++v) A.start[v + 1] += A.start[v];
  A.cells.resize(A.start[nn]);
  std::vector<int> fill(A.start.begin(), A.start.end() - 1);
  for (int c = 0; c < nc; ++c)
    for (int i = 0, k = node_count(m.type(c)); i < k; ++i) A.cells[fill[cn[c * stride + i]]++] = c;
  return A;
}

}  // namespace hexdom::mesh
