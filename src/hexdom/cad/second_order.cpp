#include "hexdom/cad/second_order.h"

#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include "hexdom/cad/face_projector.h"
#include "hexdom/cad/shape_impl.h"
#include "hexdom/common/error.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/second_order.h"

namespace hexdom::cad {

namespace {

/// The CAD edges (1-based ids) a node lies on: its own edge, or the edges of its vertex.
std::vector<int> cad_edges_of(SnapKind kind, int entity, const std::vector<std::vector<int>>& vertex_edges) {
  if (kind == SnapKind::Edge) return {entity};
  if (kind == SnapKind::Vertex) return vertex_edges[entity];
  return {};
}

std::vector<std::vector<int>> edges_of_vertices(const Shape::Impl& s) {
  TopTools_IndexedDataMapOfShapeListOfShape map;
  TopExp::MapShapesAndAncestors(s.shape, TopAbs_VERTEX, TopAbs_EDGE, map);
  std::vector<std::vector<int>> r(s.vertices.Extent() + 1);
  for (int i = 1; i <= s.vertices.Extent(); ++i) {
    const int k = map.FindIndex(s.vertices(i));
    if (k == 0) continue;
    for (TopTools_ListOfShape::Iterator it(map(k)); it.More(); it.Next()) {
      const int e = s.edges.FindIndex(it.Value());
      if (e > 0 && std::find(r[i].begin(), r[i].end(), e) == r[i].end()) r[i].push_back(e);
    }
  }
  return r;
}

SecondOrderResult make_second_order(const Shape& shape, const mesh::Mesh& linear, const std::vector<SnapKind>& kind,
                                    const std::vector<int>& entity, const mesh::SurfaceMesh& tess,
                                    const optimize::CurveOptions& curve) {
  const auto t0 = std::chrono::steady_clock::now();
  const Shape::Impl& s = shape.impl();
  mesh::require_first_order(linear, "second_order_on_brep");
  if (static_cast<int>(kind.size()) != linear.num_nodes() || static_cast<int>(entity.size()) != linear.num_nodes())
    throw InputError(s.source, 0, "second_order_on_brep: the snap result's node kinds do not match its mesh");
  for (int f = 0; f < tess.patch.size(); ++f)
    if (tess.patch(f) < 1 || tess.patch(f) > s.faces.Extent())
      throw InputError(s.source, 0, "tessellation triangle " + std::to_string(f + 1) + " names Face" +
                                        std::to_string(tess.patch(f)) + ", which the solid does not have");
  SecondOrderResult r;
  optimize::SecondOrderReport& rep = r.report;
  r.mesh = mesh::add_mid_edge_nodes(linear);
  mesh::Mesh& m = r.mesh;
  const int nv = m.num_nodes();
  if (linear.num_nodes() > 0) rep.diagonal = (linear.V.colwise().maxCoeff() - linear.V.colwise().minCoeff()).norm();

  // The CAD faces of the boundary faces around every boundary edge.
  std::unordered_map<mesh::EdgeKey, std::vector<int>> faces_of_edge;
  const std::vector<mesh::BoundaryFace> bfaces = mesh::boundary_faces(linear);
  const std::vector<int> tris = mesh::nearest_triangles(mesh::TriangleProjector(tess.V, tess.F), linear.V, bfaces);
  for (size_t k = 0; k < bfaces.size(); ++k) {
    const mesh::BoundaryFace& f = bfaces[k];
    const int tri = tris[k];
    for (int i = 0; i < f.n; ++i) {
      std::vector<int>& faces = faces_of_edge[mesh::undirected_edge(f.v[i], f.v[(i + 1) % f.n])];
      if (tri >= 0 && std::find(faces.begin(), faces.end(), tess.patch(tri)) == faces.end()) faces.push_back(tess.patch(tri));
    }
  }
  const std::vector<std::array<int, 2>> ends = mesh::mid_edge_ends(m);
  const std::vector<std::vector<int>> vertex_edges = edges_of_vertices(s);
  Projectors projectors(s);
  Eigen::MatrixXd target = m.V;
  std::vector<char> has_target(nv, 0);
  for (int v = linear.num_nodes(); v < nv; ++v) {
    const int a = ends[v][0], b = ends[v][1];
    const auto it = faces_of_edge.find(mesh::undirected_edge(a, b));
    if (it == faces_of_edge.end()) continue;  // an interior edge
    rep.boundary_mid_nodes++;
    const Eigen::RowVector3d mid = m.V.row(v);
    const gp_Pnt p(mid(0), mid(1), mid(2));
    const double half = 0.5 * (linear.V.row(a) - linear.V.row(b)).norm();
    double best = std::numeric_limits<double>::infinity();
    gp_Pnt q_best;
    std::vector<int> ea = cad_edges_of(kind[a], entity[a], vertex_edges);
    const std::vector<int> eb = cad_edges_of(kind[b], entity[b], vertex_edges);
    for (int e : ea) {
      if (std::find(eb.begin(), eb.end(), e) == eb.end()) continue;
      gp_Pnt q;
      double t, d;
      if (nearest_on_edge(projectors.curve(e), p, q, t, d) && d < best && d < half) best = d, q_best = q;
    }
    if (best < std::numeric_limits<double>::infinity()) {
      rep.edge_targets++;
    } else {
      for (int f : it->second) {
        gp_Pnt q;
        gp_Pnt2d uv;
        double d;
        projectors.face(f).nearest(p, q, d, uv);
        if (d < best) best = d, q_best = q;
      }
      if (!(best < std::numeric_limits<double>::infinity())) q_best = p, best = 0;  // stays where it is
      rep.face_targets++;
    }
    target.row(v) << q_best.X(), q_best.Y(), q_best.Z();
    has_target[v] = 1;
    rep.max_offset = std::max(rep.max_offset, best);
  }
  rep.curve = optimize::curve_mid_nodes(m, target, has_target, curve);
  r.quality = quality::quality_report(m);
  rep.seconds = seconds_since(t0);
  return r;
}

}  // namespace

SecondOrderResult second_order_on_brep(const Shape& shape, const mesh::Mesh& snapped, const std::vector<SnapKind>& kind,
                                       const std::vector<int>& entity, const mesh::SurfaceMesh& tess,
                                       const optimize::CurveOptions& curve) {
  try {
    return make_second_order(shape, snapped, kind, entity, tess, curve);
  } catch (const Standard_Failure& e) {
    throw GeometryError(shape.source() + ": putting the mid-edge nodes on the B-rep failed: " + occt_message(e));
  }
}

}  // namespace hexdom::cad
