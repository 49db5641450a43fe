#include "hexdom/autopolycube/repair/chart_graph.h"

#include "auto_test_util.h"
#include "hexdom/common/error.h"
#include "test_common.h"

using namespace hexdom;

// The graph itself (corners, curves, loops) is tested in polycube/boundary_graph.cpp.

TEST(ChartGraph, ChartsAreTheRegionsWithTheirAreas) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 3);
  auto g = autopolycube::chart_graph(s);
  EXPECT_EQ(g.num_charts(), 6);
  EXPECT_EQ(g.corners.size(), 8u);
  EXPECT_EQ(g.curves.size(), 12u);
  double total = 0;
  for (int c = 0; c < 6; ++c) {
    EXPECT_EQ(g.label[c], s.patch(g.triangles[c][0]));
    total += g.area[c];
  }
  EXPECT_NEAR(total, 10.0, 1e-12);  // a 2 x 1 x 1 box
  EXPECT_EQ(autopolycube::chart_name(g, 0).substr(0, 8), "chart 1 ");
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
