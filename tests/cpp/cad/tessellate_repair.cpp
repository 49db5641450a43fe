// cad::tessellate on solids whose tessellation was refused before (issue 19): a shell with faces
// turned over, a face whose curve of an edge strays from the edge (BRepMesh gives that face no
// triangles), a cylinder side bounded by two circles and no seam (same); and the message for a
// face that cannot be triangulated at all.
#ifdef HEXDOM_WITH_CAD
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ShapeFix_Shell.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom_Circle.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Pln.hxx>

#include "cad_test_util.h"
#include "hexdom/polycube/boundary_graph.h"

using namespace hexdom;
using hexdom::test::write_part;

namespace {

/// `solid` rebuilt with the faces numbered in `turn` (1-based, FreeCAD's FaceN) turned over in
/// its shell: the B-rep's own orientations then disagree across their edges.
TopoDS_Shape with_turned_faces(const TopoDS_Shape& solid, std::set<int> turn) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(solid, TopAbs_FACE, faces);
  BRep_Builder b;
  TopoDS_Solid out;
  b.MakeSolid(out);
  for (TopExp_Explorer sx(solid, TopAbs_SHELL); sx.More(); sx.Next()) {
    TopoDS_Shell shell;
    b.MakeShell(shell);
    for (TopExp_Explorer fx(sx.Current(), TopAbs_FACE); fx.More(); fx.Next())
      b.Add(shell, turn.count(faces.FindIndex(fx.Current())) ? fx.Current().Reversed() : fx.Current());
    shell.Closed(true);
    b.Add(out, shell);
  }
  return out;
}

/// The box with a hole whose hole's bottom circle has, on the cylinder, a curve bent away from the
/// circle (by 3 in u and v at its middle): BRepMesh gives the cylinder no triangles.
TopoDS_Shape box_with_bent_pcurve(int& cylinder_face) {
  TopoDS_Shape s = test::make_box_with_hole();
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(s, TopAbs_FACE, faces);
  for (int f = 1; f <= faces.Extent(); ++f) {
    const TopoDS_Face face = TopoDS::Face(faces(f));
    if (BRep_Tool::Surface(face)->DynamicType() != STANDARD_TYPE(Geom_CylindricalSurface)) continue;
    cylinder_face = f;
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::IsClosed(e, face) || std::abs(BRep_Tool::Pnt(TopExp::FirstVertex(e)).Z()) > 1e-9) continue;
      double a, b;
      const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, a, b);
      Handle(TColgp_HArray1OfPnt2d) pts = new TColgp_HArray1OfPnt2d(1, 3);
      const gp_Pnt2d m = pc->Value(0.5 * (a + b));
      pts->SetValue(1, pc->Value(a));
      pts->SetValue(2, gp_Pnt2d(m.X() + 3, m.Y() + 3));
      pts->SetValue(3, pc->Value(b));
      Handle(TColStd_HArray1OfReal) prm = new TColStd_HArray1OfReal(1, 3);
      prm->SetValue(1, a), prm->SetValue(2, 0.5 * (a + b)), prm->SetValue(3, b);
      Geom2dAPI_Interpolate bent(pts, prm, false, 1e-9);
      bent.Perform();
      BRep_Builder().UpdateEdge(e, bent.Curve(), face, BRep_Tool::Tolerance(e));
      return s;
    }
  }
  ADD_FAILURE() << "no bottom circle on a cylinder";
  return s;
}

/// A cylinder (radius 5, height 12) whose side is bounded by its two circles only, no seam edge;
/// `same_way` makes both circles run the same way around it (no consistent side then).
TopoDS_Shape cylinder_without_seam(bool same_way = false) {
  BRep_Builder b;
  Handle(Geom_CylindricalSurface) surface = new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), 5.0);
  TopoDS_Edge c0 = BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 5.0));
  TopoDS_Edge c1 = BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(gp_Pnt(0, 0, 12), gp::DZ()), 5.0));
  TopoDS_Face side;
  b.MakeFace(side, surface, 1e-7);
  b.UpdateEdge(c0, new Geom2d_Line(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), side, 1e-7);
  b.UpdateEdge(c1, new Geom2d_Line(gp_Pnt2d(0, 12), gp_Dir2d(1, 0)), side, 1e-7);
  TopoDS_Wire w0, w1;
  b.MakeWire(w0), b.MakeWire(w1);
  b.Add(w0, c0);
  b.Add(w1, same_way ? c1 : c1.Reversed());
  b.Add(side, w0), b.Add(side, w1);
  TopoDS_Face bottom = BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), BRepBuilderAPI_MakeWire(c0).Wire());
  TopoDS_Face top = BRepBuilderAPI_MakeFace(gp_Pln(gp_Ax3(gp_Pnt(0, 0, 12), gp::DZ())), BRepBuilderAPI_MakeWire(c1).Wire());
  TopoDS_Shell shell;
  b.MakeShell(shell);
  b.Add(shell, side), b.Add(shell, bottom.Reversed()), b.Add(shell, top);
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, shell);
  return solid;
}

/// Box 10 x 8 x 6 whose top face has a slit from (5, 0, 6) to (5, 4, 6): one edge that the top
/// face uses twice, once each way, and no other face.
TopoDS_Shape box_with_slit() {
  std::map<char, TopoDS_Vertex> v;
  const std::map<char, gp_Pnt> at = {{'a', {0, 0, 0}}, {'b', {10, 0, 0}}, {'c', {10, 8, 0}}, {'d', {0, 8, 0}},
                                     {'A', {0, 0, 6}}, {'B', {10, 0, 6}}, {'C', {10, 8, 6}}, {'D', {0, 8, 6}},
                                     {'M', {5, 0, 6}}, {'T', {5, 4, 6}}};
  for (const auto& [n, p] : at) v[n] = BRepBuilderAPI_MakeVertex(p);
  std::map<std::string, TopoDS_Edge> e;
  for (std::string n : {"ab", "bc", "cd", "da", "AM", "MB", "BC", "CD", "DA", "aA", "bB", "cC", "dD", "MT"})
    e[n] = BRepBuilderAPI_MakeEdge(v[n[0]], v[n[1]]);
  BRep_Builder b;
  auto face = [&](const std::vector<TopoDS_Edge>& es, const gp_Pln* plane = nullptr) {
    TopoDS_Wire w;
    b.MakeWire(w);
    for (const auto& x : es) b.Add(w, x);
    w.Closed(true);
    return plane ? BRepBuilderAPI_MakeFace(*plane, w, true).Face() : BRepBuilderAPI_MakeFace(w, true).Face();
  };
  const gp_Pln top(gp_Pnt(0, 0, 6), gp::DZ());
  TopoDS_Shell shell;
  b.MakeShell(shell);
  b.Add(shell, face({e["ab"], e["bc"], e["cd"], e["da"]}));
  b.Add(shell, face({e["AM"], e["MT"], TopoDS::Edge(e["MT"].Reversed()), e["MB"], e["BC"], e["CD"], e["DA"]}, &top));
  b.Add(shell, face({e["ab"], e["bB"], e["MB"], e["AM"], e["aA"]}));
  b.Add(shell, face({e["bc"], e["cC"], e["BC"], e["bB"]}));
  b.Add(shell, face({e["cd"], e["dD"], e["CD"], e["cC"]}));
  b.Add(shell, face({e["da"], e["aA"], e["DA"], e["dD"]}));
  ShapeFix_Shell fix(shell);
  fix.FixFaceOrientation(shell);
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, fix.Shell());
  ShapeFix_Solid orient(solid);
  orient.Perform();
  return orient.Solid();
}

struct Outcome {
  mesh::SurfaceMesh surface;
  std::vector<std::string> warnings;
};

Outcome tessellate_logged(const cad::Shape& shape, double size) {
  Outcome o;
  cad::TessellateOptions opt;
  opt.size = size;
  opt.log = [&](int level, const std::string& m) {
    if (level > 0) o.warnings.push_back(m);
  };
  o.surface = cad::tessellate(shape, opt);
  return o;
}

bool logged(const Outcome& o, const std::string& what) {
  for (const auto& w : o.warnings)
    if (w.find(what) != std::string::npos) return true;
  return false;
}

/// Closed, 2-manifold, outward, enclosing `volume` within 1%, every face id 1..faces present; with
/// `on_faces`, every vertex on the B-rep and every triangle on its own face (its centroid within 0.1
/// size). (OCCT's projection trims a face by its pcurves: a bent one moves the face's border.)
void expect_good_surface(const cad::Shape& shape, const mesh::SurfaceMesh& s, double volume, int faces, double size,
                         bool on_faces = true) {
  EXPECT_NO_THROW(polycube::check_closed_manifold(s)) << shape.source();
  const double v = test::enclosed_volume(s);
  EXPECT_GT(v, 0) << shape.source() << ": the triangles face inward";
  EXPECT_NEAR(v, volume, 0.01 * volume) << shape.source();
  std::set<int> ids(s.patch.data(), s.patch.data() + s.patch.size());
  std::set<int> all;
  for (int f = 1; f <= faces; ++f) all.insert(f);
  EXPECT_EQ(ids, all) << shape.source();
  if (!on_faces) return;
  EXPECT_LT(cad::project_to_shape(shape, s.V).distance.maxCoeff(), 1e-6 * size * 30) << shape.source();
  for (int f = 1; f <= faces; ++f) {
    std::vector<int> tris;
    for (int t = 0; t < s.F.rows(); ++t)
      if (s.patch(t) == f) tris.push_back(t);
    Eigen::MatrixXd C(tris.size(), 3);
    for (size_t i = 0; i < tris.size(); ++i)
      C.row(i) = (s.V.row(s.F(tris[i], 0)) + s.V.row(s.F(tris[i], 1)) + s.V.row(s.F(tris[i], 2))) / 3.0;
    if (!tris.empty()) EXPECT_LT(cad::project_to_face(shape, f, C).distance.maxCoeff(), 0.1 * size) << "Face" << f;
  }
}

}  // namespace

TEST(TessellateRepair, FacesTurnedOverInTheShellAreTurnedBack) {
  // Before: "the B-rep's initial triangulation is not closed: edge (5, 6) is used twice in one
  // direction". OCCT's volume of such a shell is wrong too (320 for the 480 box), so the reference
  // is the intact solid's.
  struct Case {
    std::string name;
    TopoDS_Shape intact;
    std::set<int> turn;
  };
  for (const Case& c : {Case{"box_face3", test::make_box(), {3}}, Case{"box_faces123", test::make_box(), {1, 2, 3}},
                        Case{"hole_cylinder", test::make_box_with_hole(), {7}}}) {
    SCOPED_TRACE(c.name);
    cad::Shape shape = cad::read_shape(write_part(with_turned_faces(c.intact, c.turn), "turned_" + c.name));
    const double size = cad::shape_info(shape).box.diagonal().norm() / 30;
    const Outcome o = tessellate_logged(shape, size);
    expect_good_surface(shape, o.surface, test::brep_volume(c.intact), cad::shape_info(shape).faces, size);
    EXPECT_TRUE(logged(o, "turned over: its triangles ran against its neighbours'")) << c.name;
  }
  // The faces that were turned are named (Face3 alone: the other five outvote it).
  cad::Shape shape = cad::read_shape(write_part(with_turned_faces(test::make_box(), {3}), "turned_named"));
  const Outcome o = tessellate_logged(shape, 1.0);
  EXPECT_TRUE(logged(o, "Face3 turned over"));
  EXPECT_FALSE(logged(o, "Face1 turned over"));
}

TEST(TessellateRepair, FaceWithoutBrepMeshTrianglesIsTriangulatedFromItsEdges) {
  // Before: "BRepMesh could not triangulate Face7". The cylinder's curve of its bottom circle is
  // bent; hexdom lays the circle's nodes onto the cylinder by projection instead.
  int cylinder = 0;
  const TopoDS_Shape bent = box_with_bent_pcurve(cylinder);
  cad::Shape shape = cad::read_shape(write_part(bent, "bent_pcurve"));
  const Outcome o = tessellate_logged(shape, 1.0);
  expect_good_surface(shape, o.surface, test::brep_volume(test::make_box_with_hole()), 7, 1.0, false);
  EXPECT_TRUE(logged(o, "Face" + std::to_string(cylinder) + " triangulated by hexdom: BRepMesh could not triangulate it"));
  // Its triangles lie on the cylinder of radius 4 about (10, 10) and cover its area (2 pi 4 10).
  double area = 0;
  for (int t = 0; t < o.surface.F.rows(); ++t) {
    if (o.surface.patch(t) != cylinder) continue;
    const Eigen::Vector3d a = o.surface.V.row(o.surface.F(t, 0)), b = o.surface.V.row(o.surface.F(t, 1)),
                          c = o.surface.V.row(o.surface.F(t, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
    for (const Eigen::Vector3d& p : {a, b, c}) EXPECT_NEAR(std::hypot(p.x() - 10, p.y() - 10), 4.0, 1e-6);
  }
  EXPECT_NEAR(area, 2 * M_PI * 4 * 10, 0.01 * 2 * M_PI * 4 * 10);
}

TEST(TessellateRepair, PeriodicFaceWithoutSeamGetsOne) {
  // Before: "BRepMesh could not triangulate Face1". OCCT's volume of this solid is wrong (314 for
  // pi 25 12 = 942), the reference is the cylinder's.
  cad::Shape shape = cad::read_shape(write_part(cylinder_without_seam(), "cylinder_no_seam"));
  for (double size : {1.0, 3.0}) {
    SCOPED_TRACE(size);
    const Outcome o = tessellate_logged(shape, size);
    expect_good_surface(shape, o.surface, M_PI * 25 * 12, 3, size);
    EXPECT_TRUE(logged(o, "Face1 triangulated by hexdom"));
  }
}

TEST(TessellateRepair, FaceThatCannotBeTriangulatedIsNamedWithTheReason) {
  cad::Shape shape = cad::read_shape(write_part(cylinder_without_seam(true), "cylinder_no_seam_same_way"));
  try {
    cad::tessellate(shape);
    FAIL() << "no error";
  } catch (const MeshingError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("Face1 cannot be triangulated: its two wires run the same way around the periodic surface"),
              std::string::npos)
        << m;
  }
}

TEST(TessellateRepair, WiresWhoseEdgesDoNotMeetAreNamed) {
  // Every edge's range cut to [0.1, 0.9] of its curve: the edges no longer reach their vertices.
  // Before: "OpenCASCADE failed while tessellating: Standard_OutOfRange ...".
  TopoDS_Shape s = test::make_box_with_hole();
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  BRep_Builder b;
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edges(i));
    b.SameRange(e, false);
    b.SameParameter(e, false);
    b.Range(e, 0.1, 0.9, true);
  }
  cad::Shape shape = cad::read_shape(write_part(s, "trimmed_edges"));
  try {
    cad::tessellate(shape);
    FAIL() << "no error";
  } catch (const MeshingError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("cannot be triangulated: a wire's 4 edges do not join into one loop"), std::string::npos) << m;
    EXPECT_NE(m.find(": Face"), std::string::npos) << m;
  }
}

TEST(TessellateRepair, OwnTriangulationOfEveryFaceMeetsTheSameChecks) {
  // brepmesh_faces = false: every face goes the way a face that BRepMesh fails on goes. After the
  // remeshing the surface meets every check the BRepMesh start meets (test_cad's tessellate.cpp).
  const std::vector<std::pair<std::string, TopoDS_Shape (*)()>> parts = {
      {"box", test::make_box},       {"box_with_hole", test::make_box_with_hole}, {"l_bracket", test::make_l_bracket},
      {"cylinder", test::make_cylinder}, {"sphere", test::make_sphere},         {"cone", test::make_cone},
      {"torus", test::make_torus},   {"box_with_cavity", test::make_box_with_cavity},
      {"filleted_box", test::make_filleted_box}};
  for (const auto& [name, make] : parts) {
    SCOPED_TRACE(name);
    cad::Shape shape = cad::read_shape(write_part(make(), "own_" + name));
    cad::TessellateOptions opt;
    opt.size = cad::shape_info(shape).box.diagonal().norm() / 30;
    opt.brepmesh_faces = false;
    const mesh::SurfaceMesh s = cad::tessellate(shape, opt);
    test::check_tessellation(shape, s, opt.size, name == "torus" ? 0.008 : 0.005);
  }
}

TEST(TessellateRepair, OwnTriangulationOfTheSharedStepParts) {
  // The same on the nine shared STEP parts (industrial and test models: fillets, cones, spheres).
  const std::string first = test::data_path("cad/i01o_m1.step");
  HEXDOM_REQUIRE_DATA(first);
  for (const std::string name : {"i01o_m1.step", "i10o_simp.step", "i11o_s1.step", "n11o_limit_cycle.stp", "s09o_bridge.step",
                                 "s11o_cube_cyl.stp", "s12o_cube_rounded_1.stp", "s14o_cube_corner_sub_sphere.stp",
                                 "s15o_cylinder.stp"}) {
    SCOPED_TRACE(name);
    cad::Shape shape = cad::read_shape(test::data_path("cad/" + name));
    cad::TessellateOptions opt;
    opt.size = cad::shape_info(shape).box.diagonal().norm() / 30;
    opt.brepmesh_faces = false;
    cad::TessellateStats st;
    const mesh::SurfaceMesh s = cad::tessellate(shape, opt, &st);
    const auto r = test::check_tessellation(shape, s, opt.size);
    std::cout << "[ figures  ] " << name << " (own triangulation of every face): " << st.triangles
              << " triangles, min angle planar " << r.min_angle_planar << ", volume error " << 100 * r.volume_error << "%\n";
  }
}

TEST(TessellateRepair, SlitFaceKeepsBrepMeshTriangles) {
  // The slit's segments have a triangle on each side within the face: a proper patch, not repaired.
  cad::Shape shape = cad::read_shape(write_part(box_with_slit(), "slit"));
  const Outcome o = tessellate_logged(shape, 1.0);
  expect_good_surface(shape, o.surface, 480.0, 6, 1.0);
  EXPECT_FALSE(logged(o, "triangulated by hexdom"));
  EXPECT_FALSE(logged(o, "turned over"));
}

TEST(TessellateRepair, PartsThatTessellatedBeforeAreNotRepaired) {
  // The repairs change nothing where BRepMesh's triangles were fine: no warning about them.
  for (auto make : {test::make_box_with_hole, test::make_sphere, test::make_torus, test::make_filleted_box}) {
    cad::Shape shape = cad::read_shape(write_part(make(), "unrepaired"));
    const Outcome o = tessellate_logged(shape, cad::shape_info(shape).box.diagonal().norm() / 30);
    EXPECT_FALSE(logged(o, "turned over")) << shape.source();
    EXPECT_FALSE(logged(o, "triangulated by hexdom")) << shape.source();
  }
}
#endif
