// hexdom_cad built without OpenCASCADE: every entry point exists and says why it cannot work.
#ifndef HEXDOM_WITH_CAD
#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/tessellate.h"
#include "test_common.h"

using namespace hexdom;

namespace {
template <class F>
void expect_no_occt(F f) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("built without OpenCASCADE: cannot"), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(WithoutOpencascade, EveryEntryPointSaysSo) {
  EXPECT_FALSE(cad::has_opencascade());
  expect_no_occt([] { cad::read_shape("part.step"); });
  expect_no_occt([] { cad::read_brep_string("CASCADE Topology V1\n"); });
  expect_no_occt([] { cad::tessellate(cad::Shape()); });
  expect_no_occt([] { cad::shape_info(cad::Shape()); });
  expect_no_occt([] { cad::project_to_face(cad::Shape(), 1, Eigen::MatrixXd::Zero(1, 3)); });
  EXPECT_THROW(cad::read_shape("part.step"), InputError);
}
#endif
