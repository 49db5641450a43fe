#include "hexdom/segmentation/patch_graph.h"

#include "seg_test_util.h"

using namespace hexdom;

TEST(PatchGraph, BoxCurvesJoinCornersAndSeparateNeighbours) {
  auto s = test::box_surface(1, 2, 1, 2);
  auto g = segmentation::patch_graph(s);
  ASSERT_EQ(g.num_patches(), 6);
  EXPECT_EQ(g.curves.size(), 12u);
  for (int r = 0; r < 6; ++r) {
    EXPECT_EQ(g.euler[r], 1);
    EXPECT_EQ(g.patch_curves(r).size(), 4u);
    EXPECT_EQ(g.axis(r), s.patch(g.layout.patches[r].triangles[0]));
    EXPECT_NEAR(g.normal.row(r).norm(), 1.0, 1e-12);
  }
  for (size_t i = 0; i < g.curves.size(); ++i) {
    const auto& c = g.curves[i];
    EXPECT_FALSE(c.closed);
    EXPECT_GE(g.layout.corner_of(c.vertices.front()), 0);
    EXPECT_GE(g.layout.corner_of(c.vertices.back()), 0);
    for (size_t k = 1; k + 1 < c.vertices.size(); ++k) EXPECT_LT(g.layout.corner_of(c.vertices[k]), 0);
    // Listed once as itself by its left patch and once reversed by its right patch.
    auto has = [&](int r, int entry) {
      const auto& v = g.patch_curves(r);
      return std::find(v.begin(), v.end(), entry) != v.end();
    };
    EXPECT_TRUE(has(c.left, static_cast<int>(i)));
    EXPECT_TRUE(has(c.right, ~static_cast<int>(i)));
  }
}

TEST(PatchGraph, AnnulusHasEulerZero) {
  auto s = test::box_surface(1, 1, 1, 4);
  for (int f = 0; f < s.F.rows(); ++f) {
    Eigen::RowVector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3;
    if (s.patch(f) == 5 && std::abs(c(0) - 0.5) < 0.25 && std::abs(c(1) - 0.5) < 0.25) s.patch(f) = 9;
  }
  auto g = segmentation::patch_graph(s);
  for (int r = 0; r < g.num_patches(); ++r) {
    const int id = s.patch(g.layout.patches[r].triangles[0]);
    EXPECT_EQ(g.euler[r], id == 5 ? 0 : 1) << id;
  }
}
