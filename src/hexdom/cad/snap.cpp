#include "hexdom/cad/snap.h"

#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "hexdom/cad/face_projector.h"
#include "hexdom/cad/project.h"
#include "hexdom/cad/shape_impl.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::cad {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// For each sub-shape of `kind` (1-based as in `map`), the sorted 1-based ids of the faces holding it.
std::vector<std::vector<int>> faces_of(const Shape::Impl& s, TopAbs_ShapeEnum kind, const TopTools_IndexedMapOfShape& map) {
  TopTools_IndexedDataMapOfShapeListOfShape anc;
  TopExp::MapShapesAndAncestors(s.shape, kind, TopAbs_FACE, anc);
  std::vector<std::vector<int>> out(map.Extent() + 1);
  for (int i = 1; i <= map.Extent(); ++i) {
    const int k = anc.FindIndex(map(i));
    if (k == 0) continue;
    std::set<int> ids;
    for (TopTools_ListOfShape::Iterator it(anc(k)); it.More(); it.Next()) {
      const int f = s.faces.FindIndex(it.Value());
      if (f > 0) ids.insert(f);
    }
    out[i].assign(ids.begin(), ids.end());
  }
  return out;
}

double worst_sj(const mesh::Mesh& m, int* inverted) {
  double w = 2;
  int bad = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    const double sj = quality::scaled_jacobian(m.type(c), quality::cell_points(m, c));
    if (quality::is_inverted(sj)) ++bad;
    w = std::min(w, sj);
  }
  if (inverted) *inverted = bad;
  return m.num_cells() ? w : 1.0;
}

void distance_stats(const Projection& p, double& max, double& mean) {
  max = p.distance.size() ? p.distance.maxCoeff() : 0.0;
  mean = p.distance.size() ? p.distance.mean() : 0.0;
}

}  // namespace

namespace {
SnapResult snap(const Shape& shape, const mesh::Mesh& input, const mesh::SurfaceMesh& tess, const SnapOptions& opt) {
  const Shape::Impl& s = shape.impl();
  auto say = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  const int nfaces = s.faces.Extent();
  if (tess.F.rows() == 0) throw InputError(s.source, 0, "snap_to_brep needs the tessellation of the part (it has no triangles)");
  if (tess.patch.size() != tess.F.rows())
    throw InputError(s.source, 0, "tessellation has " + std::to_string(tess.patch.size()) + " face ids for " +
                                      std::to_string(tess.F.rows()) + " triangles");
  for (int t = 0; t < tess.F.rows(); ++t) {
    if (tess.patch(t) < 1 || tess.patch(t) > nfaces)
      throw InputError(s.source, 0, "tessellation triangle " + std::to_string(t) + " names Face" + std::to_string(tess.patch(t)) +
                                        ", but the solid has " + std::to_string(nfaces) + " faces");
    for (int k = 0; k < 3; ++k)
      if (tess.F(t, k) < 0 || tess.F(t, k) >= tess.V.rows())
        throw InputError(s.source, 0, "tessellation triangle " + std::to_string(t) + " names vertex " + std::to_string(tess.F(t, k)) +
                                          ", but there are " + std::to_string(tess.V.rows()) + " vertices");
  }
  for (int c = 0; c < input.num_cells(); ++c)
    if (!mesh::is_volume(input.type(c)))
      throw GeometryError("cell " + std::to_string(c + 1) + " is a " + mesh::type_name(input.type(c)) +
                          ": snapping to the B-rep takes hex, prism and tet cells only");

  SnapResult r;
  SnapReport& rep = r.report;
  const auto t0 = Clock::now();
  mesh::Mesh m = input;
  const int nn = m.num_nodes();
  if (nn) rep.diagonal = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  rep.worst_sj_before = worst_sj(m, nullptr);
  r.kind.assign(nn, SnapKind::Interior);
  r.entity.assign(nn, 0);

  // CAD faces around each boundary node, and its shortest boundary edge.
  const std::vector<mesh::BoundaryFace> bfaces = mesh::boundary_faces(m);
  const mesh::TriangleProjector tp(tess.V, tess.F);
  std::vector<std::set<int>> cand(nn);
  std::vector<double> shortest(nn, std::numeric_limits<double>::infinity());
  std::vector<char> on_boundary(nn, 0);
  for (const auto& f : bfaces) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < f.n; ++i) c += m.V.row(f.v[i]).transpose();
    int tri = -1;
    tp.project(c / f.n, &tri);
    for (int i = 0; i < f.n; ++i) {
      const int v = f.v[i], w = f.v[(i + 1) % f.n];
      on_boundary[v] = 1;
      if (tri >= 0) cand[v].insert(tess.patch(tri));
      const double l = (m.V.row(v) - m.V.row(w)).norm();
      shortest[v] = std::min(shortest[v], l);
      shortest[w] = std::min(shortest[w], l);
    }
  }
  std::vector<int> boundary;
  for (int v = 0; v < nn; ++v) {
    if (!on_boundary[v]) continue;
    boundary.push_back(v);
    int tri = -1;
    tp.project(m.V.row(v).transpose(), &tri);
    if (tri >= 0) cand[v].insert(tess.patch(tri));
  }
  rep.boundary_nodes = static_cast<int>(boundary.size());
  if (boundary.empty()) {
    r.mesh = std::move(m);
    r.quality = quality::quality_report(r.mesh);
    return r;
  }
  Eigen::MatrixXd B(boundary.size(), 3);
  for (size_t i = 0; i < boundary.size(); ++i) B.row(i) = m.V.row(boundary[i]);
  distance_stats(project_to_shape(shape, B), rep.max_before, rep.mean_before);

  const std::vector<std::vector<int>> edge_faces = faces_of(s, TopAbs_EDGE, s.edges);
  const std::vector<std::vector<int>> vertex_faces = faces_of(s, TopAbs_VERTEX, s.vertices);
  std::vector<char> edge_usable(s.edges.Extent() + 1, 0);
  std::map<std::pair<int, int>, std::vector<int>> pair_edges;  // (face a < face b) -> shared edges
  for (int e = 1; e <= s.edges.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(s.edges(e));
    // Seams (one face on both sides) and degenerated edges (poles) are not features.
    edge_usable[e] = !BRep_Tool::Degenerated(edge) && edge_faces[e].size() >= 2;
    if (!edge_usable[e]) continue;
    for (size_t i = 0; i < edge_faces[e].size(); ++i)
      for (size_t j = i + 1; j < edge_faces[e].size(); ++j) pair_edges[{edge_faces[e][i], edge_faces[e][j]}].push_back(e);
  }
  auto intersect_count = [](const std::vector<int>& a, const std::set<int>& b) {
    int n = 0;
    for (int x : a) n += b.count(x) > 0;
    return n;
  };

  Eigen::MatrixXd target = m.V;
  std::vector<char> placed(nn, 0);

  // Vertices: a node whose CAD faces include three of a vertex's faces, within the tolerance of it;
  // the nearest such node per vertex.
  {
    std::map<int, std::pair<double, int>> best;  // vertex -> (distance, node)
    for (int v : boundary) {
      if (cand[v].size() < 3) continue;
      const Eigen::Vector3d p = m.V.row(v).transpose();
      for (int x = 1; x <= s.vertices.Extent(); ++x) {
        if (intersect_count(vertex_faces[x], cand[v]) < 3) continue;
        const gp_Pnt q = BRep_Tool::Pnt(TopoDS::Vertex(s.vertices(x)));
        const double d = (p - Eigen::Vector3d(q.X(), q.Y(), q.Z())).norm();
        if (d > opt.edge_tolerance * shortest[v]) continue;
        auto it = best.find(x);
        if (it == best.end() || d < it->second.first) best[x] = {d, v};
      }
    }
    std::map<int, std::pair<double, int>> by_node;  // a node near two vertices takes the nearer
    for (const auto& [x, dv] : best) {
      auto it = by_node.find(dv.second);
      if (it == by_node.end() || dv.first < it->second.first) by_node[dv.second] = {dv.first, x};
    }
    for (const auto& [v, dx] : by_node) {
      const gp_Pnt q = BRep_Tool::Pnt(TopoDS::Vertex(s.vertices(dx.second)));
      target.row(v) << q.X(), q.Y(), q.Z();
      placed[v] = 1;
      r.kind[v] = SnapKind::Vertex;
      r.entity[v] = dx.second;
    }
  }

  // Edges: batch the nodes per candidate edge, keep the nearest edge of each node.
  {
    std::map<int, std::vector<int>> per_edge;
    for (int v : boundary) {
      if (placed[v] || cand[v].size() < 2) continue;
      std::set<int> edges;
      for (auto a = cand[v].begin(); a != cand[v].end(); ++a)
        for (auto b = std::next(a); b != cand[v].end(); ++b) {
          auto it = pair_edges.find({*a, *b});
          if (it != pair_edges.end()) edges.insert(it->second.begin(), it->second.end());
        }
      for (int e : edges) per_edge[e].push_back(v);
    }
    std::vector<double> best(nn, std::numeric_limits<double>::infinity());
    for (const auto& [e, nodes] : per_edge) {
      Eigen::MatrixXd P(nodes.size(), 3);
      for (size_t i = 0; i < nodes.size(); ++i) P.row(i) = m.V.row(nodes[i]);
      const Projection pr = project_to_edge(shape, e, P);
      for (size_t i = 0; i < nodes.size(); ++i) {
        const int v = nodes[i];
        if (pr.distance(i) < best[v] && pr.distance(i) <= opt.edge_tolerance * shortest[v]) {
          best[v] = pr.distance(i);
          target.row(v) = pr.points.row(i);
          r.kind[v] = SnapKind::Edge;
          r.entity[v] = e;
        }
      }
    }
    for (int v : boundary)
      if (r.kind[v] == SnapKind::Edge) placed[v] = 1;
  }

  // Faces: the nearest of the node's CAD faces, trimmed.
  {
    std::map<int, std::vector<int>> per_face;
    for (int v : boundary)
      if (!placed[v])
        for (int f : cand[v]) per_face[f].push_back(v);
    std::vector<double> best(nn, std::numeric_limits<double>::infinity());
    for (const auto& [f, nodes] : per_face) {
      Eigen::MatrixXd P(nodes.size(), 3);
      for (size_t i = 0; i < nodes.size(); ++i) P.row(i) = m.V.row(nodes[i]);
      const Projection pr = project_to_face(shape, f, P);
      for (size_t i = 0; i < nodes.size(); ++i) {
        const int v = nodes[i];
        if (pr.distance(i) < best[v]) {
          best[v] = pr.distance(i);
          target.row(v) = pr.points.row(i);
          r.kind[v] = SnapKind::Face;
          r.entity[v] = f;
        }
      }
    }
  }

  for (int v : boundary) {
    rep.max_move = std::max(rep.max_move, (target.row(v) - m.V.row(v)).norm());
    rep.face_nodes += r.kind[v] == SnapKind::Face;
    rep.edge_nodes += r.kind[v] == SnapKind::Edge;
    rep.vertex_nodes += r.kind[v] == SnapKind::Vertex;
  }
  rep.seconds_project = since(t0);

  // Restoration. Every cell that gets worse stays at or above min(keep, worst before the snap).
  const double keep = opt.keep < 0 ? -2.0 : std::min(opt.keep, rep.worst_sj_before);
  std::vector<std::unique_ptr<FaceProjector>> faces(nfaces + 1);
  std::vector<EdgeCurve> curves(s.edges.Extent() + 1);
  std::vector<char> have_curve(s.edges.Extent() + 1, 0);
  // The mesh restored after moving the boundary to the B-rep in `steps` steps (see SnapOptions),
  // with the worst SJ and inverted cells right after the last move.
  struct Restored {
    mesh::Mesh mesh;
    double worst_snapped = 0;
    int inverted_snapped = 0;
  };
  const bool restore = opt.smooth > 0 || opt.optimize > 0;
  auto run = [&](int steps, double floor) {
    Restored out;
    mesh::Mesh w = m;
    const Eigen::MatrixXd start = m.V;
    for (int k = 1; restore && k < steps; ++k) {
      const double a = static_cast<double>(k) / steps;
      for (int v : boundary) w.V.row(v) = start.row(v) + a * (target.row(v) - start.row(v));
      optimize::ImproveOptions io;
      io.smooth = opt.smooth;
      io.optimize = opt.optimize;
      io.floor = floor;
      io.fixed_nodes = boundary;
      w = optimize::improve(w, io).mesh;
    }
    for (int v : boundary) w.V.row(v) = target.row(v);
    out.worst_snapped = worst_sj(w, &out.inverted_snapped);
    if (restore) {
      optimize::ImproveOptions io;
      io.smooth = opt.smooth;
      io.optimize = opt.optimize;
      io.floor = floor;
      io.mean_after = true;  // the smoothing costs the mean improve reached
      for (int v : boundary)
        if (!opt.slide || r.kind[v] == SnapKind::Vertex) io.fixed_nodes.push_back(v);
      if (opt.slide)
        io.project = [&](int v, const Eigen::Vector3d& x) -> Eigen::Vector3d {
          const gp_Pnt p(x(0), x(1), x(2));
          gp_Pnt q;
          double d = std::numeric_limits<double>::infinity();
          const int id = r.entity[v];
          if (r.kind[v] == SnapKind::Face) {
            if (!faces[id]) faces[id] = std::make_unique<FaceProjector>(TopoDS::Face(s.faces(id)));
            gp_Pnt2d uv;
            faces[id]->nearest(p, q, d, uv);
          } else if (r.kind[v] == SnapKind::Edge) {
            if (!have_curve[id]) curves[id] = edge_curve(TopoDS::Edge(s.edges(id))), have_curve[id] = 1;
            double t;
            if (!nearest_on_edge(curves[id], p, q, t, d)) d = std::numeric_limits<double>::infinity();
          }
          if (!std::isfinite(d)) return w.V.row(v).transpose();  // stays where it is
          return Eigen::Vector3d(q.X(), q.Y(), q.Z());
        };
      w = optimize::improve(w, io).mesh;
    }
    out.mesh = std::move(w);
    return out;
  };

  const auto t1 = Clock::now();
  char line[320];
  Restored best = run(1, keep);
  if (restore && opt.steps > 1) {
    // The progressive snap where the direct one costs quality: fewer inverted cells first, then
    // the better worst cell.
    int inv_best = 0;
    const double w_best = worst_sj(best.mesh, &inv_best);
    if (inv_best > 0 || w_best < rep.worst_sj_before - 1e-3) {
      Restored other = run(opt.steps, keep);
      int inv_other = 0;
      const double w_other = worst_sj(other.mesh, &inv_other);
      std::snprintf(line, sizeof line, "snap: direct worst SJ %.4f (%d inverted), in %d steps %.4f (%d inverted)", w_best,
                    inv_best, opt.steps, w_other, inv_other);
      say(line);
      if (inv_other < inv_best || (inv_other == inv_best && w_other > w_best)) best = std::move(other);
    }
  }
  if (restore && keep > -2) {
    // The floor can stall untangling (its path may need good cells to give way): then without it.
    int inv_best = 0;
    const double w_best = worst_sj(best.mesh, &inv_best);
    if (inv_best > 0) {
      Restored other = run(1, -2);
      int inv_other = 0;
      const double w_other = worst_sj(other.mesh, &inv_other);
      std::snprintf(line, sizeof line, "snap: with the floor worst SJ %.4f (%d inverted), without %.4f (%d inverted)",
                    w_best, inv_best, w_other, inv_other);
      say(line);
      if (inv_other < inv_best || (inv_other == inv_best && w_other > w_best)) best = std::move(other);
    }
  }
  m = std::move(best.mesh);
  rep.worst_sj_snapped = best.worst_snapped;
  rep.inverted_snapped = best.inverted_snapped;
  std::snprintf(line, sizeof line,
                "snap: %d boundary nodes onto %d faces, %d edges, %d vertices (largest move %.3g); worst SJ %.4f -> %.4f, "
                "%d inverted",
                rep.boundary_nodes, rep.face_nodes, rep.edge_nodes, rep.vertex_nodes, rep.max_move, rep.worst_sj_before,
                rep.worst_sj_snapped, rep.inverted_snapped);
  say(line);
  rep.seconds_restore = since(t1);
  rep.worst_sj = worst_sj(m, &rep.inverted);

  for (size_t i = 0; i < boundary.size(); ++i) B.row(i) = m.V.row(boundary[i]);
  distance_stats(project_to_shape(shape, B), rep.max_after, rep.mean_after);
  r.quality = quality::quality_report(m);
  r.mesh = std::move(m);
  std::snprintf(line, sizeof line,
                "snap: B-rep distance max %.3g -> %.3g (%.2e of the diagonal), mean %.3g -> %.3g; worst SJ %.4f, %d inverted",
                rep.max_before, rep.max_after, rep.diagonal > 0 ? rep.max_after / rep.diagonal : 0.0, rep.mean_before,
                rep.mean_after, rep.worst_sj, rep.inverted);
  say(line);
  return r;
}
}  // namespace

SnapResult snap_to_brep(const Shape& shape, const mesh::Mesh& input, const mesh::SurfaceMesh& tess, const SnapOptions& opt) {
  try {
    return snap(shape, input, tess, opt);
  } catch (const Standard_Failure& e) {
    throw GeometryError(shape.source() + ": snapping the mesh to the B-rep failed: " + occt_message(e));
  }
}

}  // namespace hexdom::cad
