// hexdom_cad without OpenCASCADE: the same functions, each throwing "built without OpenCASCADE:
// cannot ...", so that callers never test the build flag (as Gmsh's OCC_Internals stub does).
#include "hexdom/cad/project.h"
#include "hexdom/cad/read_shape.h"
#include "hexdom/cad/second_order.h"
#include "hexdom/cad/shape.h"
#include "hexdom/cad/snap.h"
#include "hexdom/cad/tessellate.h"
#include "hexdom/common/error.h"

namespace hexdom::cad {

namespace {
[[noreturn]] void no_occt(const std::string& what) { throw Error("built without OpenCASCADE: cannot " + what); }
[[noreturn]] void no_occt_input(const std::string& source, const std::string& what) {
  throw InputError(source, 0, "built without OpenCASCADE: cannot " + what);
}
}  // namespace

struct Shape::Impl {};

const Shape::Impl& Shape::impl() const { no_occt("use CAD shapes"); }
const std::string& Shape::source() const {
  static const std::string none = "<empty shape>";
  return none;
}

std::string surface_type_name(SurfaceType type) {
  static const char* names[] = {"plane", "cylinder", "cone", "sphere", "torus", "bspline", "bezier", "revolution", "extrusion", "offset", "other"};
  return names[static_cast<int>(type)];
}

bool has_opencascade() { return false; }
ShapeInfo shape_info(const Shape&) { no_occt("inspect CAD shapes"); }
double shape_volume(const Shape&) { no_occt("compute the volume of a CAD shape"); }
std::string write_brep_string(const Shape&) { no_occt("write BREP"); }
void write_brep(const Shape&, const std::string& path) { no_occt_input(path, "write BREP files"); }

Shape read_shape(const std::string& path, const ReadOptions&) { no_occt_input(path, "read CAD files (STEP, IGES, BREP)"); }
Shape read_brep_string(const std::string&, const ReadOptions&) { no_occt_input("<BREP string>", "read BREP"); }
bool is_brep_string(const std::string& text) { return text.find("CASCADE Topology") != std::string::npos; }
Shape read_shape_or_brep(const std::string& source, const ReadOptions& options) {
  return is_brep_string(source) ? read_brep_string(source, options) : read_shape(source, options);
}
std::vector<Shape> read_solids(const std::string& source, const ReadOptions& options) {
  return {read_shape_or_brep(source, options)};
}
std::vector<int> source_numbers(const Shape&, int) { no_occt("number CAD faces"); }
std::vector<std::array<int, 2>> touching_solids(const std::vector<Shape>&, double) { no_occt("compare CAD solids"); }

mesh::SurfaceMesh tessellate(const Shape&, const TessellateOptions&, TessellateStats*) { no_occt("tessellate CAD shapes"); }
TessellateStats tessellation_stats(const Shape&, const mesh::SurfaceMesh&) { no_occt("tessellate CAD shapes"); }

Projection project_to_face(const Shape&, int, const Eigen::MatrixXd&) { no_occt("project onto CAD faces"); }
Projection project_to_edge(const Shape&, int, const Eigen::MatrixXd&) { no_occt("project onto CAD edges"); }
Eigen::MatrixXd edge_points(const Shape&, int, double) { no_occt("sample CAD edges"); }
Projection project_to_shape(const Shape&, const Eigen::MatrixXd&) { no_occt("project onto CAD shapes"); }

SecondOrderResult second_order_on_brep(const Shape&, const mesh::Mesh&, const std::vector<SnapKind>&, const std::vector<int>&,
                                       const mesh::SurfaceMesh&, const optimize::CurveOptions&) {
  no_occt("put mid-edge nodes on a B-rep");
}
SnapResult snap_to_brep(const Shape&, const mesh::Mesh&, const mesh::SurfaceMesh&, const SnapOptions&) {
  no_occt("snap a mesh to the B-rep");
}

}  // namespace hexdom::cad
