#include <cmath>
#include <numeric>

#include "hexdom/io/mesh_io.h"
#include "hexdom/quality/report.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;

namespace {
// Cells are separate copies of `P` (type t), each transformed by `f(i, P)`.
template <class F>
mesh::Mesh cells(CellType t, int n, F f) {
  const int k = mesh::node_count(t);
  Eigen::MatrixXd V(n * k, 3);
  mesh::MeshBuilder b;
  for (int i = 0; i < n; ++i) {
    quality::CellPoints P = t == CellType::Hex ? test::unit_hex() : t == CellType::Wedge ? test::unit_wedge() : test::unit_tet();
    f(i, P);
    int ids[8];
    for (int j = 0; j < k; ++j) {
      V.row(i * k + j) = P.row(j);
      ids[j] = i * k + j;
    }
    b.add(t, ids, 0);
  }
  return b.finish(V);
}
}  // namespace

TEST(QualityReport, CountsInvertedAndStatisticsPerType) {
  // Three hexes: ideal, sheared (SJ cos 0.4), mirrored (SJ -1).
  auto m = cells(CellType::Hex, 3, [](int i, quality::CellPoints& P) {
    if (i == 1) for (int r = 4; r < 8; ++r) P(r, 0) += std::tan(0.4);
    if (i == 2) P.col(2) *= -1.0;
  });
  const auto r = quality::quality_report(m);
  EXPECT_EQ(r.hex.count, 3);
  EXPECT_EQ(r.hex.inverted, 1);
  EXPECT_NEAR(r.hex.sj_min, -1.0, 1e-15);
  EXPECT_NEAR(r.hex.sj_mean, (1.0 + std::cos(0.4) - 1.0) / 3.0, 1e-12);
  EXPECT_NEAR(r.hex.edge_ratio_min, 1.0, 1e-15);
  EXPECT_NEAR(r.hex.volume, 1.0 + 1.0 - 1.0, 1e-12);
  EXPECT_EQ(std::accumulate(r.hex.histogram.begin(), r.hex.histogram.end(), 0), 3);
  EXPECT_EQ(r.hex.histogram[0], 1);
  EXPECT_EQ(r.hex.histogram[19], 2);  // 1 and cos 0.4 = 0.92
  EXPECT_EQ(r.prism.count, 0);
  EXPECT_TRUE(std::isnan(r.prism.sj_min) && std::isnan(r.tet.edge_ratio_max) && std::isnan(r.tet.sj_mean));
}

TEST(QualityReport, DegenerateCellsCountAsMinusOne) {
  auto m = cells(CellType::Wedge, 2, [](int i, quality::CellPoints& P) {
    if (i == 1) P.row(4) = P.row(1);  // zero-length vertical edge
  });
  const auto r = quality::quality_report(m);
  EXPECT_EQ(r.prism.count, 2);
  EXPECT_EQ(r.prism.inverted, 1);
  EXPECT_EQ(r.prism.sj_min, -1.0);
  EXPECT_NEAR(r.prism.sj_mean, 0.0, 1e-12);
  EXPECT_EQ(r.prism.edge_ratio_max, 1e30);
}

TEST(QualityReport, TetWithCoincidentNodesIsInverted) {
  // Verdict's tet scaled Jacobian of a tet whose nodes 2 and 3 coincide is a rounding error that
  // may be positive; the report must still count the tet as degenerate.
  auto m = cells(CellType::Tet, 3, [](int i, quality::CellPoints& P) {
    P.row(3) << 0.3, 0.45, 0.7;
    if (i == 1) P.row(3) = P.row(2);
    if (i == 2) P.row(1) = P.row(0);
  });
  const auto r = quality::quality_report(m);
  EXPECT_EQ(r.tet.count, 3);
  EXPECT_EQ(r.tet.inverted, 2);
  EXPECT_LE(r.tet.sj_min, 0.0);
}

TEST(QualityReport, RockerarmHexGenOutput) {
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm3_hex.vtk");
  HEXDOM_REQUIRE_DATA(path);
  const auto r = quality::quality_report(io::read_mesh(path));
  EXPECT_EQ(r.hex.count, 3840);
  EXPECT_EQ(r.hex.inverted, 11);
  EXPECT_NEAR(r.hex.sj_min, -0.4509443843940587, 1e-12);
  EXPECT_NEAR(r.hex.sj_mean, 0.836170011564014, 1e-12);  // Verdict's mean
  EXPECT_GT(r.total_volume, 0);
}
