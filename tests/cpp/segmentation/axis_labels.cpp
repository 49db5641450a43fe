#include "hexdom/segmentation/axis_labels.h"

#include "hexdom/common/error.h"
#include "seg_test_util.h"

using namespace hexdom;

TEST(AxisLabels, LabelsNameTheSixAxes) {
  const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (int l = 1; l <= 6; ++l) {
    EXPECT_EQ(segmentation::label_name(l), names[l - 1]);
    EXPECT_EQ(segmentation::nearest_label(segmentation::label_axis(l)), l);
    EXPECT_NEAR(segmentation::label_axis(l).norm(), 1.0, 0);
  }
  EXPECT_TRUE(segmentation::are_opposite(1, 2));
  EXPECT_TRUE(segmentation::are_opposite(6, 5));
  EXPECT_FALSE(segmentation::are_opposite(2, 3));
  EXPECT_FALSE(segmentation::are_opposite(4, 4));
  EXPECT_EQ(segmentation::label_name(0), "?");
  EXPECT_THROW(segmentation::label_axis(7), std::invalid_argument);
  EXPECT_EQ(segmentation::nearest_label(Eigen::Vector3d(0.3, -0.9, 0.2)), 4);
  EXPECT_EQ(segmentation::nearest_label(Eigen::Vector3d(1, 1, 0)), 1);  // ties go to the lower label
}

TEST(TriangleGeometry, UnitBoxNormalsAndAreas) {
  auto s = test::box_surface(1, 1, 1, 1);
  auto g = segmentation::triangle_geometry(s);
  EXPECT_NEAR(g.area.sum(), 6.0, 1e-12);
  for (int f = 0; f < s.F.rows(); ++f) EXPECT_NEAR(g.normal.row(f).dot(segmentation::label_axis(s.patch(f))), 1.0, 1e-12);
}

TEST(CheckSurface, MessagesNameTheProblem) {
  auto s = test::box_surface(1, 1, 1, 1);
  EXPECT_NO_THROW(segmentation::check_surface(s));
  auto bad = s;
  bad.patch.resize(3);
  EXPECT_THROW(segmentation::check_surface(bad), GeometryError);
  bad = s;
  bad.V.row(bad.F(4, 2)) = 0.5 * (bad.V.row(bad.F(4, 0)) + bad.V.row(bad.F(4, 1)));
  try {
    segmentation::check_surface(bad);
    FAIL();
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("zero area"), std::string::npos) << e.what();
  }
}
