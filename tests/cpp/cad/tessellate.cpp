// cad::tessellate on parts built here with OCCT and on the shared STEP parts.
#ifdef HEXDOM_WITH_CAD
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS.hxx>

#include <filesystem>
#include <functional>

#include "cad_test_util.h"

using namespace hexdom;
using hexdom::test::check_tessellation;
using hexdom::test::write_part;

namespace {

struct Part {
  std::string name;
  std::function<TopoDS_Shape()> make;
  /// Enclosed-volume tolerance at size = diagonal / 30 with the default deflection (size / 50).
  /// The torus (minor radius 3 in a diagonal of 32) loses 0.6% to its chords there; with a smaller
  /// deflection it meets 0.5% (DeflectionBoundsTheVolumeError).
  double volume_tolerance = 0.005;
};

void PrintTo(const Part& part, std::ostream* os) { *os << part.name; }

std::vector<Part> test_parts() {
  return {{"box", test::make_box},           {"box_with_hole", test::make_box_with_hole},
          {"l_bracket", test::make_l_bracket}, {"cylinder", test::make_cylinder},
          {"sphere", test::make_sphere},     {"cone", test::make_cone},
          {"torus", test::make_torus, 0.008}, {"box_with_cavity", test::make_box_with_cavity},
          {"filleted_box", test::make_filleted_box}};
}

double diagonal(const cad::Shape& s) { return cad::shape_info(s).box.diagonal().norm(); }

class TessellateTestPart : public ::testing::TestWithParam<Part> {};

}  // namespace

TEST_P(TessellateTestPart, ClosedOutwardAccurateAndWellShaped) {
  // At the bench's size (diagonal / 30) the enclosed volume is within 0.5%; at twice that size the
  // chords of a sphere or torus alone lose about 2%.
  const Part& part = GetParam();
  cad::Shape shape = cad::read_shape(write_part(part.make(), part.name));
  for (auto [divisions, volume_tolerance] : {std::pair{30.0, part.volume_tolerance}, std::pair{15.0, 0.025}}) {
    cad::TessellateOptions opt;
    opt.size = diagonal(shape) / divisions;
    cad::TessellateStats st;
    mesh::SurfaceMesh s = cad::tessellate(shape, opt, &st);
    SCOPED_TRACE(part.name + " at size diagonal/" + std::to_string(static_cast<int>(divisions)));
    auto r = check_tessellation(shape, s, opt.size, volume_tolerance);
    EXPECT_TRUE(st.closed);
    EXPECT_NEAR(st.min_angle, r.min_angle, 1e-9);
    EXPECT_NEAR(st.volume, test::enclosed_volume(s), 1e-9 * std::abs(st.volume));
  }
}

TEST_P(TessellateTestPart, DeflectionBoundsTheVolumeError) {
  // A small deflection refines curved faces until the coarse size meets 0.5% too.
  const Part& part = GetParam();
  cad::Shape shape = cad::read_shape(write_part(part.make(), part.name + "_defl"));
  cad::TessellateOptions opt;
  opt.size = diagonal(shape) / 15;
  opt.deflection = opt.size / 200;
  mesh::SurfaceMesh s = cad::tessellate(shape, opt);
  check_tessellation(shape, s, opt.size, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Parts, TessellateTestPart, ::testing::ValuesIn(test_parts()),
                         [](const auto& info) { return info.param.name; });

TEST(Tessellate, BoxGivesExactlySixFaceIds) {
  cad::Shape shape = cad::read_shape(write_part(test::make_box(), "box6"));
  cad::TessellateOptions opt;
  opt.size = 2.0;
  mesh::SurfaceMesh s = cad::tessellate(shape, opt);
  auto r = check_tessellation(shape, s, opt.size);
  EXPECT_EQ(r.face_ids, (std::set<int>{1, 2, 3, 4, 5, 6}));
}

TEST(Tessellate, SizeFollowsTheOption) {
  cad::Shape shape = cad::read_shape(write_part(test::make_box_with_hole(), "hole_sizes"));
  std::vector<int> triangles;
  for (double size : {2.0, 1.0, 0.5}) {
    cad::TessellateOptions opt;
    opt.size = size;
    mesh::SurfaceMesh s = cad::tessellate(shape, opt);
    auto r = check_tessellation(shape, s, size);
    EXPECT_GT(r.mean_edge_planar, 0.7 * size) << size;
    EXPECT_LT(r.mean_edge_planar, 1.15 * size) << size;
    triangles.push_back(static_cast<int>(s.F.rows()));
  }
  // Halving the size about quadruples the triangles.
  for (int i = 1; i < 3; ++i) {
    const double ratio = static_cast<double>(triangles[i]) / triangles[i - 1];
    EXPECT_GT(ratio, 3.0) << triangles[i - 1] << " -> " << triangles[i];
    EXPECT_LT(ratio, 5.0) << triangles[i - 1] << " -> " << triangles[i];
  }
}

TEST(Tessellate, CurvatureRefinesSmallHoles) {
  // A hole of radius 4 at size 4: the 30-degree angle limit puts at least 12 edges around it.
  cad::Shape shape = cad::read_shape(write_part(test::make_box_with_hole(), "hole_curvature"));
  cad::TessellateOptions opt;
  opt.size = 4.0;
  mesh::SurfaceMesh s = cad::tessellate(shape, opt);
  int on_rim = 0;
  for (int v = 0; v < s.V.rows(); ++v) {
    const double r = std::hypot(s.V(v, 0) - 10, s.V(v, 1) - 10);
    if (std::abs(r - 4.0) < 1e-6 && std::abs(s.V(v, 2)) < 1e-9) ++on_rim;
  }
  EXPECT_GE(on_rim, 12);
}

TEST(Tessellate, SmallSizesDoNotSpreadAlongLongEdges) {
  // A plate 200 x 100 with a slot 0.3 wide and 150 long: the slot's faces need edges of about 0.3,
  // and BRepMesh's first triangles join the slot's ends to far corners of the plate by edges 100
  // long. The split points of such an edge take sizes graded from its ends, so the small sizes
  // reach only a few units into the plate's faces: splits stay within a few times the vertices
  // kept (1.7 times; sizes averaged from the ends filled whole edges: 12 times).
  const TopoDS_Shape plate = BRepPrimAPI_MakeBox(200.0, 100.0, 10.0).Shape();
  const TopoDS_Shape slot = BRepPrimAPI_MakeBox(gp_Pnt(25.0, 49.85, -1.0), 150.0, 0.3, 12.0).Shape();
  cad::Shape shape = cad::read_shape(write_part(BRepAlgoAPI_Cut(plate, slot).Shape(), "long_slot"));
  cad::TessellateStats st;
  mesh::SurfaceMesh s = cad::tessellate(shape, {}, &st);
  EXPECT_TRUE(st.closed);
  EXPECT_LT(st.min_edge, 0.35);  // the slot's width is resolved
  EXPECT_LT(st.splits, 3L * st.vertices) << st.vertices << " vertices";
}

TEST(Tessellate, VerticesLieOnTheBrep) {
  for (const Part& part : test_parts()) {
    cad::Shape shape = cad::read_shape(write_part(part.make(), part.name + "_on"));
    mesh::SurfaceMesh s = cad::tessellate(shape);
    const cad::Projection p = cad::project_to_shape(shape, s.V);
    EXPECT_LT(p.distance.maxCoeff(), 1e-6 * diagonal(shape)) << part.name;
  }
}

TEST(Tessellate, CadEdgesAreMeshEdges) {
  // Every mesh edge between two different faces lies on a CAD edge, and every CAD edge other than a
  // seam is covered by such mesh edges.
  const std::string path = write_part(test::make_box_with_hole(), "hole_edges");
  cad::Shape shape = cad::read_shape(path);
  mesh::SurfaceMesh s = cad::tessellate(shape);
  const cad::ShapeInfo info = cad::shape_info(shape);
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (int t = 0; t < s.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      int a = s.F(t, k), b = s.F(t, (k + 1) % 3);
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(s.patch(t));
    }
  std::vector<double> covered(info.edges + 1, 0.0);
  for (const auto& [e, f] : faces_of_edge) {
    ASSERT_EQ(f.size(), 2u);
    if (f[0] == f[1]) continue;
    Eigen::MatrixXd P(2, 3);
    P.row(0) = s.V.row(e.first);
    P.row(1) = s.V.row(e.second);
    int on = -1;
    for (int id = 1; id <= info.edges && on < 0; ++id) {
      try {
        if (cad::project_to_edge(shape, id, P).distance.maxCoeff() < 1e-7) on = id;
      } catch (const GeometryError&) {  // a degenerated edge has no curve
      }
    }
    ASSERT_GT(on, 0) << "feature edge (" << e.first << ", " << e.second << ") is on no CAD edge";
    covered[on] += (s.V.row(e.first) - s.V.row(e.second)).norm();
  }
  // Independently: the edges and their faces as OCCT reads the file.
  TopoDS_Shape read;
  BRep_Builder builder;
  ASSERT_TRUE(BRepTools::Read(read, path.c_str(), builder));
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(read, TopAbs_EDGE, edges);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(read, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  ASSERT_EQ(edges.Extent(), info.edges);
  for (int id = 1; id <= info.edges; ++id) {
    if (edge_faces.FindFromKey(edges(id)).Extent() < 2) continue;  // a seam
    GProp_GProps g;
    BRepGProp::LinearProperties(edges(id), g);
    // Straight edges are covered exactly, circles by chords (12 or more: within 1.2%).
    EXPECT_NEAR(covered[id], g.Mass(), 0.012 * g.Mass()) << "Edge" << id;
  }
}

TEST(Tessellate, FaceIdsAreFreeCadFaceNumbers) {
  // Independently of hexdom_cad: TopExp::MapShapes on the original shape and OCCT's own distance.
  TopoDS_Shape original = test::make_l_bracket();
  cad::Shape shape = cad::read_shape(write_part(original, "lbracket_ids"));
  mesh::SurfaceMesh s = cad::tessellate(shape);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(original, TopAbs_FACE, faces);
  ASSERT_EQ(faces.Extent(), 8);
  for (int t = 0; t < s.F.rows(); t += 7) {
    const Eigen::Vector3d c = (s.V.row(s.F(t, 0)) + s.V.row(s.F(t, 1)) + s.V.row(s.F(t, 2))) / 3.0;
    BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(gp_Pnt(c.x(), c.y(), c.z())).Vertex(),
                                 faces(s.patch(t)));
    ASSERT_TRUE(d.IsDone());
    EXPECT_LT(d.Value(), 1e-7) << "triangle " << t << " labelled Face" << s.patch(t);
  }
}

TEST(Tessellate, InsideOutSolidStillGivesOutwardTriangles) {
  std::vector<std::string> warnings;
  cad::ReadOptions ro;
  ro.log = [&](int, const std::string& m) { warnings.push_back(m); };
  cad::Shape shape = cad::read_shape(write_part(test::make_cylinder().Reversed(), "reversed"), ro);
  mesh::SurfaceMesh s = cad::tessellate(shape);
  EXPECT_GT(test::enclosed_volume(s), 0);
  EXPECT_GT(cad::shape_volume(shape), 0);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("inside out"), std::string::npos) << warnings[0];
}

TEST(Tessellate, BrepMeshAloneGivesSkinnyTriangles) {
  // iterations = 0 keeps BRepMesh's triangles: closed, but with the needles that the remeshing removes.
  cad::Shape shape = cad::read_shape(write_part(test::make_box_with_hole(), "hole_raw"));
  cad::TessellateOptions opt;
  opt.iterations = 0;
  cad::TessellateStats raw, remeshed;
  cad::tessellate(shape, opt, &raw);
  cad::tessellate(shape, {}, &remeshed);
  EXPECT_TRUE(raw.closed);
  EXPECT_LT(raw.min_angle_planar, 15.0);
  EXPECT_GE(remeshed.min_angle_planar, 20.0);
}

TEST(Tessellate, BadOptionsAreInputErrors) {
  cad::Shape shape = cad::read_shape(write_part(test::make_box(), "box_opts"));
  cad::TessellateOptions opt;
  opt.size = -1;
  EXPECT_THROW(cad::tessellate(shape, opt), InputError);
  opt.size = 1e-4;  // 10^9 triangles
  try {
    cad::tessellate(shape, opt);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangles"), std::string::npos) << e.what();
  }
}

TEST(Tessellate, EmptyShapeIsAGeometryError) { EXPECT_THROW(cad::tessellate(cad::Shape()), GeometryError); }

namespace {
std::vector<std::string> shared_step_parts() {
  std::vector<std::string> names = {"i01o_m1.step", "i10o_simp.step", "i11o_s1.step", "n11o_limit_cycle.stp",
                                    "s09o_bridge.step", "s11o_cube_cyl.stp", "s12o_cube_rounded_1.stp",
                                    "s14o_cube_corner_sub_sphere.stp", "s15o_cylinder.stp"};
  return names;
}
class TessellateSharedStep : public ::testing::TestWithParam<std::string> {};
}  // namespace

TEST_P(TessellateSharedStep, ClosedOutwardAccurateAndWellShaped) {
  const std::string path = test::data_path("cad/" + GetParam());
  HEXDOM_REQUIRE_DATA(path);
  cad::Shape shape = cad::read_shape(path);
  cad::TessellateOptions opt;
  opt.size = diagonal(shape) / 30.0;
  cad::TessellateStats st;
  mesh::SurfaceMesh s = cad::tessellate(shape, opt, &st);
  auto r = check_tessellation(shape, s, opt.size);
  RecordProperty("triangles", st.triangles);
  std::cout << "[ figures  ] " << GetParam() << ": " << st.triangles << " triangles, min angle planar "
            << r.min_angle_planar << " (away from sharp corners), all " << r.min_angle << ", volume error "
            << 100 * r.volume_error << "%\n";
}

INSTANTIATE_TEST_SUITE_P(Shared, TessellateSharedStep, ::testing::ValuesIn(shared_step_parts()),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });
#endif
