#include "hexdom/autopolycube/chart_graph.h"

#include "auto_test_util.h"
#include "hexdom/common/error.h"
#include "test_common.h"

using namespace hexdom;

TEST(ChartGraph, BoxHasSixChartsEightCornersTwelveCurves) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 3);
  auto g = autopolycube::chart_graph(s);
  EXPECT_EQ(g.num_charts(), 6);
  EXPECT_EQ(g.corners.size(), 8u);
  EXPECT_EQ(g.curves.size(), 12u);
  EXPECT_TRUE(g.pinches.empty());
  for (int c = 0; c < 6; ++c) {
    ASSERT_EQ(g.loop_corners[c].size(), 1u);
    EXPECT_EQ(g.loop_corners[c][0].size(), 4u);
    EXPECT_EQ(g.loop_curves[c][0].size(), 4u);
  }
  for (const auto& c : g.curves) {
    EXPECT_FALSE(c.closed);
    EXPECT_LT(c.left, c.right);
    EXPECT_GE(g.corner_of(c.vertices.front()), 0);
    EXPECT_GE(g.corner_of(c.vertices.back()), 0);
  }
}

TEST(ChartGraph, LoopsRunCounterClockwiseAndChainAtCorners) {
  // L shape: the top and bottom are L-shaped charts with 6 corners, one of them concave.
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2);
  auto g = autopolycube::chart_graph(s);
  EXPECT_EQ(g.num_charts(), 8);
  EXPECT_EQ(g.corners.size(), 12u);
  int six = 0;
  for (int c = 0; c < g.num_charts(); ++c) {
    for (size_t l = 0; l < g.loop_curves[c].size(); ++l) {
      const auto& loop = g.loop_curves[c][l];
      six += loop.size() == 6;
      // Consecutive curves meet at the loop's corners.
      for (size_t i = 0; i < loop.size(); ++i) {
        auto end = [&](int sc, bool last) {
          const auto& cv = g.curves[sc < 0 ? ~sc : sc];
          return (sc < 0) != last ? cv.vertices.back() : cv.vertices.front();
        };
        EXPECT_EQ(end(loop[i], true), end(loop[(i + 1) % loop.size()], false));
        EXPECT_EQ(end(loop[i], false), g.loop_corners[c][l][i]);
      }
    }
  }
  EXPECT_EQ(six, 2);
}

TEST(ChartGraph, IslandMeetsItsSurroundingsAlongAClosedCurve) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  // Two triangles in the middle of the +Z face labelled +X.
  int changed = 0;
  for (int f = 0; f < s.F.rows() && changed < 2; ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    if (s.patch(f) == 5 && std::abs(c(0) - 0.5) < 0.25 && std::abs(c(1) - 0.5) < 0.25) { s.patch(f) = 1; ++changed; }
  }
  ASSERT_EQ(changed, 2);
  auto g = autopolycube::chart_graph(s);
  EXPECT_EQ(g.num_charts(), 7);
  int closed = 0;
  for (const auto& c : g.curves) closed += c.closed;
  EXPECT_EQ(closed, 1);
}

TEST(ChartGraph, LabelsOutsideOneToSixAreRejected) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.patch(3) = 7;
  try {
    autopolycube::chart_graph(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 4 has label 7"), std::string::npos) << e.what();
  }
}

TEST(ChartGraph, OpenSurfaceIsRejected) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.F.conservativeResize(s.F.rows() - 1, 3);
  s.patch.conservativeResize(s.F.rows());
  EXPECT_THROW(autopolycube::chart_graph(s), GeometryError);
}
