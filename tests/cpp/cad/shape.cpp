// cad::ShapeInfo, shape_volume and BREP output.
#ifdef HEXDOM_WITH_CAD
#include <algorithm>

#include "cad_test_util.h"

using namespace hexdom;
using hexdom::test::write_part;

TEST(ShapeInfo, BoxFacts) {
  cad::ShapeInfo info = cad::shape_info(cad::read_shape(write_part(test::make_box(), "box_info")));
  EXPECT_EQ(info.faces, 6);
  EXPECT_EQ(info.edges, 12);
  EXPECT_EQ(info.vertices, 8);
  EXPECT_EQ(info.shells, 1);
  EXPECT_NEAR(info.volume, 480, 1e-9);
  EXPECT_NEAR(info.area, 2 * (80 + 60 + 48), 1e-9);
  EXPECT_TRUE(info.box.min().isApprox(Eigen::Vector3d(0, 0, 0), 1e-9) || info.box.min().norm() < 1e-6);
  EXPECT_LT((info.box.max() - Eigen::Vector3d(10, 8, 6)).norm(), 1e-6);
  EXPECT_EQ(info.vertex_points.rows(), 8);
  for (auto t : info.face_types) EXPECT_EQ(t, cad::SurfaceType::Plane);
}

TEST(ShapeInfo, SurfaceTypes) {
  auto types = [](const TopoDS_Shape& s, const std::string& name) {
    auto t = cad::shape_info(cad::read_shape(write_part(s, name))).face_types;
    std::vector<std::string> names;
    for (auto x : t) names.push_back(cad::surface_type_name(x));
    std::sort(names.begin(), names.end());
    return names;
  };
  EXPECT_EQ(types(test::make_cylinder(), "cyl_types"), (std::vector<std::string>{"cylinder", "plane", "plane"}));
  EXPECT_EQ(types(test::make_sphere(), "sphere_types"), (std::vector<std::string>{"sphere"}));
  EXPECT_EQ(types(test::make_cone(), "cone_types"), (std::vector<std::string>{"cone", "plane"}));
  EXPECT_EQ(types(test::make_torus(), "torus_types"), (std::vector<std::string>{"torus"}));
}

TEST(ShapeVolume, KnownSolids) {
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(write_part(test::make_sphere(), "sphere_vol"))), 4.0 / 3 * M_PI * 125, 1e-6);
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(write_part(test::make_cone(), "cone_vol"))), M_PI * 25 * 10 / 3, 1e-6);
}

TEST(WriteBrep, RoundTripsThroughAFile) {
  cad::Shape s = cad::read_shape(write_part(test::make_l_bracket(), "bracket_out"));
  const std::string path = test::temp_path("bracket_copy.brep");
  cad::write_brep(s, path);
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(path)), cad::shape_volume(s), 1e-9);
}

TEST(HasOpencascade, IsTrueInThisBuild) { EXPECT_TRUE(cad::has_opencascade()); }

TEST(Shape, EmptyShapeIsAGeometryError) {
  EXPECT_TRUE(cad::Shape().is_empty());
  EXPECT_THROW(cad::shape_info(cad::Shape()), GeometryError);
}
#endif
