// Nearest points on one trimmed face or one edge of a B-rep, kept between queries. Internal to
// hexdom_cad (it includes OCCT): project.cpp, snap.cpp and second_order.cpp use it.
#pragma once

#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Extrema_LocateExtPC.hxx>
#include <Extrema_POnCurv.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "hexdom/cad/shape_impl.h"

namespace hexdom::cad {

struct EdgeCurve {
  Handle(Geom_Curve) curve;
  double first = 0, last = 0;
  Bnd_Box box;  ///< holds the whole edge (from its curve, not its polygon), with its tolerance

  /// No point of the edge is nearer to p than this.
  double lower_bound(const gp_Pnt& p) const { return box.IsVoid() ? 0.0 : box.Distance(Bnd_Box(p.XYZ(), p.XYZ())); }
};

/// Nearest point of one edge's 3D curve within its range (ends included).
inline bool nearest_on_edge(const EdgeCurve& e, const gp_Pnt& p, gp_Pnt& q, double& t, double& d) {
  return nearest_on_curve(e.curve, e.first, e.last, p, q, t, d);
}

/// nearest_on_edge for a point near one whose nearest point had parameter `start` (a node sliding
/// along the edge): the local minimum of the distance from there (Newton's method) when it lies in
/// the range and no end of the edge is nearer; otherwise the whole edge is searched.
inline bool nearest_on_edge_from(const EdgeCurve& e, const gp_Pnt& p, double start, gp_Pnt& q, double& t, double& d) {
  if (e.curve.IsNull()) return false;
  const GeomAdaptor_Curve c(e.curve, e.first, e.last);
  const double tol = 1e-9 * std::max(1.0, std::abs(e.last - e.first));
  Extrema_LocateExtPC local(p, c, std::clamp(start, e.first, e.last), tol);
  if (local.IsDone() && local.IsMin()) {
    const Extrema_POnCurv& x = local.Point();
    const double u = x.Parameter(), dist = std::sqrt(local.SquareDistance());
    const bool inside = u >= e.first && u <= e.last;
    if (inside && dist <= p.Distance(e.curve->Value(e.first)) && dist <= p.Distance(e.curve->Value(e.last))) {
      q = x.Value();
      t = u;
      d = dist;
      return true;
    }
  }
  return nearest_on_edge(e, p, q, t, d);
}

inline EdgeCurve edge_curve(const TopoDS_Edge& edge) {
  EdgeCurve e;
  if (!BRep_Tool::Degenerated(edge)) {
    e.curve = BRep_Tool::Curve(edge, e.first, e.last);
    BRepBndLib::Add(edge, e.box, false);
  }
  return e;
}

/// Nearest point of one trimmed face: the nearest of the surface's extrema that lie inside the
/// face and of the nearest points of its boundary edges. One projector serves one thread.
class FaceProjector {
 public:
  explicit FaceProjector(const TopoDS_Face& face) : face_(face) {
    surface_ = BRep_Tool::Surface(face);
    analysis_ = new ShapeAnalysis_Surface(surface_);
    BRepTools::UVBounds(face, u0_, u1_, v0_, v1_);
    tol_ = std::max(BRep_Tool::Tolerance(face), 1e-9);
    classifier_ = std::make_unique<BRepTopAdaptor_FClass2d>(face, tol_);
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) edges_.push_back(edge_curve(TopoDS::Edge(ex.Current())));
    BRepBndLib::Add(face, box_);
    // The extremum search samples the surface once here, not on every query.
    proj_.Init(surface_, u0_, u1_, v0_, v1_);
  }

  /// Lower bound of the distance from p to the face.
  double lower_bound(const gp_Pnt& p) const { return box_.IsVoid() ? 0.0 : box_.Distance(Bnd_Box(p.XYZ(), p.XYZ())); }

  void nearest(const gp_Pnt& p, gp_Pnt& best, double& best_d, gp_Pnt2d& best_uv) const {
    best_d = std::numeric_limits<double>::infinity();
    GeomAPI_ProjectPointOnSurf& proj = proj_;
    proj.Perform(p);
    for (int i = 1; i <= proj.NbPoints(); ++i) {
      double u, v;
      proj.Parameters(i, u, v);
      if (classifier_->Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) continue;
      const double d = proj.Distance(i);
      if (d < best_d) best_d = d, best = proj.Point(i), best_uv = gp_Pnt2d(u, v);
    }
    // The boundary edges, nearest box first; an edge whose box is no nearer than the best point so
    // far cannot hold a nearer one (most queries lie inside the face, away from its edges).
    by_box_.clear();
    for (size_t i = 0; i < edges_.size(); ++i) by_box_.emplace_back(edges_[i].lower_bound(p), static_cast<int>(i));
    std::sort(by_box_.begin(), by_box_.end());
    bool on_edge = false;
    for (const auto& [bound, i] : by_box_) {
      if (bound >= best_d) break;
      gp_Pnt q;
      double t, d;
      if (nearest_on_edge(edges_[i], p, q, t, d) && d < best_d) best_d = d, best = q, on_edge = true;
    }
    if (on_edge) best_uv = analysis_->ValueOfUV(best, tol_);
  }

  /// A local search for the nearest point from parameters `start` (Newton's method on the surface):
  /// true with its point, distance and parameters when it ends inside the face, false otherwise. It
  /// finds the nearest point of the face when `start` is near it (a node sliding on the face, or the
  /// previous of a row of close nodes); the caller judges that.
  bool nearest_local(const gp_Pnt& p, const gp_Pnt2d& start, gp_Pnt& best, double& best_d, gp_Pnt2d& best_uv) const {
    const gp_Pnt2d uv = analysis_->NextValueOfUV(start, p, tol_);
    if (classifier_->Perform(uv) != TopAbs_IN) return false;
    best = surface_->Value(uv.X(), uv.Y());
    best_d = best.Distance(p);
    best_uv = uv;
    return true;
  }

  /// nearest() for a point near one whose nearest point had parameters `start` (a node sliding on
  /// the face): nearest_local from there when it ends inside the face; otherwise nearest().
  void nearest_from(const gp_Pnt& p, const gp_Pnt2d& start, gp_Pnt& best, double& best_d, gp_Pnt2d& best_uv) const {
    if (!nearest_local(p, start, best, best_d, best_uv)) nearest(p, best, best_d, best_uv);
  }

 private:
  TopoDS_Face face_;
  Handle(Geom_Surface) surface_;
  Handle(ShapeAnalysis_Surface) analysis_;
  std::unique_ptr<BRepTopAdaptor_FClass2d> classifier_;
  std::vector<EdgeCurve> edges_;
  mutable std::vector<std::pair<double, int>> by_box_;  // nearest()'s scratch: edges by box distance
  Bnd_Box box_;
  mutable GeomAPI_ProjectPointOnSurf proj_;  // not for use from two threads at once
  double u0_ = 0, u1_ = 0, v0_ = 0, v1_ = 0, tol_ = 1e-7;
};

/// The face and edge projectors of one shape, built on first use and kept for every query of a snap
/// (one thread): snap.cpp, second_order.cpp.
class Projectors {
 public:
  explicit Projectors(const Shape::Impl& s)
      : s_(s), faces_(s.faces.Extent() + 1), curves_(s.edges.Extent() + 1), have_curve_(s.edges.Extent() + 1, 0) {}
  FaceProjector& face(int id) {
    if (!faces_[id]) faces_[id] = std::make_unique<FaceProjector>(TopoDS::Face(s_.faces(id)));
    return *faces_[id];
  }
  const EdgeCurve& curve(int id) {
    if (!have_curve_[id]) curves_[id] = edge_curve(TopoDS::Edge(s_.edges(id))), have_curve_[id] = 1;
    return curves_[id];
  }

 private:
  const Shape::Impl& s_;
  std::vector<std::unique_ptr<FaceProjector>> faces_;
  std::vector<EdgeCurve> curves_;
  std::vector<char> have_curve_;
};

}  // namespace hexdom::cad
