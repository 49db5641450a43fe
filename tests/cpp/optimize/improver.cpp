// The passes' colouring: no two nodes of a colour share a cell, and improve() gives the same mesh
// on 1, 2 and 3 threads.
// Improver::min_slopes against the forward differences it stands in for: on jittered hex grids
// (with and without prisms among the hexes), every interior node's slopes along the three axes are
// those of moving the node by the step and taking the lowest scaled Jacobian of all its cells again,
// to the last bit.
#include "hexdom/optimize/improver.h"

#include "hexdom/optimize/improve.h"

#include "hexdom/optimize/node_kinds.h"
#include "hex_grid.h"
#include "test_common.h"

using namespace hexdom;

TEST(Improver, MinSlopesAreTheForwardDifferencesOverAllCells) {
  int compared = 0;
  for (unsigned seed : {1u, 2u, 3u})
    for (bool prism : {false, true}) {
      mesh::Mesh m = test::jittered_cube_grid(4, 0.35, seed, 1.0, prism);
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

TEST(Improver, NoTwoNodesOfAColourShareACell) {
  mesh::Mesh m = test::jittered_cube_grid(5, 0.3, 4, 1.0, true);
  const optimize::NodeKinds kinds = optimize::node_kinds(m, 35.0, nullptr);
  const optimize::BoundaryConstraints cons = optimize::boundary_constraints(m, kinds, {});
  optimize::Improver imp(m, kinds, cons);
  EXPECT_GE(imp.colours(), 8);  // the 8 nodes of a hex differ in colour
  EXPECT_LE(imp.colours(), 27);
  for (int q = 0; q < m.num_cells(); ++q)
    for (int i = 0; i < mesh::node_count(m.type(q)); ++i)
      for (int j = i + 1; j < mesh::node_count(m.type(q)); ++j)
        EXPECT_NE(imp.colour(m.cells(q, i)), imp.colour(m.cells(q, j))) << "cell " << q << " nodes " << i << ", " << j;
}

TEST(Improver, TheMeshIsTheSameOnOneTwoAndThreeThreads) {
  // 12^3 cells, 2197 nodes: each colour has a few hundred, enough to be shared among the threads.
  const mesh::Mesh m = test::jittered_cube_grid(12, 0.4, 9, 1.0, true);
  optimize::ImproveOptions opt;
  opt.threads = 1;
  const optimize::ImproveResult one = optimize::improve(m, opt);
  ASSERT_GT(one.after.hex.sj_min, one.before.hex.sj_min + 0.1) << "the run should move many nodes";
  for (int threads : {2, 3}) {
    opt.threads = threads;
    const optimize::ImproveResult other = optimize::improve(m, opt);
    EXPECT_TRUE(other.mesh.V == one.mesh.V) << threads << " threads";
    EXPECT_EQ(other.rounds, one.rounds);
  }
}
