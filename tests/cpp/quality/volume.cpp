#include <cmath>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

TEST(Volume, UnitCellsHaveKnownVolumes) {
  EXPECT_NEAR(quality::volume(CellType::Hex, test::unit_hex()), 1.0, 1e-14);
  EXPECT_NEAR(quality::volume(CellType::Wedge, test::unit_wedge()), std::sqrt(3.0) / 4.0, 1e-14);
  EXPECT_NEAR(quality::volume(CellType::Tet, test::unit_tet()), 1.0 / 6.0, 1e-14);
}

TEST(Volume, TrilinearHexIsExact) {
  // Node 6 raised by a: z = w (1 + a u v), det J = 1 + a u v, volume 1 + a/4.
  const double a = 0.8;
  auto P = test::unit_hex();
  P(6, 2) += a;
  EXPECT_NEAR(quality::volume(CellType::Hex, P), 1.0 + a / 4.0, 1e-14);
}

TEST(Volume, BilinearWedgeIsExact) {
  // Right wedge (0,0),(1,0),(0,1) extruded to z = 1 + a r at the top's node 4 (VTK order below):
  // height 1 + a r over the triangle, volume 1/2 + a/6.
  const double a = 0.9;
  quality::CellPoints P = quality::CellPoints::Zero();
  P.topRows(6) << 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 0, 1 + a;
  EXPECT_NEAR(quality::volume(CellType::Wedge, P), 0.5 + a / 6.0, 1e-14);
}

TEST(Volume, InvertedCellsAreNegative) {
  auto P = test::unit_hex();
  P.col(1) *= -1.0;
  EXPECT_NEAR(quality::volume(CellType::Hex, P), -1.0, 1e-14);
  auto W = test::unit_wedge();
  W.col(1) *= -1.0;
  EXPECT_NEAR(quality::volume(CellType::Wedge, W), -std::sqrt(3.0) / 4.0, 1e-14);
  auto T = test::unit_tet();
  T.col(1) *= -1.0;
  EXPECT_NEAR(quality::volume(CellType::Tet, T), -1.0 / 6.0, 1e-15);
}
