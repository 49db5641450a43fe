// cad::project_to_face / project_to_edge / project_to_shape.
#ifdef HEXDOM_WITH_CAD
#include "cad_test_util.h"

using namespace hexdom;
using hexdom::test::write_part;

namespace {
/// The id of the box face lying in the plane coordinate `axis` = `value`.
int box_face(const cad::Shape& s, int axis, double value) {
  const cad::ShapeInfo info = cad::shape_info(s);
  Eigen::MatrixXd P(1, 3);
  P << 5, 4, 3;
  P(0, axis) = value;
  for (int f = 1; f <= info.faces; ++f)
    if (cad::project_to_face(s, f, P).distance(0) < 1e-9) return f;
  return -1;
}
}  // namespace

TEST(ProjectToFace, PointAboveAPlanarFaceDropsOntoIt) {
  cad::Shape s = cad::read_shape(write_part(test::make_box(), "proj_box"));
  const int top = box_face(s, 2, 6.0);
  ASSERT_GT(top, 0);
  Eigen::MatrixXd P(2, 3);
  P << 2, 3, 9, 7, 1, 6.5;
  cad::Projection r = cad::project_to_face(s, top, P);
  EXPECT_LT((r.points.row(0) - Eigen::RowVector3d(2, 3, 6)).norm(), 1e-9);
  EXPECT_NEAR(r.distance(0), 3, 1e-9);
  EXPECT_LT((r.points.row(1) - Eigen::RowVector3d(7, 1, 6)).norm(), 1e-9);
  EXPECT_EQ(r.id(0), top);
}

TEST(ProjectToFace, PointBesideTheFaceGoesToItsBoundary) {
  // The plane extends beyond the face; the nearest point of the (trimmed) face is on its edge.
  cad::Shape s = cad::read_shape(write_part(test::make_box(), "proj_trim"));
  const int top = box_face(s, 2, 6.0);
  Eigen::MatrixXd P(1, 3);
  P << 14, 3, 7;
  cad::Projection r = cad::project_to_face(s, top, P);
  EXPECT_LT((r.points.row(0) - Eigen::RowVector3d(10, 3, 6)).norm(), 1e-7) << r.points;
  EXPECT_NEAR(r.distance(0), std::sqrt(17.0), 1e-7);
}

TEST(ProjectToFace, HoleIsNotPartOfTheFace) {
  cad::Shape s = cad::read_shape(write_part(test::make_box_with_hole(), "proj_hole"));
  Eigen::MatrixXd Q(1, 3);
  Q << 1, 1, 10;
  int top = -1;
  for (int f = 1; f <= cad::shape_info(s).faces; ++f)
    if (cad::project_to_face(s, f, Q).distance(0) < 1e-9) top = f;
  ASSERT_GT(top, 0);
  Eigen::MatrixXd P(1, 3);
  P << 10, 11, 12;  // above the hole, 1 from its axis: nearest is the rim, 3 away sideways
  cad::Projection r = cad::project_to_face(s, top, P);
  EXPECT_NEAR(r.points(0, 2), 10, 1e-7);
  EXPECT_NEAR(std::hypot(r.points(0, 0) - 10, r.points(0, 1) - 10), 4, 1e-6);
  EXPECT_NEAR(r.distance(0), std::sqrt(9.0 + 4.0), 1e-6);
}

TEST(ProjectToFace, CylinderPointsGoRadially) {
  cad::Shape s = cad::read_shape(write_part(test::make_cylinder(), "proj_cyl"));
  const cad::ShapeInfo info = cad::shape_info(s);
  const int side = static_cast<int>(std::find(info.face_types.begin(), info.face_types.end(), cad::SurfaceType::Cylinder) -
                                    info.face_types.begin()) + 1;
  Eigen::MatrixXd P(3, 3);
  P << 9, 0, 5, 0, -2, 7, 3, 4, 11;
  cad::Projection r = cad::project_to_face(s, side, P);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::hypot(r.points(i, 0), r.points(i, 1)), 5, 1e-7);
    EXPECT_NEAR(r.points(i, 2), P(i, 2), 1e-7);
  }
  EXPECT_NEAR(r.distance(0), 4, 1e-7);
  EXPECT_NEAR(r.distance(1), 3, 1e-7);
  EXPECT_NEAR(r.distance(2), 0, 1e-7);
}

TEST(ProjectToFace, BadFaceIdIsAnInputError) {
  cad::Shape s = cad::read_shape(write_part(test::make_box(), "proj_bad"));
  EXPECT_THROW(cad::project_to_face(s, 7, Eigen::MatrixXd::Zero(1, 3)), InputError);
  EXPECT_THROW(cad::project_to_face(s, 0, Eigen::MatrixXd::Zero(1, 3)), InputError);
  EXPECT_THROW(cad::project_to_face(s, 1, Eigen::MatrixXd::Zero(1, 2)), InputError);
}

TEST(ProjectToEdge, LineEdgeClampsToItsEnds) {
  cad::Shape s = cad::read_shape(write_part(test::make_box(), "proj_edge"));
  const cad::ShapeInfo info = cad::shape_info(s);
  Eigen::MatrixXd P(2, 3);
  P << 5, -3, -4, 20, 0, 0;
  int found = 0;
  for (int e = 1; e <= info.edges; ++e) {
    cad::Projection r = cad::project_to_edge(s, e, P);
    if (r.distance(0) < 5 + 1e-9) {  // the edge along x at y = z = 0
      ++found;
      EXPECT_LT((r.points.row(0) - Eigen::RowVector3d(5, 0, 0)).norm(), 1e-9);
      EXPECT_LT((r.points.row(1) - Eigen::RowVector3d(10, 0, 0)).norm(), 1e-9);
      EXPECT_NEAR(r.distance(1), 10, 1e-9);
    }
  }
  EXPECT_EQ(found, 1);
  EXPECT_THROW(cad::project_to_edge(s, 13, P), InputError);
}

TEST(ProjectToShape, NamesTheNearestFace) {
  cad::Shape s = cad::read_shape(write_part(test::make_box(), "proj_shape"));
  Eigen::MatrixXd P(3, 3);
  P << 5, 4, 7, 5, 4, 5.5, -1, 4, 3;
  cad::Projection r = cad::project_to_shape(s, P);
  EXPECT_EQ(r.id(0), box_face(s, 2, 6.0));
  EXPECT_EQ(r.id(1), box_face(s, 2, 6.0));
  EXPECT_EQ(r.id(2), box_face(s, 0, 0.0));
  EXPECT_NEAR(r.distance(0), 1, 1e-9);
  EXPECT_NEAR(r.distance(1), 0.5, 1e-9);
  EXPECT_NEAR(r.distance(2), 1, 1e-9);
}
#endif
