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

// Points along an edge: on it (their projections onto it are themselves), from end to end, no
// two consecutive ones farther apart than the spacing; a circle's points on the circle.
TEST(EdgePoints, FollowTheEdgeAtTheSpacing) {
  cad::Shape s = cad::read_shape(write_part(test::make_cylinder(), "edge_points"));
  const cad::ShapeInfo info = cad::shape_info(s);
  int circles = 0;
  for (int e = 1; e <= info.edges; ++e) {
    const Eigen::MatrixXd P = cad::edge_points(s, e, 0.5);
    ASSERT_GE(P.rows(), 2);
    EXPECT_LT(cad::project_to_edge(s, e, P).distance.maxCoeff(), 1e-7);
    double longest = 0, length = 0;
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
      longest = std::max(longest, (P.row(i + 1) - P.row(i)).norm());
      length += (P.row(i + 1) - P.row(i)).norm();
    }
    EXPECT_LE(longest, 0.5);
    const Eigen::VectorXd r = P.leftCols(2).rowwise().norm();
    const bool flat = P.col(2).maxCoeff() - P.col(2).minCoeff() < 1e-9;  // (the seam is at radius 5 too)
    if (flat && (r.array() - 5).abs().maxCoeff() < 1e-9) {  // a rim: radius 5, closed, 2 pi 5 long
      ++circles;
      EXPECT_NEAR(length, 2 * M_PI * 5, 0.01);
      EXPECT_LT((P.row(0) - P.row(P.rows() - 1)).norm(), 1e-9);
    }
  }
  EXPECT_EQ(circles, 2);
  EXPECT_THROW(cad::edge_points(s, info.edges + 1, 0.5), InputError);
  EXPECT_THROW(cad::edge_points(s, 1, 0), InputError);
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

#ifdef HEXDOM_WITH_CAD
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <gp_Circ.hxx>

#include <random>

#include "hexdom/cad/face_projector.h"

// A node sliding along an edge (the snap's restoration) is projected from its last parameter
// (nearest_on_edge_from): on a circular arc and on a wavy B-spline, points stepping along the edge
// 0.3 off it get the same nearest point as the whole-edge search, and a point beyond an end gets
// that end.
TEST(ProjectToEdge, FromTheLastParameterMatchesTheWholeEdgeSearch) {
  TColgp_Array1OfPnt pts(1, 12);
  for (int i = 1; i <= 12; ++i) pts(i) = gp_Pnt(3.0 * i, 2.0 * std::sin(0.8 * i), 0.5 * std::cos(1.3 * i));
  const TopoDS_Edge spline = BRepBuilderAPI_MakeEdge(Handle(Geom_Curve)(GeomAPI_PointsToBSpline(pts).Curve()));
  const TopoDS_Edge arc = BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 10.0), 0.2, 2.5);
  for (const TopoDS_Edge& edge : {spline, arc}) {
    const cad::EdgeCurve e = cad::edge_curve(edge);
    ASSERT_FALSE(e.curve.IsNull());
    double t_last = 0;
    bool have = false;
    int checked = 0;
    for (int k = 0; k <= 200; ++k) {
      const double u = e.first + (e.last - e.first) * k / 200.0;
      gp_Pnt on;
      gp_Vec tangent;
      e.curve->D1(u, on, tangent);
      gp_Vec side = tangent.Crossed(gp_Vec(0, 0, 1));
      if (side.Magnitude() < 1e-9) continue;
      const gp_Pnt p = on.Translated(side.Normalized() * 0.3);
      gp_Pnt qg, ql;
      double tg, tl, dg, dl;
      ASSERT_TRUE(cad::nearest_on_edge(e, p, qg, tg, dg));
      ASSERT_TRUE(have ? cad::nearest_on_edge_from(e, p, t_last, ql, tl, dl) : cad::nearest_on_edge(e, p, ql, tl, dl));
      EXPECT_LT(ql.Distance(qg), 1e-7) << "k " << k;
      EXPECT_NEAR(dl, dg, 1e-9);
      t_last = tl;
      have = true;
      ++checked;
    }
    EXPECT_GT(checked, 150);
    // Beyond the last end: that end, from a parameter near it.
    gp_Pnt end;
    gp_Vec tangent;
    e.curve->D1(e.last, end, tangent);
    const gp_Pnt beyond = end.Translated(tangent.Normalized() * 2.0);
    gp_Pnt q;
    double t, d;
    ASSERT_TRUE(cad::nearest_on_edge_from(e, beyond, e.last - 0.01 * (e.last - e.first), q, t, d));
    EXPECT_LT(q.Distance(end), 1e-7);
    EXPECT_NEAR(d, 2.0, 1e-6);
  }
}

// FaceClassifier answers as BRepTopAdaptor_FClass2d does, on every face of parts with holes, fillets,
// periodic surfaces (cylinder, sphere, cone, torus) and a hole far smaller than a grid cell (radius
// 0.01 in a face 20 wide: cells of 0.16): random points over the face's parameter bounds and 10%
// beyond them, points along each boundary curve and 1e-3 of the bounds on either side of it, and
// points around the small hole. Many of them come from the grid, so the grid is what is checked.
TEST(FaceClassifier, AnswersAsTheClassifierOnEveryFace) {
  TopoDS_Shape pinhole = BRepAlgoAPI_Cut(BRepPrimAPI_MakeBox(20.0, 20.0, 10.0).Shape(),
                                         BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(7, 9, -1), gp_Dir(0, 0, 1)), 0.01, 12.0).Shape())
                             .Shape();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long checked = 0, from_grid = 0, inside_hole = 0;
  for (const TopoDS_Shape& shape : {test::make_box_with_hole(), test::make_filleted_box(), test::make_cylinder(), test::make_sphere(),
                                    test::make_cone(), test::make_torus(), pinhole}) {
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face face = TopoDS::Face(ex.Current());
      double u0, u1, v0, v1;
      BRepTools::UVBounds(face, u0, u1, v0, v1);
      const double tol = std::max(BRep_Tool::Tolerance(face), 1e-9);
      const BRepTopAdaptor_FClass2d reference(face, tol);
      const cad::FaceClassifier cached(face, tol, u0, u1, v0, v1);
      std::vector<gp_Pnt2d> points;
      for (int k = 0; k < 4000; ++k)
        points.emplace_back(u0 + (u1 - u0) * (1.2 * unit(rng) - 0.1), v0 + (v1 - v0) * (1.2 * unit(rng) - 0.1));
      for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
        double first, last;
        const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Current()), face, first, last);
        ASSERT_FALSE(c.IsNull());
        for (int k = 0; k <= 50; ++k) {
          const gp_Pnt2d q = c->Value(first + (last - first) * k / 50.0);
          for (double du : {-1e-3, 0.0, 1e-3})
            for (double dv : {-1e-3, 0.0, 1e-3}) points.emplace_back(q.X() + du * (u1 - u0), q.Y() + dv * (v1 - v0));
        }
      }
      // The pin hole at (7, 9) on the plane faces z = 0 and z = 10, whose parameters are x and y
      // up to a shift: points within and around it in the parameters' own units.
      Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
      GeomAPI_ProjectPointOnSurf onto(gp_Pnt(7, 9, 0), surface);
      if (shape.IsSame(pinhole) && onto.NbPoints() > 0) {
        double u, v;
        onto.LowerDistanceParameters(u, v);
        for (int k = 0; k < 400; ++k) points.emplace_back(u + 0.03 * (unit(rng) - 0.5), v + 0.03 * (unit(rng) - 0.5));
      }
      for (const gp_Pnt2d& p : points) {
        const TopAbs_State want = reference.Perform(p), got = cached.Perform(p);
        ASSERT_EQ(got, want) << "(" << p.X() << ", " << p.Y() << ") on a face of bounds [" << u0 << ", " << u1 << "] x [" << v0
                             << ", " << v1 << "]";
        ++checked;
        const gp_Pnt x = surface->Value(p.X(), p.Y());
        inside_hole += shape.IsSame(pinhole) && want == TopAbs_OUT && std::hypot(x.X() - 7, x.Y() - 9) < 0.009;
      }
      from_grid += cached.from_grid();
    }
  }
  std::printf("%ld points, %ld from the grid, %ld inside the pin hole\n", checked, from_grid, inside_hole);
  EXPECT_GT(from_grid, checked / 3);  // 44%: a third of the points lie near a boundary or beyond the bounds
  EXPECT_GT(inside_hole, 0) << "no point fell in the pin hole: the test would not see it";
}
#endif

