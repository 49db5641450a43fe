#include "hexdom/cad/project.h"

#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "hexdom/cad/face_projector.h"
#include "hexdom/cad/shape_impl.h"
#include "hexdom/common/error.h"

namespace hexdom::cad {

namespace {

Projection make_result(Eigen::Index n) {
  Projection r;
  r.points.resize(n, 3);
  r.distance.resize(n);
  r.param.resize(n, 2);
  r.id.resize(n);
  return r;
}

void check_points(const Eigen::MatrixXd& P, const std::string& source) {
  if (P.cols() != 3) throw InputError(source, 0, "points to project must be an N x 3 array, got " + std::to_string(P.cols()) + " columns");
}

}  // namespace

bool nearest_on_curve(const Handle(Geom_Curve)& curve, double first, double last, const gp_Pnt& p, gp_Pnt& q,
                      double& t, double& d) {
  if (curve.IsNull()) return false;
  d = std::numeric_limits<double>::infinity();
  for (double end : {first, last}) {
    const gp_Pnt e = curve->Value(end);
    if (p.Distance(e) < d) d = p.Distance(e), q = e, t = end;
  }
  GeomAPI_ProjectPointOnCurve proj(p, curve, first, last);
  for (int i = 1; i <= proj.NbPoints(); ++i)
    if (proj.Distance(i) < d) d = proj.Distance(i), q = proj.Point(i), t = proj.Parameter(i);
  return true;
}

Projection project_to_face(const Shape& shape, int face_id, const Eigen::MatrixXd& P) {
  const Shape::Impl& s = shape.impl();
  check_points(P, s.source);
  if (face_id < 1 || face_id > s.faces.Extent())
    throw InputError(s.source, 0, "Face" + std::to_string(face_id) + " does not exist (the solid has " +
                                      std::to_string(s.faces.Extent()) + " faces)");
  Projection r = make_result(P.rows());
  try {
    FaceProjector fp(TopoDS::Face(s.faces(face_id)));
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      gp_Pnt q;
      gp_Pnt2d uv;
      double d;
      fp.nearest(gp_Pnt(P(i, 0), P(i, 1), P(i, 2)), q, d, uv);
      r.points.row(i) << q.X(), q.Y(), q.Z();
      r.distance(i) = d;
      r.param.row(i) << uv.X(), uv.Y();
      r.id(i) = face_id;
    }
  } catch (const Standard_Failure& e) {
    throw GeometryError(s.source + ": projecting onto Face" + std::to_string(face_id) + " failed: " + occt_message(e));
  }
  return r;
}

Projection project_to_edge(const Shape& shape, int edge_id, const Eigen::MatrixXd& P) {
  const Shape::Impl& s = shape.impl();
  check_points(P, s.source);
  if (edge_id < 1 || edge_id > s.edges.Extent())
    throw InputError(s.source, 0, "Edge" + std::to_string(edge_id) + " does not exist (the solid has " +
                                      std::to_string(s.edges.Extent()) + " edges)");
  const EdgeCurve e = edge_curve(TopoDS::Edge(s.edges(edge_id)));
  if (e.curve.IsNull()) throw GeometryError(s.source + ": Edge" + std::to_string(edge_id) + " has no 3D curve (degenerated)");
  Projection r = make_result(P.rows());
  try {
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      gp_Pnt q;
      double t = 0, d = 0;
      nearest_on_edge(e, gp_Pnt(P(i, 0), P(i, 1), P(i, 2)), q, t, d);
      r.points.row(i) << q.X(), q.Y(), q.Z();
      r.distance(i) = d;
      r.param.row(i) << t, 0;
      r.id(i) = edge_id;
    }
  } catch (const Standard_Failure& e) {
    throw GeometryError(s.source + ": projecting onto Edge" + std::to_string(edge_id) + " failed: " + occt_message(e));
  }
  return r;
}

Eigen::MatrixXd edge_points(const Shape& shape, int edge_id, double spacing) {
  const Shape::Impl& s = shape.impl();
  if (edge_id < 1 || edge_id > s.edges.Extent())
    throw InputError(s.source, 0, "Edge" + std::to_string(edge_id) + " does not exist (the solid has " +
                                      std::to_string(s.edges.Extent()) + " edges)");
  if (!(spacing > 0)) throw InputError("edge_points: the spacing must be positive");
  const EdgeCurve e = edge_curve(TopoDS::Edge(s.edges(edge_id)));
  if (e.curve.IsNull()) throw GeometryError(s.source + ": Edge" + std::to_string(edge_id) + " has no 3D curve (degenerated)");
  try {
    // The length from a fine polygon, then points evenly in the parameter, 4 per spacing.
    auto at = [&](double u) {
      const gp_Pnt p = e.curve->Value(u);
      return Eigen::RowVector3d(p.X(), p.Y(), p.Z());
    };
    double length = 0;
    const int probe = 256;
    for (int i = 0; i < probe; ++i)
      length += (at(e.first + (e.last - e.first) * (i + 1) / probe) - at(e.first + (e.last - e.first) * i / probe)).norm();
    const int n = static_cast<int>(std::min(1e5 - 1, std::max(1.0, std::ceil(4 * length / spacing))));
    Eigen::MatrixXd P(n + 1, 3);
    for (int i = 0; i <= n; ++i) P.row(i) = at(e.first + (e.last - e.first) * i / n);
    return P;
  } catch (const Standard_Failure& f) {
    throw GeometryError(s.source + ": sampling Edge" + std::to_string(edge_id) + " failed: " + occt_message(f));
  }
}

Projection project_to_shape(const Shape& shape, const Eigen::MatrixXd& P) {
  const Shape::Impl& s = shape.impl();
  check_points(P, s.source);
  Projection r = make_result(P.rows());
  try {
    std::vector<std::unique_ptr<FaceProjector>> faces;
    for (int f = 1; f <= s.faces.Extent(); ++f) faces.push_back(std::make_unique<FaceProjector>(TopoDS::Face(s.faces(f))));
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const gp_Pnt p(P(i, 0), P(i, 1), P(i, 2));
      double best = std::numeric_limits<double>::infinity();
      for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
        if (faces[f]->lower_bound(p) >= best) continue;
        gp_Pnt q;
        gp_Pnt2d uv;
        double d;
        faces[f]->nearest(p, q, d, uv);
        if (d < best) {
          best = d;
          r.points.row(i) << q.X(), q.Y(), q.Z();
          r.distance(i) = d;
          r.param.row(i) << uv.X(), uv.Y();
          r.id(i) = f + 1;
        }
      }
    }
  } catch (const Standard_Failure& e) {
    throw GeometryError(s.source + ": projecting onto the solid failed: " + occt_message(e));
  }
  return r;
}

}  // namespace hexdom::cad
