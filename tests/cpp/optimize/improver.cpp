// Improver::min_slopes against the forward differences it stands in for: on jittered hex grids
// (with and without prisms among the hexes), every interior node's slopes along the three axes are
// those of moving the node by the step and taking the lowest scaled Jacobian of all its cells again,
// to the last bit.
#include "hexdom/optimize/improver.h"

#include <random>

#include "hexdom/optimize/node_kinds.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

namespace {

// An n^3 grid of unit cubes, interior nodes moved by up to `jitter`; with `prism`, the last cube
// is two prisms instead (VTK wedge order).
mesh::Mesh jittered_grid(int n, double jitter, bool prism, unsigned seed) {
  const int m = n + 1;
  auto id = [&](int i, int j, int k) { return i + m * (j + m * k); };
  Eigen::MatrixXd V(m * m * m, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const bool inner = i > 0 && j > 0 && k > 0 && i < n && j < n && k < n;
        V.row(id(i, j, k)) << i + (inner ? u(rng) : 0), j + (inner ? u(rng) : 0), k + (inner ? u(rng) : 0);
      }
  mesh::MeshBuilder b;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int h[8] = {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (prism && i == n - 1 && j == n - 1 && k == n - 1) {
          const int w1[6] = {h[0], h[1], h[2], h[4], h[5], h[6]}, w2[6] = {h[0], h[2], h[3], h[4], h[6], h[7]};
          b.add(CellType::Wedge, w1, 1);
          b.add(CellType::Wedge, w2, 1);
        } else {
          b.add(CellType::Hex, h, 1);
        }
      }
  return b.finish(V);
}

}  // namespace

TEST(Improver, MinSlopesAreTheForwardDifferencesOverAllCells) {
  int compared = 0;
  for (unsigned seed : {1u, 2u, 3u})
    for (bool prism : {false, true}) {
      mesh::Mesh m = jittered_grid(4, 0.35, prism, seed);
      const optimize::NodeKinds kinds = optimize::node_kinds(m, 35.0, nullptr);
      const optimize::BoundaryConstraints cons = optimize::boundary_constraints(m, kinds, {});
      optimize::Improver imp(m, kinds, cons);
      for (int v = 0; v < m.num_nodes(); ++v) {
        if (kinds.kind[v] != optimize::Interior) continue;
        const double h = 1e-4;  // the optimiser's step: 1e-4 of the typical edge (1 here)
        const Eigen::Vector3d g = imp.min_slopes(v, h);
        const Eigen::Vector3d x0 = m.V.row(v).transpose();
        const double f0 = imp.local_min(v);
        for (int k = 0; k < 3; ++k) {
          m.V(v, k) = x0(k) + h;
          double f = 2;
          for (int q : kinds.node_cells[v]) f = std::min(f, optimize::cell_sj(m, q));
          m.V.row(v) = x0.transpose();
          EXPECT_EQ(g(k), (f - f0) / h) << "seed " << seed << " node " << v << " axis " << k;
          ++compared;
        }
      }
    }
  EXPECT_GT(compared, 400);  // of the 27 interior nodes of each grid, nearly all count as Interior
}
