#include "hexdom/mesh/triangle_adjacency.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "hexdom/mesh/edge_key.h"

namespace hexdom::mesh {

Eigen::MatrixXi triangle_adjacency(const Eigen::MatrixXi& F) {
  const int nf = static_cast<int>(F.rows());
  Eigen::MatrixXi TT = Eigen::MatrixXi::Constant(nf, 3, -1);
  // Half-edges sorted by (undirected edge, f * 3 + k): the first two of each edge are paired.
  std::vector<std::pair<EdgeKey, int>> half(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) half[3 * static_cast<size_t>(f) + k] = {undirected_edge(F(f, k), F(f, (k + 1) % 3)), 3 * f + k};
  std::sort(half.begin(), half.end());
  for (size_t i = 0; i < half.size();) {
    size_t j = i + 1;
    while (j < half.size() && half[j].first == half[i].first) ++j;
    if (j - i >= 2) {
      const int f = half[i].second / 3, k = half[i].second % 3, g = half[i + 1].second / 3, l = half[i + 1].second % 3;
      TT(f, k) = g;
      TT(g, l) = f;
    }
    i = j;
  }
  return TT;
}

}  // namespace hexdom::mesh
