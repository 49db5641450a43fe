#include "hexdom/cad/tessellate.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GeomLProp_CLProps.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <IMeshTools_Parameters.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <limits>

#include "hexdom/cad/shape_impl.h"
#include "hexdom/cad/tessellate_merge.h"
#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/remesh_surface.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::cad {

namespace {

using mesh::remesh::Kind;
using mesh::remesh::RVertex;
constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
gp_Pnt pnt(const Eigen::Vector3d& p) { return gp_Pnt(p.x(), p.y(), p.z()); }

/// The B-rep as RemeshGeometry: projections onto faces and edge curves, and the size field.
class OcctGeometry : public mesh::remesh::RemeshGeometry {
 public:
  OcctGeometry(const TopTools_IndexedMapOfShape& faces,
               const TopTools_IndexedMapOfShape& edges, const TopTools_IndexedMapOfShape& vertices,
               double max_size, double deflection, double angle, double min_size)
      : max_size_(max_size), deflection_(deflection), angle_(angle), min_size_(min_size) {
    for (int i = 1; i <= faces.Extent(); ++i) {
      FaceData fd;
      fd.face = TopoDS::Face(faces(i));
      fd.surface = BRep_Tool::Surface(fd.face);
      fd.analysis = new ShapeAnalysis_Surface(fd.surface);
      fd.tolerance = std::max(BRep_Tool::Tolerance(fd.face), 1e-9);
      BRepAdaptor_Surface ad(fd.face, false);
      fd.type = ad.GetType();
      if (fd.type == GeomAbs_Cylinder) fd.curvature = 1.0 / ad.Cylinder().Radius();
      if (fd.type == GeomAbs_Sphere) fd.curvature = 1.0 / ad.Sphere().Radius();
      faces_.push_back(fd);
    }
    for (int i = 1; i <= edges.Extent(); ++i) {
      EdgeData ed;
      ed.edge = TopoDS::Edge(edges(i));
      ed.degenerated = BRep_Tool::Degenerated(ed.edge);
      if (!ed.degenerated) {
        ed.curve = BRep_Tool::Curve(ed.edge, ed.first, ed.last);
        BRepAdaptor_Curve ac(ed.edge);
        ed.type = ac.GetType();
        if (ed.type == GeomAbs_Circle) ed.curvature = 1.0 / ac.Circle().Radius();
        ed.length = GCPnts_AbscissaPoint::Length(ac);
        TopoDS_Vertex v1, v2;
        TopExp::Vertices(ed.edge, v1, v2);
        ed.v1 = vertices.FindIndex(v1) - 1;
        ed.v2 = vertices.FindIndex(v2) - 1;
        // Samples for the thin-face size limit, about max_size / 4 apart.
        const int n = std::clamp(static_cast<int>(std::ceil(ed.length / (0.25 * max_size))), 1, 2000);
        for (int k = 0; k <= n; ++k) {
          const double t = ed.first + (ed.last - ed.first) * k / n;
          ed.sample_t.push_back(t);
          ed.sample_p.push_back(vec(ac.Value(t)));
          ed.sample_cap.push_back(std::numeric_limits<double>::infinity());
        }
      }
      edges_.push_back(ed);
    }
    for (int i = 1; i <= vertices.Extent(); ++i) corner_p_.push_back(vec(BRep_Tool::Pnt(TopoDS::Vertex(vertices(i)))));
    cap_floor_ = 0.02 * min_size;
    compute_caps(faces, edges, vertices);
  }

  bool project_to_face(RVertex& v, const Eigen::Vector3d& p) const override {
    const FaceData& fd = faces_[v.owner];
    try {
      const gp_Pnt P = pnt(p);
      const gp_Pnt2d uv = v.has_uv ? fd.analysis->NextValueOfUV(gp_Pnt2d(v.uv.x(), v.uv.y()), P, fd.tolerance)
                                   : fd.analysis->ValueOfUV(P, fd.tolerance);
      const Eigen::Vector3d q = vec(fd.surface->Value(uv.X(), uv.Y()));
      if (!q.allFinite()) return false;
      v.p = q;
      v.uv = {uv.X(), uv.Y()};
      v.has_uv = true;
      return true;
    } catch (const Standard_Failure&) {
      return false;
    }
  }

  bool project_to_curve(RVertex& v, const Eigen::Vector3d& p) const override {
    const EdgeData& ed = edges_[v.owner];
    if (ed.curve.IsNull()) return false;
    try {
      gp_Pnt proj;
      double t = 0, d = 0;
      if (!nearest_on_curve(ed.curve, ed.first, ed.last, pnt(p), proj, t, d)) return false;
      const Eigen::Vector3d q = vec(proj);
      if (!q.allFinite()) return false;
      v.p = q;
      v.t = t;
      return true;
    } catch (const Standard_Failure&) {
      return false;
    }
  }

  bool is_planar(int f) const override { return faces_[f].type == GeomAbs_Plane; }

  double size_at(const RVertex& v) const override {
    double h = max_size_;
    try {
      if (v.kind == Kind::Corner) return std::min(h, corner_cap_[v.owner]);
      if (v.kind == Kind::Curve) {
        const EdgeData& ed = edges_[v.owner];
        double k = 0;
        if (ed.type == GeomAbs_Circle) {
          k = ed.curvature;
        } else if (ed.type != GeomAbs_Line && !ed.curve.IsNull()) {
          GeomLProp_CLProps props(ed.curve, v.t, 2, 1e-9);
          if (props.IsTangentDefined()) k = std::abs(props.Curvature());
        }
        return std::min(size_for_curvature(k), cap_on_edge(ed, v.t));
      }
      const FaceData& fd = faces_[v.owner];
      double k = 0;
      if (fd.type == GeomAbs_Plane) {
        k = 0;
      } else if (fd.type == GeomAbs_Cylinder || fd.type == GeomAbs_Sphere) {
        k = fd.curvature;
      } else if (v.has_uv) {
        GeomLProp_SLProps props(fd.surface, v.uv.x(), v.uv.y(), 2, 1e-9);
        if (props.IsCurvatureDefined()) k = std::max(std::abs(props.MaxCurvature()), std::abs(props.MinCurvature()));
      }
      return size_for_curvature(k);
    } catch (const Standard_Failure&) {
      return h;
    }
  }

 private:
  struct FaceData {
    TopoDS_Face face;
    Handle(Geom_Surface) surface;
    Handle(ShapeAnalysis_Surface) analysis;
    GeomAbs_SurfaceType type = GeomAbs_OtherSurface;
    double curvature = 0;
    double tolerance = 1e-7;
  };
  struct EdgeData {
    TopoDS_Edge edge;
    Handle(Geom_Curve) curve;
    double first = 0, last = 0, length = 0, curvature = 0;
    GeomAbs_CurveType type = GeomAbs_OtherCurve;
    bool degenerated = false;
    int v1 = -1, v2 = -1;
    std::vector<double> sample_t, sample_cap;
    std::vector<Eigen::Vector3d> sample_p;
  };

  /// Edge length that keeps the chord within `deflection_` and the turning angle within `angle_`
  /// on a curvature k.
  double size_for_curvature(double k) const {
    if (k <= 1e-12) return max_size_;
    const double r = 1.0 / k;
    double l = max_size_;
    if (deflection_ > 0) l = std::min(l, deflection_ < r ? 2.0 * std::sqrt(deflection_ * (2.0 * r - deflection_)) : 2.0 * r);
    if (angle_ > 0) l = std::min(l, r * angle_);
    return std::max(l, min_size_);
  }

  static double cap_on_edge(const EdgeData& ed, double t) {
    const auto& ts = ed.sample_t;
    if (ts.size() < 2) return std::numeric_limits<double>::infinity();
    const double s = (t - ts.front()) / (ts.back() - ts.front()) * (ts.size() - 1);
    const int i = std::clamp(static_cast<int>(std::floor(s)), 0, static_cast<int>(ts.size()) - 2);
    const double w = std::clamp(s - i, 0.0, 1.0);
    const double a = ed.sample_cap[i], b = ed.sample_cap[i + 1];
    if (!std::isfinite(a) || !std::isfinite(b)) return std::min(a, b);
    return (1 - w) * a + w * b;
  }

  /// Size limits from the B-rep's topology: along an edge, the distance to the other edges of the
  /// same face that share no vertex with it (a thin face needs triangles as small as its width);
  /// at a CAD vertex, the length of its shortest edge.
  void compute_caps(const TopTools_IndexedMapOfShape& faces, const TopTools_IndexedMapOfShape& edges,
                    const TopTools_IndexedMapOfShape& vertices) {
    for (int f = 1; f <= faces.Extent(); ++f) {
      const TopoDS_Face& face = TopoDS::Face(faces(f));
      std::vector<int> boundary;
      for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
        const int e = edges.FindIndex(ex.Current()) - 1;
        if (edges_[e].degenerated || BRep_Tool::IsClosed(TopoDS::Edge(ex.Current()), face)) continue;
        if (std::find(boundary.begin(), boundary.end(), e) == boundary.end()) boundary.push_back(e);
      }
      for (int e : boundary) {
        EdgeData& ed = edges_[e];
        for (int o : boundary) {
          if (o == e) continue;
          const EdgeData& od = edges_[o];
          // Edges that meet at a CAD vertex c count only where they are closer to each other than
          // half their distance to c: near a corner sharper than about 30 degrees (a cusp between
          // tangent arcs), not near an ordinary one.
          std::vector<Eigen::Vector3d> shared;
          for (int v : {od.v1, od.v2})
            if (v >= 0 && (v == ed.v1 || v == ed.v2)) shared.push_back(corner_p_[v]);
          for (size_t i = 0; i < ed.sample_p.size(); ++i) {
            const Eigen::Vector3d& x = ed.sample_p[i];
            for (const auto& y : od.sample_p) {
              const double d = (x - y).norm();
              if (d >= ed.sample_cap[i]) continue;
              bool near_corner = false;
              for (const auto& c : shared) {
                const double r = std::min((x - c).norm(), (y - c).norm());
                if (r <= 1e-6 * max_size_ || d >= 0.5 * r) near_corner = true;
              }
              if (!near_corner) ed.sample_cap[i] = std::max(d, cap_floor_);
            }
          }
        }
      }
    }
    corner_cap_.assign(vertices.Extent(), std::numeric_limits<double>::infinity());
    for (const EdgeData& ed : edges_) {
      if (ed.degenerated || ed.v1 < 0) continue;
      for (int v : {ed.v1, ed.v2}) {
        double& c = corner_cap_[v];
        c = std::min(c, std::max(ed.length, cap_floor_));
        if (!ed.sample_cap.empty()) c = std::min(c, v == ed.v1 ? ed.sample_cap.front() : ed.sample_cap.back());
      }
    }
  }

  std::vector<FaceData> faces_;
  std::vector<EdgeData> edges_;
  std::vector<double> corner_cap_;
  std::vector<Eigen::Vector3d> corner_p_;
  double cap_floor_ = 0;  ///< thin faces and cusps refine down to this length, no further
  double max_size_, deflection_, angle_, min_size_;
};

double tri_min_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  auto angle = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
  return std::min({angle(b - a, c - a), angle(a - b, c - b), angle(a - c, b - c)}) * 180.0 / kPi;
}

}  // namespace

TessellateStats tessellation_stats(const Shape& shape, const mesh::SurfaceMesh& s) {
  const ShapeInfo info = shape_info(shape);
  TessellateStats st;
  st.triangles = static_cast<int>(s.F.rows());
  st.vertices = static_cast<int>(s.V.rows());
  st.faces = info.faces;
  st.min_angle = 180;
  st.min_angle_planar = 180;
  st.min_edge = std::numeric_limits<double>::infinity();
  double edge_sum = 0;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    const double ang = tri_min_angle_deg(a, b, c);
    st.min_angle = std::min(st.min_angle, ang);
    const int f = s.patch(t);
    if (f >= 1 && f <= info.faces && info.face_types[f - 1] == SurfaceType::Plane)
      st.min_angle_planar = std::min(st.min_angle_planar, ang);
    for (double l : {(b - a).norm(), (c - b).norm(), (a - c).norm()}) {
      edge_sum += l;
      st.min_edge = std::min(st.min_edge, l);
      st.max_edge = std::max(st.max_edge, l);
    }
  }
  st.mean_edge = s.F.rows() ? edge_sum / (3.0 * s.F.rows()) : 0;
  st.closed = s.F.rows() > 0 && closed_manifold_problem(s.F).empty();
  st.volume = mesh::enclosed_volume(s.V, s.F);
  st.brep_volume = info.volume;
  return st;
}

namespace {
mesh::SurfaceMesh tessellate_once(const Shape& shape, const TessellateOptions& options, TessellateStats* stats);
}  // namespace

mesh::SurfaceMesh tessellate(const Shape& shape, const TessellateOptions& options, TessellateStats* stats) {
  mesh::SurfaceMesh s = tessellate_once(shape, options, stats);
  if (options.size > 0 || !options.size_in_frame || s.F.rows() == 0) return s;
  const segmentation::CubeFrame frame = segmentation::cube_frame(s);
  if (!frame.turned()) return s;
  TessellateOptions again = options;
  again.size = segmentation::frame_diagonal(s, frame.rotation) / 30.0;
  if (options.log)
    options.log(0, fmt("tessellate: the faces fit axes turned by %.1f degrees; size from the box square to them: %g",
                       frame.angle_degrees, again.size));
  const double first = stats ? stats->seconds : 0.0;
  s = tessellate_once(shape, again, stats);
  if (stats) stats->seconds += first;
  return s;
}

namespace {

/// The options' sizes, the defaults taken from the solid's bounding box. Throws GeometryError for a
/// solid without extent, InputError for a size that would give more than 20 million triangles.
Sizes resolve_sizes(const Shape& shape, const TessellateOptions& options) {
  const Shape::Impl& impl = shape.impl();
  const std::string& source = impl.source;
  Bnd_Box box;
  BRepBndLib::Add(impl.shape, box);
  if (box.IsVoid()) throw GeometryError(source + ": the solid has no extent");
  const double diag = std::sqrt(box.SquareExtent());
  Sizes z;
  z.size = options.size > 0 ? options.size : diag / 30.0;
  z.deflection = options.deflection > 0 ? options.deflection : z.size / 50.0;
  z.min_size = std::min(options.min_size > 0 ? options.min_size : z.size / 20.0, z.size);
  z.angle = options.angle * kPi / 180.0;
  const ShapeInfo info = shape_info(shape);
  const double estimate = info.area / (0.433 * z.size * z.size);
  if (estimate > 2e7)
    throw InputError(source, 0, "size " + std::to_string(z.size) + " would give about " +
                                    std::to_string(static_cast<long>(estimate)) +
                                    " triangles (limit 20 million): choose a larger size");
  return z;
}

/// A copy without triangulations, so the caller's shape is left untouched.
WorkShape copy_without_triangulations(const Shape::Impl& impl) {
  const std::string& source = impl.source;
  WorkShape w;
  w.source = source;
  BRepBuilderAPI_Copy copier(impl.shape, true, false);
  w.shape = copier.Shape();
  BRepTools::Clean(w.shape);
  BRepLib::BuildCurves3d(w.shape);
  TopExp::MapShapes(w.shape, TopAbs_FACE, w.faces);
  TopExp::MapShapes(w.shape, TopAbs_EDGE, w.edges);
  TopExp::MapShapes(w.shape, TopAbs_VERTEX, w.vertices);
  // The copy's faces in the original's numbering, without relying on the copy keeping the order.
  w.original_face.assign(w.faces.Extent(), -1);
  for (int i = 1; i <= impl.faces.Extent(); ++i) {
    const int k = w.faces.FindIndex(copier.ModifiedShape(impl.faces(i)));
    if (k < 1 || w.original_face[k - 1] >= 0)
      throw MeshingError(source + ": copying the solid lost track of Face" + std::to_string(i));
    w.original_face[k - 1] = i;
  }
  return w;
}

/// Triangulates the copy with BRepMesh: the initial triangles, which the remesher refines.
void run_brepmesh(const WorkShape& w, const Sizes& z, const std::string& source) {
  IMeshTools_Parameters mp;
  mp.Deflection = z.deflection;
  mp.Angle = z.angle > 0 ? std::min(z.angle, 0.5) : 0.5;
  mp.Relative = Standard_False;
  mp.InParallel = Standard_False;
  mp.MinSize = 0.25 * z.min_size;
  check_interrupt("tessellate");
  BRepMesh_IncrementalMesh mesher(w.shape, mp);
  check_interrupt("tessellate");
  if (!mesher.IsDone()) throw MeshingError(source + ": BRepMesh failed");
}

/// The merged triangles remeshed on the B-rep (OcctGeometry), each triangle's patch its face in the
/// original's numbering.
mesh::SurfaceMesh remesh_on_brep(const WorkShape& w, Merged&& merged, const Sizes& z, const TessellateOptions& options,
                                 long* splits) {
  OcctGeometry geometry(w.faces, w.edges, w.vertices, z.size, z.deflection, z.angle, z.min_size);
  mesh::remesh::RemeshParams rp;
  rp.max_size = z.size;
  rp.iterations = options.iterations;
  rp.log = options.log;
  mesh::remesh::SurfaceRemesher remesher(std::move(merged.V), merged.F, merged.face_of, geometry, rp);
  const std::vector<std::vector<int>>& edge_nodes = merged.edge_nodes;
  for (int e = 0; e < w.edges.Extent(); ++e)
    if (edge_nodes[e].size() == 2 && edge_nodes[e][0] != edge_nodes[e][1])
      remesher.set_corner_edge(edge_nodes[e][0], edge_nodes[e][1], e);
  remesher.run();
  *splits = remesher.splits();

  mesh::SurfaceMesh out;
  Eigen::VectorXi face;
  remesher.extract(out.V, out.F, face);
  out.patch.resize(face.size());
  for (Eigen::Index t = 0; t < face.size(); ++t) out.patch(t) = w.original_face[face(t)];
  return out;
}

mesh::SurfaceMesh tessellate_once(const Shape& shape, const TessellateOptions& options, TessellateStats* stats) {
  const auto t_start = std::chrono::steady_clock::now();
  const Shape::Impl& impl = shape.impl();
  const std::string& source = impl.source;
  if (!(options.size >= 0) || !(options.deflection >= 0) || !(options.angle >= 0) || !(options.min_size >= 0) ||
      !std::isfinite(options.size) || !std::isfinite(options.deflection))
    throw InputError(source, 0, "tessellation options must be finite and non-negative");
  try {
    const Sizes z = resolve_sizes(shape, options);
    const WorkShape w = copy_without_triangulations(impl);
    run_brepmesh(w, z, source);
    long splits = 0;
    mesh::SurfaceMesh out = remesh_on_brep(w, merge_triangulations(w, z, options), z, options, &splits);
    int at = -1;
    const std::string problem = closed_manifold_problem(out.F, &at);
    if (!problem.empty())
      throw MeshingError(source + ": the tessellation is not closed" +
                         (at >= 0 ? " at Face" + std::to_string(out.patch(at)) : std::string()) + ": " + problem);
    if (mesh::enclosed_volume(out.V, out.F) < 0) {
      out.F.col(1).swap(out.F.col(2));
      if (options.log) options.log(1, source + ": the solid's faces point inward; turned the triangles over");
    }
    if (stats) {
      *stats = tessellation_stats(shape, out);
      stats->size = z.size;
      stats->splits = splits;
      stats->seconds = seconds_since(t_start);
      if (options.log && stats->brep_volume != 0 &&
          std::abs(stats->volume - stats->brep_volume) > 0.01 * std::abs(stats->brep_volume))
        options.log(1, source + ": the tessellation encloses " + std::to_string(stats->volume) +
                           " but the solid's volume is " + std::to_string(stats->brep_volume));
    }
    return out;
  } catch (const Standard_Failure& e) {
    throw MeshingError(source + ": OpenCASCADE failed while tessellating: " + occt_message(e));
  }
}

}  // namespace

}  // namespace hexdom::cad
