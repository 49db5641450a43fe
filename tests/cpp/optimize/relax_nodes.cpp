#include <algorithm>
#include <random>

#include "hexdom/mesh/adjacency.h"
#include "hexdom/optimize/relax_nodes.h"
#include "hexdom/quality/metrics.h"
#include "hex_grid.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;
using optimize::NodeFreedom;
using optimize::NodeKind;

namespace {

// An n x n x n grid of unit hexes, node (i, j, k) numbered i + (n+1) (j + (n+1) k).
struct Grid {
  int n;
  mesh::Mesh m;
  int node(int i, int j, int k) const { return test::grid_node(i, j, k, n + 1, n + 1); }
  bool on_boundary(int v) const { return test::on_grid_boundary(v, n); }
  explicit Grid(int cells) : n(cells), m(test::jittered_cube_grid(cells, 0.0, 0)) {}
  // Boundary nodes fixed, interior nodes free.
  NodeFreedom freedom() const {
    NodeFreedom F;
    const int nn = m.num_nodes();
    F.kind.assign(nn, NodeKind::Interior);
    for (int v = 0; v < nn; ++v)
      if (on_boundary(v)) F.kind[v] = NodeKind::Corner;
    F.param.assign(nn, {0.0, 0.0});
    F.now = F.param;
    return F;
  }
};


}  // namespace

// relax_poor on a 4x4x4 grid whose interior nodes are shaken: the worst cell rises (and, by the
// contract, a move never lowers it), boundary nodes stay, and `left` names the cells still poor.
TEST(RelaxPoor, RaisesTheWorstCellOfAPerturbedGridAndNeverLowersIt) {
  Grid g(4);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  for (int v = 0; v < g.m.num_nodes(); ++v)
    if (!g.on_boundary(v))
      for (int d = 0; d < 3; ++d) g.m.V(v, d) += u(rng);
  const NodeFreedom F = g.freedom();
  const mesh::Mesh before = g.m;
  const test::Worst w0 = test::worst_of(before);
  ASSERT_LT(w0.all, 0.2) << "the shaken grid should have poor cells";
  // One sweep at a time: the worst cell never falls.
  double last = w0.all;
  const mesh::NodeCells cells = mesh::node_cells(g.m);
  for (int round = 0; round < 5; ++round) {
    optimize::relax_poor(g.m, cells, F.kind, 1, 0.2, 1);
    const double now = test::worst_of(g.m).all;
    EXPECT_GE(now, last) << "round " << round;
    last = now;
  }
  EXPECT_GT(last, w0.all + 0.05);
  for (int v = 0; v < g.m.num_nodes(); ++v) {
    if (g.on_boundary(v)) {
      EXPECT_TRUE(g.m.V.row(v) == before.V.row(v)) << "boundary node " << v << " moved";
    }
  }
  // The same on one and two threads, and `left` lists exactly the cells at most its threshold.
  mesh::Mesh one = before, two = before;
  std::vector<int> left;
  optimize::relax_poor(one, cells, F.kind, 2, 0.2, 1);
  optimize::relax_poor(two, cells, F.kind, 2, 0.2, 2, &left, 0.15);
  EXPECT_TRUE(one.V == two.V);
  std::vector<int> expect;
  for (int c = 0; c < two.num_cells(); ++c)
    if (quality::scaled_jacobian(CellType::Hex, quality::cell_points(two, c)) <= 0.15) expect.push_back(c);
  EXPECT_EQ(left, expect);
}

// One interior node of a 3x3x3 grid pushed through its neighbours inverts the hexes around it;
// untangle_nodes moves it (and only free nodes) until none is inverted.
TEST(UntangleNodes, UntanglesAnInvertedHexInAGrid) {
  Grid g(3);
  const int v = g.node(1, 1, 1);
  g.m.V.row(v) << 2.3, 1.2, 1.1;  // past the nodes at x = 2
  NodeFreedom F = g.freedom();
  const mesh::Mesh before = g.m;
  const test::Worst w0 = test::worst_of(before);
  ASSERT_GT(w0.inverted, 0);
  std::vector<int> left;
  const std::string summary = optimize::untangle_nodes(g.m, mesh::node_cells(g.m), F, 10, 0.0, 0.2, 0.0, 0.1, nullptr, &left);
  const test::Worst w1 = test::worst_of(g.m);
  EXPECT_EQ(w1.inverted, 0) << summary;
  EXPECT_GT(w1.all, w0.all);
  EXPECT_TRUE(left.empty());
  for (int u = 0; u < g.m.num_nodes(); ++u) {
    if (g.on_boundary(u)) {
      EXPECT_TRUE(g.m.V.row(u) == before.V.row(u)) << "boundary node " << u << " moved";
    }
  }
}

// A node on the grid's bottom face may slide in it (patch parameters (u, v) -> (3u, 3v, 0)) within
// `box` of where it was made: pushed past its neighbour, it comes back within the face.
TEST(UntangleNodes, SurfaceNodesSlideWithinTheirPatch) {
  Grid g(3);
  NodeFreedom F = g.freedom();
  const int v = g.node(1, 1, 0);
  F.kind[v] = NodeKind::Surface;
  F.param[v] = {1.0 / 3, 1.0 / 3};
  F.now[v] = {2.5 / 3, 1.0 / 3};
  g.m.V.row(v) << 2.5, 1, 0;  // past the node at x = 2: the cells above it are inverted
  F.place = [](int, const double* q, double* x) {
    x[0] = 3 * q[0];
    x[1] = 3 * q[1];
    x[2] = 0;
  };
  F.clamp = [](int, double* q) {
    q[0] = std::clamp(q[0], 1e-6, 1 - 1e-6);
    q[1] = std::clamp(q[1], 1e-6, 1 - 1e-6);
  };
  ASSERT_GT(test::worst_of(g.m).inverted, 0);
  const double box = 0.15;
  const std::string summary = optimize::untangle_nodes(g.m, mesh::node_cells(g.m), F, 10, 0.0, 0.2, 0.0, box);
  EXPECT_EQ(test::worst_of(g.m).inverted, 0) << summary;
  EXPECT_EQ(g.m.V(v, 2), 0.0);
  EXPECT_LE(std::abs(F.now[v][0] - F.param[v][0]), box + 1e-15);
  EXPECT_NEAR(g.m.V(v, 0), 3 * F.now[v][0], 1e-15);
}
