// Edge neighbours of the triangles of a closed manifold surface, and the components they connect.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace hexdom::mesh {

/// #F by 3: TT(f, k) is the triangle across edge (F(f, k), F(f, (k + 1) % 3)), -1 on an open edge.
/// Expects a manifold surface (see check_surface); with more than two triangles on an edge the
/// result pairs the two lowest (f, k) half-edges on it.
Eigen::MatrixXi triangle_adjacency(const Eigen::MatrixXi& F);

/// Connected components of the triangles through the edges of TT that `joined(f, k)` accepts (edge
/// k of triangle f, to TT(f, k) >= 0): component[f] = 0, 1, ... in the order of each component's
/// lowest triangle; returns their number.
template <class Joined>
int triangle_components(const Eigen::MatrixXi& TT, Joined joined, std::vector<int>& component) {
  const int n = static_cast<int>(TT.rows());
  component.assign(n, -1);
  int count = 0;
  std::vector<int> stack;
  for (int f0 = 0; f0 < n; ++f0) {
    if (component[f0] >= 0) continue;
    component[f0] = count;
    stack.assign(1, f0);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = TT(f, k);
        if (g < 0 || component[g] >= 0 || !joined(f, k)) continue;
        component[g] = count;
        stack.push_back(g);
      }
    }
    ++count;
  }
  return count;
}

}  // namespace hexdom::mesh
