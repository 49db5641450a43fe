#include <cmath>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

TEST(ComputeMetrics, MatchesThePerCellFunctions) {
  mesh::MeshBuilder b;
  Eigen::MatrixXd V(9, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1.2, 1.1, 1.3, 0, 1, 1, 0.5, 0.5, 2;
  const int hex[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int tet[4] = {4, 5, 6, 8};
  const int tri[3] = {0, 1, 2};
  b.add(CellType::Hex, hex, 0);
  b.add(CellType::Tet, tet, 0);
  b.add(CellType::Triangle, tri, 0);
  const mesh::Mesh m = b.finish(V);
  const auto q = quality::compute_metrics(m);
  ASSERT_EQ(q.scaled_jacobian.size(), 3);
  for (int c = 0; c < 2; ++c) {
    const auto P = quality::cell_points(m, c);
    EXPECT_EQ(q.scaled_jacobian(c), quality::scaled_jacobian(m.type(c), P));
    EXPECT_EQ(q.edge_ratio(c), quality::edge_ratio(m.type(c), P));
    EXPECT_EQ(q.volume(c), quality::volume(m.type(c), P));
  }
  EXPECT_LT(q.scaled_jacobian(0), 1.0);
  EXPECT_GT(q.scaled_jacobian(0), 0.0);
  EXPECT_TRUE(std::isnan(q.scaled_jacobian(2)));
  EXPECT_TRUE(std::isnan(q.edge_ratio(2)));
  EXPECT_TRUE(std::isnan(q.volume(2)));
}

TEST(ComputeMetrics, TheSameFiguresOnOneAndThreeThreads) {
  // 1,000 hexes of a grid whose nodes are moved by a fixed pseudo-random amount (some cells
  // inverted): each thread takes runs of cells, and every figure must be the one-thread figure.
  mesh::MeshBuilder b;
  const int n = 10, s = n + 1;
  Eigen::MatrixXd V(s * s * s, 3);
  unsigned x = 12345;
  auto jitter = [&] { x = x * 1103515245u + 12345u; return ((x >> 8) % 1000) / 1000.0 - 0.5; };
  for (int k = 0; k < s; ++k)
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) V.row((k * s + j) * s + i) << i + 0.9 * jitter(), j + 0.9 * jitter(), k + 0.9 * jitter();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int o = (k * s + j) * s + i;
        const int hex[8] = {o, o + 1, o + s + 1, o + s, o + s * s, o + s * s + 1, o + s * s + s + 1, o + s * s + s};
        b.add(CellType::Hex, hex, 0);
      }
  const mesh::Mesh m = b.finish(V);
  const auto one = quality::compute_metrics(m, 1), three = quality::compute_metrics(m, 3);
  int inverted = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const auto P = quality::cell_points(m, c);
    EXPECT_EQ(one.scaled_jacobian(c), quality::scaled_jacobian(CellType::Hex, P));
    EXPECT_EQ(three.scaled_jacobian(c), one.scaled_jacobian(c));
    EXPECT_EQ(three.edge_ratio(c), one.edge_ratio(c));
    EXPECT_EQ(three.volume(c), one.volume(c));
    inverted += !(one.scaled_jacobian(c) > 0);
  }
  EXPECT_GT(inverted, 0);
  EXPECT_LT(inverted, m.num_cells());
}
