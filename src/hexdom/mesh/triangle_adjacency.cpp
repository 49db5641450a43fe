#include "hexdom/mesh/triangle_adjacency.h"

#include <algorithm>
#include <unordered_map>

namespace hexdom::mesh {

Eigen::MatrixXi triangle_adjacency(const Eigen::MatrixXi& F) {
  const int nf = static_cast<int>(F.rows());
  Eigen::MatrixXi TT = Eigen::MatrixXi::Constant(nf, 3, -1);
  std::unordered_map<long long, int> open;  // undirected edge -> f * 3 + k of its first triangle
  open.reserve(2 * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      const long long key = (static_cast<long long>(std::min(a, b)) << 32) | static_cast<unsigned>(std::max(a, b));
      auto [it, inserted] = open.try_emplace(key, f * 3 + k);
      if (!inserted) {
        const int g = it->second / 3, l = it->second % 3;
        if (TT(g, l) < 0) {
          TT(g, l) = f;
          TT(f, k) = g;
        }
      }
    }
  return TT;
}

}  // namespace hexdom::mesh
