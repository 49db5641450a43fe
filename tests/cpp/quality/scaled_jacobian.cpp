#include <cmath>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

TEST(ScaledJacobian, UnitCubeIsOne) {
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Hex, test::unit_hex()), 1.0, 1e-15);
}

TEST(ScaledJacobian, EquilateralWedgeIsOne) {
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Wedge, test::unit_wedge()), 1.0, 1e-12);
}

TEST(ScaledJacobian, TiltedParallelepipedIsCosine) {
  const double t = 0.4;
  auto P = test::unit_hex();
  for (int i = 4; i < 8; ++i) P(i, 0) += std::tan(t);  // top face sheared along x
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Hex, P), std::cos(t), 1e-12);
}

TEST(ScaledJacobian, MirroredHexIsNegative) {
  auto P = test::unit_hex();
  P.col(2) *= -1.0;
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Hex, P), -1.0, 1e-15);
  EXPECT_TRUE(quality::is_inverted(quality::scaled_jacobian(CellType::Hex, P)));
}

TEST(Volume, UnitCellsHaveKnownVolumes) {
  EXPECT_NEAR(quality::volume(CellType::Hex, test::unit_hex()), 1.0, 1e-14);
  EXPECT_NEAR(quality::volume(CellType::Wedge, test::unit_wedge()), std::sqrt(3.0) / 4.0, 1e-14);
  EXPECT_NEAR(quality::volume(CellType::Tet, test::unit_tet()), 1.0 / 6.0, 1e-14);
}
