#include <set>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/second_order.h"
#include "hex_grid.h"
#include "test_common.h"

using namespace hexdom;

namespace {

/// An n x n x n grid of unit cubes, the last cell two wedges when `prisms`.
mesh::Mesh cube_grid(int n, bool prisms) {
  const int m = n + 1;
  Eigen::MatrixXd V(m * m * m, 3);
  for (int l = 0; l < m; ++l)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) V.row(test::grid_node(i, j, l, m, m)) << i, j, l;
  return test::grid_cells(V, n, n, m, m, prisms);
}

}  // namespace

TEST(AddMidEdgeNodes, OneNodePerEdgeAtItsMidpointAndTheCornersUnchanged) {
  for (bool prisms : {false, true}) {
    const mesh::Mesh linear = cube_grid(3, prisms);
    const mesh::Mesh m = mesh::add_mid_edge_nodes(linear);
    ASSERT_TRUE(m.second_order());
    EXPECT_NO_THROW(mesh::validate(m));
    EXPECT_TRUE(m.V.topRows(linear.num_nodes()) == linear.V);
    EXPECT_TRUE(m.cells == linear.cells);
    // The grid's edges (3 n (n+1)^2), plus the split cell's two face diagonals when prisms.
    std::set<mesh::EdgeKey> edges;
    for (int c = 0; c < linear.num_cells(); ++c) {
      const auto [e, ne] = mesh::cell_edges(linear.type(c));
      for (int k = 0; k < ne; ++k) edges.insert(mesh::undirected_edge(linear.cells(c, e[k][0]), linear.cells(c, e[k][1])));
    }
    EXPECT_EQ(edges.size(), static_cast<size_t>(3 * 3 * 16 + (prisms ? 2 : 0)));
    EXPECT_EQ(m.num_nodes(), linear.num_nodes() + static_cast<int>(edges.size()));
    const auto ends = mesh::mid_edge_ends(m);
    for (int c = 0; c < m.num_cells(); ++c) {
      const auto [e, ne] = mesh::cell_edges(m.type(c));
      for (int k = 0; k < ne; ++k) {
        const int v = m.mid(c, k), a = m.cells(c, e[k][0]), b = m.cells(c, e[k][1]);
        EXPECT_GE(v, linear.num_nodes());
        EXPECT_TRUE(m.V.row(v).isApprox(0.5 * (m.V.row(a) + m.V.row(b))));
        EXPECT_EQ(ends[v][0], std::min(a, b));
        EXPECT_EQ(ends[v][1], std::max(a, b));
      }
      for (int k = ne; k < 12; ++k) EXPECT_EQ(m.mid(c, k), -1);
    }
    int nodes[20];
    EXPECT_EQ(mesh::cell_nodes(m, 0, nodes), 20);
    EXPECT_EQ(m.vtk_type(0), 25);
    EXPECT_EQ(m.vtk_type(m.num_cells() - 1), prisms ? 26 : 25);
  }
}

TEST(AddMidEdgeNodes, SecondOrderMeshesAreCheckedAndRefusedWhereFirstOrderIsNeeded) {
  mesh::Mesh m = mesh::add_mid_edge_nodes(cube_grid(1, false));
  EXPECT_THROW(mesh::add_mid_edge_nodes(m), InputError);
  EXPECT_THROW(mesh::require_first_order(m, "improving a mesh"), InputError);
  m.mid(0, 3) = m.num_nodes();  // a node that does not exist
  EXPECT_THROW(mesh::validate(m), GeometryError);
  m.mid(0, 3) = m.mid(0, 2);  // two edges of one cell on one node
  EXPECT_THROW(mesh::mid_edge_ends(m), GeometryError);
  // Surface cells have no mid-edge nodes.
  mesh::MeshBuilder b;
  const int tri[3] = {0, 1, 2};
  b.add(mesh::CellType::Triangle, tri, 0);
  EXPECT_THROW(mesh::add_mid_edge_nodes(b.finish(Eigen::MatrixXd::Identity(3, 3))), GeometryError);
}
