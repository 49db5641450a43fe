#include "hexdom/mesh/adjacency.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

// Two hexes sharing a face, a wedge on top of the second and a tet beside it: every node lists the
// cells holding it, in increasing order, and a node no cell uses lists none.
TEST(NodeCells, ListsTheCellsOfEveryNodeInOrder) {
  mesh::MeshBuilder b;
  const int h0[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int h1[8] = {1, 8, 9, 2, 5, 10, 11, 6};
  const int w[6] = {5, 10, 6, 12, 13, 14};
  const int t[4] = {9, 11, 2, 15};
  b.add(CellType::Hex, h0, 1);
  b.add(CellType::Hex, h1, 1);
  b.add(CellType::Wedge, w, 2);
  b.add(CellType::Tet, t, 3);
  const mesh::Mesh m = b.finish(Eigen::MatrixXd::Zero(17, 3));  // node 16 in no cell
  const mesh::NodeCells nc = mesh::node_cells(m);
  ASSERT_EQ(nc.start.size(), 18u);
  EXPECT_EQ(nc.cells.size(), 8u + 8u + 6u + 4u);
  auto of = [&](int v) { return std::vector<int>(nc.cells.begin() + nc.begin(v), nc.cells.begin() + nc.end(v)); };
  EXPECT_EQ(of(0), (std::vector<int>{0}));
  EXPECT_EQ(of(1), (std::vector<int>{0, 1}));
  EXPECT_EQ(of(2), (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(of(5), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(of(6), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(of(9), (std::vector<int>{1, 3}));
  EXPECT_EQ(of(12), (std::vector<int>{2}));
  EXPECT_EQ(of(15), (std::vector<int>{3}));
  EXPECT_TRUE(of(16).empty());
  // Every listing is one of the cell's nodes, and every (cell, node) pair is listed.
  for (int v = 0; v < m.num_nodes(); ++v)
    for (int c : of(v)) {
      bool holds = false;
      for (int i = 0; i < mesh::node_count(m.type(c)); ++i) holds = holds || m.cells(c, i) == v;
      EXPECT_TRUE(holds) << "node " << v << " cell " << c;
    }
}

TEST(NodeCells, EmptyMesh) {
  mesh::Mesh m;
  m.V = Eigen::MatrixXd::Zero(3, 3);
  const mesh::NodeCells nc = mesh::node_cells(m);
  EXPECT_EQ(nc.start, (std::vector<int>{0, 0, 0, 0}));
  EXPECT_TRUE(nc.cells.empty());
}
