#include "hexdom/segmentation/segmentation_stats.h"

#include "seg_test_util.h"

using namespace hexdom;

TEST(SegmentationStats, BoxKnownAnswers) {
  auto s = test::box_surface(2, 1, 1, 3);
  auto st = segmentation::segmentation_stats(s, s.patch);
  EXPECT_EQ(st.patches, 6);
  EXPECT_EQ(st.small_patches, 0);
  EXPECT_NEAR(st.boundary_length, 4 * 2 + 4 * 1 + 4 * 1, 1e-12);
  EXPECT_EQ(st.teeth, 0);
  EXPECT_DOUBLE_EQ(st.axis_fraction, 1.0);
  EXPECT_NEAR(st.label_area[0], 1.0, 1e-12);  // +X face 1 x 1
  EXPECT_NEAR(st.label_area[4], 2.0, 1e-12);  // +Z face 2 x 1
}

TEST(SegmentationStats, ATriangleOfAnotherLabelIsATooth) {
  auto s = test::box_surface(1, 1, 1, 4);
  Eigen::VectorXi label = s.patch;
  int f = 0;
  while (label(f) != 5) ++f;
  // A triangle inside the +Z face, given -X: 3 neighbours of another label, all area off-axis.
  for (int g = 0; g < s.F.rows(); ++g) {
    Eigen::RowVector3d c = (s.V.row(s.F(g, 0)) + s.V.row(s.F(g, 1)) + s.V.row(s.F(g, 2))) / 3;
    if (label(g) == 5 && std::abs(c(0) - 0.4) < 0.1 && std::abs(c(1) - 0.4) < 0.1) { f = g; break; }
  }
  label(f) = 2;
  auto st = segmentation::segmentation_stats(s, label);
  EXPECT_EQ(st.teeth, 1);  // the triangle: its 3 neighbours have one foreign side each
  EXPECT_EQ(st.patches, 7);
  EXPECT_EQ(st.small_patches, 1);
  EXPECT_LT(st.axis_fraction, 1.0);
  EXPECT_NE(segmentation::to_text(st).find("zig-zag triangles"), std::string::npos);
}
