#include "hexdom/cad/shape.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopoDS.hxx>

#include <sstream>

#include "hexdom/cad/shape_impl.h"
#include "hexdom/common/error.h"
#include "hexdom/io/text.h"

namespace hexdom::cad {

namespace {
SurfaceType surface_type(GeomAbs_SurfaceType t) {
  switch (t) {
    case GeomAbs_Plane: return SurfaceType::Plane;
    case GeomAbs_Cylinder: return SurfaceType::Cylinder;
    case GeomAbs_Cone: return SurfaceType::Cone;
    case GeomAbs_Sphere: return SurfaceType::Sphere;
    case GeomAbs_Torus: return SurfaceType::Torus;
    case GeomAbs_BSplineSurface: return SurfaceType::BSpline;
    case GeomAbs_BezierSurface: return SurfaceType::Bezier;
    case GeomAbs_SurfaceOfRevolution: return SurfaceType::Revolution;
    case GeomAbs_SurfaceOfExtrusion: return SurfaceType::Extrusion;
    case GeomAbs_OffsetSurface: return SurfaceType::Offset;
    default: return SurfaceType::Other;
  }
}
}  // namespace

std::string surface_type_name(SurfaceType type) {
  switch (type) {
    case SurfaceType::Plane: return "plane";
    case SurfaceType::Cylinder: return "cylinder";
    case SurfaceType::Cone: return "cone";
    case SurfaceType::Sphere: return "sphere";
    case SurfaceType::Torus: return "torus";
    case SurfaceType::BSpline: return "bspline";
    case SurfaceType::Bezier: return "bezier";
    case SurfaceType::Revolution: return "revolution";
    case SurfaceType::Extrusion: return "extrusion";
    case SurfaceType::Offset: return "offset";
    default: return "other";
  }
}

const Shape::Impl& Shape::impl() const {
  if (!impl_) throw GeometryError("empty CAD shape");
  return *impl_;
}

const std::string& Shape::source() const {
  static const std::string none = "<empty shape>";
  return impl_ ? impl_->source : none;
}

bool has_opencascade() { return true; }

std::string occt_message(const Standard_Failure& e) {
  std::string text = e.DynamicType()->Name();
  const char* msg = e.GetMessageString();
  if (msg && *msg) text += std::string(": ") + msg;
  return text;
}

Shape make_shape(const TopoDS_Shape& solid, const std::string& source) {
  auto impl = std::make_shared<Shape::Impl>();
  impl->shape = solid;
  impl->source = source;
  TopExp::MapShapes(solid, TopAbs_FACE, impl->faces);
  TopExp::MapShapes(solid, TopAbs_EDGE, impl->edges);
  TopExp::MapShapes(solid, TopAbs_VERTEX, impl->vertices);
  return Shape(std::move(impl));
}

std::vector<int> source_numbers(const Shape& shape, int dim) {
  const auto& s = shape.impl();
  if (dim < 0 || dim > 2) throw std::invalid_argument("source_numbers: dim " + std::to_string(dim) + " is not 0, 1 or 2");
  const std::vector<int>& given = dim == 2 ? s.source_faces : dim == 1 ? s.source_edges : s.source_vertices;
  if (!given.empty()) return given;
  std::vector<int> out((dim == 2 ? s.faces : dim == 1 ? s.edges : s.vertices).Extent());
  for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<int>(i) + 1;
  return out;
}

ShapeInfo shape_info(const Shape& shape) {
  const auto& s = shape.impl();
  ShapeInfo info;
  info.faces = s.faces.Extent();
  info.edges = s.edges.Extent();
  info.vertices = s.vertices.Extent();
  TopTools_IndexedMapOfShape shells;
  TopExp::MapShapes(s.shape, TopAbs_SHELL, shells);
  info.shells = shells.Extent();
  try {
    GProp_GProps vp, sp;
    BRepGProp::VolumeProperties(s.shape, vp);
    BRepGProp::SurfaceProperties(s.shape, sp);
    info.volume = vp.Mass();
    info.area = sp.Mass();
    Bnd_Box b;
    BRepBndLib::AddOptimal(s.shape, b, false, false);
    if (!b.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      b.Get(x0, y0, z0, x1, y1, z1);
      info.box = Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
    }
    info.vertex_points.resize(s.vertices.Extent(), 3);
    for (int i = 1; i <= s.vertices.Extent(); ++i) {
      const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(s.vertices(i)));
      info.vertex_points.row(i - 1) << p.X(), p.Y(), p.Z();
    }
    for (int i = 1; i <= s.faces.Extent(); ++i)
      info.face_types.push_back(surface_type(BRepAdaptor_Surface(TopoDS::Face(s.faces(i)), false).GetType()));
  } catch (const Standard_Failure& e) {
    throw GeometryError(s.source + ": " + occt_message(e));
  }
  return info;
}

double shape_volume(const Shape& shape) {
  const auto& s = shape.impl();
  GProp_GProps vp;
  BRepGProp::VolumeProperties(s.shape, vp);
  return vp.Mass();
}

std::string write_brep_string(const Shape& shape) {
  std::ostringstream out;
  BRepTools::Write(shape.impl().shape, out);
  return out.str();
}

void write_brep(const Shape& shape, const std::string& path) {
  const std::string text = write_brep_string(shape);
  io::write_atomically(path, false, [&](std::ostream& o) { o << text; });
}

}  // namespace hexdom::cad
