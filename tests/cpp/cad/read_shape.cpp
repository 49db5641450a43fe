// cad::read_shape / read_brep_string: formats, solid selection and every error path.
#ifdef HEXDOM_WITH_CAD
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Builder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>

#include <fstream>

#include "cad_test_util.h"

using namespace hexdom;
using hexdom::test::write_part;

namespace {

std::string write_step(const TopoDS_Shape& shape, const std::string& name) {
  const std::string path = test::temp_path(name + ".step");
  STEPControl_Writer w;
  w.Transfer(shape, STEPControl_AsIs);
  w.Write(path.c_str());
  return path;
}

/// Expects `f` to throw E with a message containing every one of `parts`.
template <class E, class F>
void expect_error(F f, std::initializer_list<std::string> parts) {
  try {
    f();
    FAIL() << "no error";
  } catch (const E& e) {
    for (const auto& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what() << " lacks " << p;
  }
}

/// The five faces of a box without its top: an open shell.
TopoDS_Shape open_box_shell() {
  BRepBuilderAPI_Sewing sewing;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(test::make_box(), TopAbs_FACE, faces);
  for (int i = 1; i <= 5; ++i) sewing.Add(faces(i));
  sewing.Perform();
  TopExp_Explorer ex(sewing.SewedShape(), TopAbs_SHELL);
  return ex.Current();
}

}  // namespace

TEST(ReadShape, BrepFileGivesTheSolid) {
  cad::Shape s = cad::read_shape(write_part(test::make_box_with_hole(), "read_hole"));
  EXPECT_NEAR(cad::shape_volume(s), test::brep_volume(test::make_box_with_hole()), 1e-9);
  EXPECT_NEAR(cad::shape_volume(s), 20 * 20 * 10 - M_PI * 16 * 10, 1e-6);
  EXPECT_EQ(s.source(), test::temp_path("read_hole.brep"));
}

TEST(ReadShape, StepRoundTrip) {
  cad::Shape s = cad::read_shape(write_step(test::make_l_bracket(), "lbracket"));
  EXPECT_NEAR(cad::shape_volume(s), (30 * 6 + 6 * 14) * 15.0, 1e-6);
  EXPECT_EQ(cad::shape_info(s).faces, 8);
}

TEST(ReadShape, StpExtensionAndUpperCase) {
  const std::string step = write_step(test::make_box(), "box_case");
  const std::string upper = test::temp_path("BOX_CASE.STP");
  std::filesystem::copy_file(step, upper, std::filesystem::copy_options::overwrite_existing);
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(upper)), 480, 1e-6);
}

TEST(ReadShape, IgesFacesAreSewnIntoASolid) {
  IGESControl_Controller::Init();
  Interface_Static::SetIVal("write.iges.brep.mode", 0);  // trimmed surfaces: no solid in the file
  IGESControl_Writer w("MM", 0);
  w.AddShape(test::make_cylinder());
  w.ComputeModel();
  const std::string path = test::temp_path("cylinder.igs");
  ASSERT_TRUE(w.Write(path.c_str()));
  std::vector<std::string> log;
  cad::ReadOptions ro;
  ro.log = [&](int, const std::string& m) { log.push_back(m); };
  cad::Shape s = cad::read_shape(path, ro);
  EXPECT_NEAR(cad::shape_volume(s), M_PI * 25 * 12, 1e-3);
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log[0].find("sewed"), std::string::npos) << log[0];
}

TEST(ReadShape, MissingFileIsAnInputErrorNamingThePath) {
  const std::string path = test::temp_path("no_such_part.step");
  expect_error<InputError>([&] { cad::read_shape(path); }, {path, "cannot open"});
}

TEST(ReadShape, CorruptStepIsAnInputErrorNamingTheLine) {
  const std::string path = test::temp_path("corrupt.step");
  test::write_text(path, "ISO-10303-21;\nHEADER;\nFILE_NAME('x');\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('',(0.,0.,0.);\n"
                         "ENDSEC;\nEND-ISO-10303-21;\n");
  try {
    cad::read_shape(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_EQ(e.line(), 6) << e.what();
    EXPECT_NE(std::string(e.what()).find(path + ":6: Incorrect syntax"), std::string::npos) << e.what();
  }
  test::write_text(path, "");
  expect_error<InputError>([&] { cad::read_shape(path); }, {path});
}

TEST(ReadShape, TruncatedStepIsAClearError) {
  const std::string good = write_step(test::make_box_with_hole(), "to_truncate");
  std::string text;
  {
    std::ifstream in(good);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string path = test::temp_path("truncated.step");
  test::write_text(path, text.substr(0, text.size() / 2));
  try {
    cad::read_shape(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(ReadShape, UnknownExtensionIsAnInputError) {
  const std::string path = test::temp_path("part.sldprt");
  test::write_text(path, "x");
  expect_error<InputError>([&] { cad::read_shape(path); }, {path, ".sldprt", ".step"});
}

TEST(ReadShape, FacesOnlyIsAGeometryError) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(test::make_box(), TopAbs_FACE, faces);
  const std::string path = write_part(faces(1), "one_face");
  expect_error<GeometryError>([&] { cad::read_shape(path); }, {path, "no solid", "1 face"});
}

TEST(ReadShape, ShellIsAGeometryError) {
  const std::string path = write_part(open_box_shell(), "open_shell");
  expect_error<GeometryError>([&] { cad::read_shape(path); }, {path, "no solid", "1 shell", "0 closed"});
}

TEST(ReadShape, OpenSolidIsAGeometryErrorNamingTheEdge) {
  BRepBuilderAPI_MakeSolid make(TopoDS::Shell(open_box_shell()));
  const std::string path = write_part(make.Solid(), "open_solid");
  expect_error<GeometryError>([&] { cad::read_shape(path); }, {path, "solid 1 is open", "Edge", "bounds only Face", "4 free edges"});
}

TEST(ReadShape, WireframeIsAGeometryError) {
  const std::string path = write_part(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0)).Edge(), "edge");
  expect_error<GeometryError>([&] { cad::read_shape(path); }, {path, "no solid", "1 edge"});
}

TEST(ReadShape, MultiSolidPicksByIndex) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, test::make_box());
  b.Add(c, test::make_cylinder());
  const std::string path = write_part(c, "two_solids");
  cad::ReadOptions ro;
  ro.solid = 1;
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(path, ro)), 480, 1e-9);
  ro.solid = 2;
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(path, ro)), M_PI * 25 * 12, 1e-6);
  ro.solid = 3;
  expect_error<InputError>([&] { cad::read_shape(path, ro); }, {path, "solid 3", "2 solids"});
  // No choice: the first, with a warning.
  std::vector<std::string> log;
  ro.solid = 0;
  ro.log = [&](int level, const std::string& m) {
    EXPECT_EQ(level, 1);
    log.push_back(m);
  };
  EXPECT_NEAR(cad::shape_volume(cad::read_shape(path, ro)), 480, 1e-9);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("2 solids"), std::string::npos) << log[0];
}

TEST(ReadShape, FaceIdsNumberTheChosenSolid) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, test::make_box());
  b.Add(c, test::make_l_bracket());
  cad::ReadOptions ro;
  ro.solid = 2;
  cad::Shape s = cad::read_shape(write_part(c, "box_and_bracket"), ro);
  EXPECT_EQ(cad::shape_info(s).faces, 8);
  EXPECT_EQ(cad::tessellate(s).patch.maxCoeff(), 8);
}

TEST(ReadBrepString, RoundTrip) {
  cad::Shape s = cad::read_shape(write_part(test::make_torus(), "torus_string"));
  const std::string text = cad::write_brep_string(s);
  EXPECT_TRUE(cad::is_brep_string(text));
  EXPECT_FALSE(cad::is_brep_string("part.brep"));
  cad::Shape t = cad::read_brep_string(text);
  EXPECT_EQ(t.source(), "<BREP string>");
  EXPECT_NEAR(cad::shape_volume(t), cad::shape_volume(s), 1e-9 * cad::shape_volume(s));
  EXPECT_NEAR(cad::shape_volume(cad::read_shape_or_brep(text)), cad::shape_volume(s), 1e-6);
}

TEST(ReadBrepString, GarbageIsAnInputError) {
  expect_error<InputError>([] { cad::read_brep_string("not a shape"); }, {"<BREP string>"});
  expect_error<InputError>([] { cad::read_brep_string("CASCADE Topology V1, (c) Matra-Datavision\nLocations 3\n1\n"); },
                           {"<BREP string>"});
}

TEST(ReadShape, InsideOutSolidIsTurnedOver) {
  std::vector<std::string> log;
  cad::ReadOptions ro;
  ro.log = [&](int, const std::string& m) { log.push_back(m); };
  cad::Shape s = cad::read_shape(write_part(test::make_box().Reversed(), "box_reversed"), ro);
  EXPECT_NEAR(cad::shape_volume(s), 480, 1e-9);
  ASSERT_EQ(log.size(), 1u);
}
#endif
