#include <cmath>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

TEST(EdgeRatio, IdealCellsAreOne) {
  EXPECT_NEAR(quality::edge_ratio(CellType::Hex, test::unit_hex()), 1.0, 1e-15);
  EXPECT_NEAR(quality::edge_ratio(CellType::Wedge, test::unit_wedge()), 1.0, 1e-15);
  quality::CellPoints P = quality::CellPoints::Zero();
  P.topRows(4) << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0, 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
  EXPECT_NEAR(quality::edge_ratio(CellType::Tet, P), 1.0, 1e-15);
}

TEST(EdgeRatio, IsLongestOverShortestEdge) {
  auto P = test::unit_hex();
  P.col(0) *= 3.0;
  P.col(2) *= 0.5;
  EXPECT_NEAR(quality::edge_ratio(CellType::Hex, P), 6.0, 1e-14);
  EXPECT_NEAR(quality::edge_ratio(CellType::Tet, test::unit_tet()), std::sqrt(2.0), 1e-15);
  auto W = test::unit_wedge();
  W.middleRows(3, 3).col(2) *= 4.0;  // height 4, triangle edges 1
  EXPECT_NEAR(quality::edge_ratio(CellType::Wedge, W), 4.0, 1e-14);
}

TEST(EdgeRatio, HexUsesAllTwelveEdges) {
  // Only edges 6-7, 7-4 and 3-7 grow. Verdict (VTK 9.1) would report the longest of its first six
  // edges over the shortest: 1.
  auto P = test::unit_hex();
  P.row(7) << 0, 3, 3;
  const double longest = std::sqrt(9.0 + 4.0);  // 3-7: (0,1,0) -> (0,3,3)
  EXPECT_NEAR(quality::edge_ratio(CellType::Hex, P), longest, 1e-14);
}

TEST(EdgeRatio, ZeroLengthEdgeGivesDblMax) {
  auto P = test::unit_hex();
  P.row(6) = P.row(2);
  EXPECT_EQ(quality::edge_ratio(CellType::Hex, P), 1e30);
  auto T = test::unit_tet();
  T.row(3) = T.row(0);
  EXPECT_EQ(quality::edge_ratio(CellType::Tet, T), 1e30);
}
