#include <cmath>

#include "hexdom/io/mesh_io.h"
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

TEST(ScaledJacobian, RegularTetIsOne) {
  quality::CellPoints P = quality::CellPoints::Zero();
  P.topRows(4) << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0, 0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0);
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Tet, P), 1.0, 1e-12);
}

TEST(ScaledJacobian, CornerTetIsSqrtTwoOverTwo) {
  // Corner 0: det 1 over edge-length product 1; corner 1: det 1 over 1*sqrt2*sqrt2 = 2 (the
  // largest product): sqrt(2) * 1 / 2.
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Tet, test::unit_tet()), std::sqrt(2.0) / 2, 1e-15);
}

TEST(ScaledJacobian, TiltedParallelepipedIsCosine) {
  const double t = 0.4;
  auto P = test::unit_hex();
  for (int i = 4; i < 8; ++i) P(i, 0) += std::tan(t);  // top face sheared along x
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Hex, P), std::cos(t), 1e-12);
}

TEST(ScaledJacobian, MirroredCellsAreNegative) {
  auto P = test::unit_hex();
  P.col(2) *= -1.0;
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Hex, P), -1.0, 1e-15);
  EXPECT_TRUE(quality::is_inverted(quality::scaled_jacobian(CellType::Hex, P)));
  auto W = test::unit_wedge();
  W.col(2) *= -1.0;
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Wedge, W), -1.0, 1e-12);
  auto T = test::unit_tet();
  T.col(2) *= -1.0;
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Tet, T), -std::sqrt(2.0) / 2, 1e-15);
}

TEST(ScaledJacobian, WedgeIsReadInVtkOrder) {
  // VTK order: the first triangle's normal points away from the second. Swapping the triangles'
  // winding (Verdict's own order) turns an ideal wedge inside out.
  auto W = test::unit_wedge();
  quality::CellPoints V = W;
  for (int r : {0, 3}) V.row(r + 1).swap(V.row(r + 2));
  EXPECT_NEAR(quality::scaled_jacobian(CellType::Wedge, V), -1.0, 1e-12);
}

TEST(ScaledJacobian, ZeroLengthEdgeMakesHexAndWedgeInvalid) {
  const int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : hex_edges) {
    auto P = test::unit_hex();
    P.row(e[1]) = P.row(e[0]);
    const double sj = quality::scaled_jacobian(CellType::Hex, P);
    EXPECT_EQ(sj, 1e30) << e[0] << "-" << e[1];
    EXPECT_TRUE(quality::is_inverted(sj));
  }
  // Verdict itself returns -1e30, 0 or even a positive value here, depending on the corner.
  const int wedge_edges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
  for (const auto& e : wedge_edges) {
    auto P = test::unit_wedge();
    P.row(e[1]) = P.row(e[0]);
    const double sj = quality::scaled_jacobian(CellType::Wedge, P);
    EXPECT_EQ(sj, 1e30) << e[0] << "-" << e[1];
    EXPECT_TRUE(quality::is_inverted(sj));
  }
}

TEST(ScaledJacobian, TwoDCellsAreNaN) {
  EXPECT_TRUE(std::isnan(quality::scaled_jacobian(CellType::Triangle, test::unit_tet())));
  EXPECT_TRUE(std::isnan(quality::scaled_jacobian(CellType::Quad, test::unit_hex())));
}

TEST(ScaledJacobian, RockerarmHexGenOutputMatchesVerdict) {
  // Verdict (VTK 9.1, vtkMeshQuality::HexScaledJacobian) on rockerarm3_hex.vtk: the worst hex is
  // cell 2521 at -0.4509443843940587; 11 hexes are inverted.
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm3_hex.vtk");
  HEXDOM_REQUIRE_DATA(path);
  const mesh::Mesh m = io::read_mesh(path);
  int worst = -1, inverted = 0;
  double min_sj = 2;
  for (int c = 0; c < m.num_cells(); ++c) {
    const double sj = quality::scaled_jacobian(m.type(c), quality::cell_points(m, c));
    inverted += quality::is_inverted(sj);
    if (sj < min_sj) { min_sj = sj; worst = c; }
  }
  EXPECT_EQ(worst, 2521);
  EXPECT_NEAR(min_sj, -0.4509443843940587, 1e-12);
  EXPECT_EQ(inverted, 11);
}

TEST(ScaledJacobian, RockerarmStructureMatchesVerdict) {
  // Verdict on rockerarm_polycube_withtet.k: worst hex (cell 2) 0.16223780046589822, worst wedge
  // (cell 69) 0.18573227671742412, worst tet (cell 68) 0.36161296646256.
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm_polycube_withtet.k");
  HEXDOM_REQUIRE_DATA(path);
  const mesh::Mesh m = io::read_mesh(path);
  EXPECT_NEAR(quality::scaled_jacobian(m.type(2), quality::cell_points(m, 2)), 0.16223780046589822, 1e-12);
  EXPECT_EQ(m.type(69), CellType::Wedge);
  EXPECT_NEAR(quality::scaled_jacobian(m.type(69), quality::cell_points(m, 69)), 0.18573227671742412, 1e-12);
  EXPECT_EQ(m.type(68), CellType::Tet);
  EXPECT_NEAR(quality::scaled_jacobian(m.type(68), quality::cell_points(m, 68)), 0.36161296646256, 1e-12);
}

TEST(ScaledJacobian, AxisStepsOfOneNodeAreTheMovedCellsValuesBitForBit) {
  // Distorted hexes (some inverted), every node, steps large enough to flip corners, and a step
  // that closes an edge (the invalid value): each of the three values is scaled_jacobian's on the
  // cell with that node moved.
  std::srand(7);
  auto jitter = [] { return (std::rand() / static_cast<double>(RAND_MAX) - 0.5) * 0.9; };
  int compared = 0, negative = 0;
  for (int trial = 0; trial < 200; ++trial) {
    quality::CellPoints P = test::unit_hex();
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) P(i, k) += jitter();
    for (int node = 0; node < 8; ++node)
      for (double h : {1e-4, 0.3, -0.7}) {
        double out[3];
        quality::hex_sj_axis_steps(P, node, h, out);
        for (int k = 0; k < 3; ++k) {
          quality::CellPoints Q = P;
          Q(node, k) += h;
          const double expected = quality::scaled_jacobian(CellType::Hex, Q);
          EXPECT_EQ(out[k], expected) << "trial " << trial << " node " << node << " axis " << k << " step " << h;
          negative += expected < 0;
          ++compared;
        }
      }
  }
  EXPECT_EQ(compared, 200 * 8 * 3 * 3);
  EXPECT_GT(negative, 100);  // inverted corners are among the cases
  // Node 1 of the unit cube moved onto node 0 along x: a zero-length edge, DBL_MAX on that axis only.
  double out[3];
  quality::hex_sj_axis_steps(test::unit_hex(), 1, -1.0, out);
  EXPECT_EQ(out[0], 1e30);
  EXPECT_LT(out[1], 1.0);
  EXPECT_EQ(out[1], quality::scaled_jacobian(CellType::Hex, [] { auto Q = test::unit_hex(); Q(1, 1) -= 1.0; return Q; }()));
}
