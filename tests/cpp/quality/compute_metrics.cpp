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
