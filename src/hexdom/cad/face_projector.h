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
#include <Geom2d_Curve.hxx>
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

/// BRepTopAdaptor_FClass2d (IN / ON / OUT of a face's parameter domain, a polygon test over its
/// boundary's discretisation) with a grid of 128 x 128 cells over the face's parameter bounds,
/// made at the first query: cells within two cells of a sample of a boundary edge's curve on the
/// face (samples at most a quarter of a cell apart) always ask the classifier; any other cell holds
/// the state of its centre, asked once (IN or OUT; otherwise the cell asks), and answers for every
/// point in it. Such a cell lies inside one connected piece of the domain's interior or exterior
/// (no boundary curve crosses it, nor the classifier's polygon, which stays within its deflection
/// of the curves), so its answers are the classifier's. Points outside the bounds (a periodic
/// parameter), and every point of a face whose edges lack a curve on it or need more than 65,536
/// samples, ask the classifier. Not for use from two threads at once.
class FaceClassifier {
 public:
  FaceClassifier(const TopoDS_Face& face, double tol, double u0, double u1, double v0, double v1)
      : face_(face), classifier_(face, tol), u0_(u0), v0_(v0), du_((u1 - u0) / kCells), dv_((v1 - v0) / kCells) {}

  TopAbs_State Perform(const gp_Pnt2d& uv) const {
    if (state_.empty()) build();
    const double fu = (uv.X() - u0_) / du_, fv = (uv.Y() - v0_) / dv_;
    if (!(fu >= 0 && fu < kCells && fv >= 0 && fv < kCells)) return classifier_.Perform(uv);
    const int i = static_cast<int>(fu), j = static_cast<int>(fv);
    signed char& s = state_[j * kCells + i];
    if (s == kNearBoundary) return classifier_.Perform(uv);
    if (s == kUnknown) {
      const TopAbs_State centre = classifier_.Perform(gp_Pnt2d(u0_ + (i + 0.5) * du_, v0_ + (j + 0.5) * dv_));
      s = centre == TopAbs_IN || centre == TopAbs_OUT ? static_cast<signed char>(centre) : kNearBoundary;
      if (s == kNearBoundary) return classifier_.Perform(uv);
    }
    ++from_grid_;
    return static_cast<TopAbs_State>(s);
  }

  /// Queries answered by a grid cell so far (the rest asked the classifier).
  long from_grid() const { return from_grid_; }

 private:
  static constexpr int kCells = 128;
  static constexpr signed char kUnknown = -1, kNearBoundary = -2;

  void build() const {
    state_.assign(kCells * kCells, kUnknown);
    if (!(du_ > 0 && dv_ > 0)) return mark_all();
    auto mark = [&](double u, double v) {
      const int ci = static_cast<int>(std::floor((u - u0_) / du_)), cj = static_cast<int>(std::floor((v - v0_) / dv_));
      for (int j = std::max(cj - 2, 0); j <= std::min(cj + 2, kCells - 1); ++j)
        for (int i = std::max(ci - 2, 0); i <= std::min(ci + 2, kCells - 1); ++i) state_[j * kCells + i] = kNearBoundary;
    };
    for (TopExp_Explorer ex(face_, TopAbs_EDGE); ex.More(); ex.Next()) {
      double first = 0, last = 0;
      const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face_, first, last);
      if (c.IsNull() || !std::isfinite(first) || !std::isfinite(last)) return mark_all();
      // Samples a quarter of a cell apart at most: the count doubled until the largest step is.
      std::vector<gp_Pnt2d> samples;
      for (int n = 256;; n *= 2) {
        if (n > (1 << 16)) return mark_all();
        samples.assign(1, c->Value(first));
        bool fine = true;
        for (int k = 1; k <= n && fine; ++k) {
          samples.push_back(c->Value(first + (last - first) * k / n));
          const gp_Pnt2d &a = samples[k - 1], &b = samples[k];
          fine = std::abs(b.X() - a.X()) <= 0.25 * du_ && std::abs(b.Y() - a.Y()) <= 0.25 * dv_;
        }
        if (fine) break;
      }
      for (const gp_Pnt2d& q : samples) mark(q.X(), q.Y());
    }
  }
  void mark_all() const { std::fill(state_.begin(), state_.end(), kNearBoundary); }

  TopoDS_Face face_;
  BRepTopAdaptor_FClass2d classifier_;
  double u0_, v0_, du_, dv_;
  mutable std::vector<signed char> state_;  // per cell: a TopAbs_State, kUnknown or kNearBoundary
  mutable long from_grid_ = 0;
};

/// Nearest point of one trimmed face: the nearest of the surface's extrema that lie inside the
/// face and of the nearest points of its boundary edges. One projector serves one thread.
class FaceProjector {
 public:
  explicit FaceProjector(const TopoDS_Face& face) : face_(face) {
    surface_ = BRep_Tool::Surface(face);
    analysis_ = new ShapeAnalysis_Surface(surface_);
    BRepTools::UVBounds(face, u0_, u1_, v0_, v1_);
    tol_ = std::max(BRep_Tool::Tolerance(face), 1e-9);
    classifier_ = std::make_unique<FaceClassifier>(face, tol_, u0_, u1_, v0_, v1_);
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
  std::unique_ptr<FaceClassifier> classifier_;
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
