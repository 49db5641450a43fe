#include "hexdom/cad/snap.h"

#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <unordered_map>

#include "hexdom/cad/face_projector.h"
#include "hexdom/cad/project.h"
#include "hexdom/cad/shape_impl.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/common/parallel_for.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::cad {

namespace {

using Clock = std::chrono::steady_clock;

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


}  // namespace

namespace {

void say(const SnapOptions& opt, const std::string& m) {
  if (opt.log) opt.log(0, m);
}

/// Throws InputError when the tessellation does not fit the solid (no triangles, a face id per
/// triangle missing or naming no face, a vertex index out of range), GeometryError for a cell that
/// is not a volume cell.
void check_input(const Shape::Impl& s, const mesh::Mesh& input, const mesh::SurfaceMesh& tess) {
  mesh::require_first_order(input, "snapping to the B-rep");
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
}

/// The boundary nodes of a mesh, with the CAD faces around each and its shortest boundary edge.
struct BoundaryNodes {
  std::vector<int> nodes;           ///< ascending
  std::vector<std::set<int>> cand;  ///< per mesh node: the faces of the tessellation triangles nearest to
                                    ///< it and to the centres of its boundary faces
  std::vector<double> shortest;     ///< per mesh node: its shortest boundary edge
};

BoundaryNodes boundary_nodes(const mesh::Mesh& m, const mesh::SurfaceMesh& tess) {
  const int nn = m.num_nodes();
  BoundaryNodes b;
  const std::vector<mesh::BoundaryFace> bfaces = mesh::boundary_faces(m);
  const mesh::TriangleProjector tp(tess.V, tess.F);
  b.cand.resize(nn);
  b.shortest.assign(nn, std::numeric_limits<double>::infinity());
  std::vector<char> on_boundary(nn, 0);
  const std::vector<int> tris = mesh::nearest_triangles(tp, m.V, bfaces);
  for (size_t k = 0; k < bfaces.size(); ++k) {
    const mesh::BoundaryFace& f = bfaces[k];
    const int tri = tris[k];
    for (int i = 0; i < f.n; ++i) {
      const int v = f.v[i], w = f.v[(i + 1) % f.n];
      on_boundary[v] = 1;
      if (tri >= 0) b.cand[v].insert(tess.patch(tri));
      const double l = (m.V.row(v) - m.V.row(w)).norm();
      b.shortest[v] = std::min(b.shortest[v], l);
      b.shortest[w] = std::min(b.shortest[w], l);
    }
  }
  for (int v = 0; v < nn; ++v) {
    if (!on_boundary[v]) continue;
    b.nodes.push_back(v);
    int tri = -1;
    tp.project(m.V.row(v).transpose(), &tri);
    if (tri >= 0) b.cand[v].insert(tess.patch(tri));
  }
  return b;
}

using FacePairEdges = std::map<std::pair<int, int>, std::vector<int>>;  // (face a < face b) -> shared edges

/// The CAD edges shared by each two faces (1-based ids). Seams (one face on both sides) and
/// degenerated edges (poles) are not features and are left out.
FacePairEdges edges_between_faces(const Shape::Impl& s, const std::vector<std::vector<int>>& edge_faces) {
  std::vector<char> edge_usable(s.edges.Extent() + 1, 0);
  FacePairEdges pair_edges;
  for (int e = 1; e <= s.edges.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(s.edges(e));
    edge_usable[e] = !BRep_Tool::Degenerated(edge) && edge_faces[e].size() >= 2;
    if (!edge_usable[e]) continue;
    for (size_t i = 0; i < edge_faces[e].size(); ++i)
      for (size_t j = i + 1; j < edge_faces[e].size(); ++j) pair_edges[{edge_faces[e][i], edge_faces[e][j]}].push_back(e);
  }
  return pair_edges;
}

int intersect_count(const std::vector<int>& a, const std::set<int>& b) {
  int n = 0;
  for (int x : a) n += b.count(x) > 0;
  return n;
}

/// Where the projection puts the boundary nodes: the target of each node, whether it is placed
/// yet, and what it is put on (the result's kind and entity).
struct Targets {
  Eigen::MatrixXd point;
  std::vector<char> placed;
  SnapResult& r;
  std::unordered_map<int, gp_Pnt2d> uv;  ///< face nodes: the parameters of their target on the face
};

/// Projectors for the threads of a restoration: a call takes one no other thread is using (a
/// FaceProjector serves one thread at a time) and gives it back; more are built as needed. A
/// projection's result depends only on the face or edge and its arguments, not on which projectors
/// made it, so the mesh does not depend on the number of threads.
class ProjectorPool {
 public:
  ProjectorPool(const Shape::Impl& s, Projectors& first) : s_(s), free_{&first} {}
  /// One projectors object for the caller's use until the lease ends.
  class Lease {
   public:
    explicit Lease(ProjectorPool& pool) : pool_(pool), p_(pool.take()) {}
    ~Lease() { pool_.give(p_); }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    Projectors& operator*() const { return *p_; }

   private:
    ProjectorPool& pool_;
    Projectors* p_;
  };

 private:
  Projectors* take() {
    std::lock_guard<std::mutex> lock(mu_);
    if (free_.empty()) {
      owned_.push_back(std::make_unique<Projectors>(s_));
      return owned_.back().get();
    }
    Projectors* p = free_.back();
    free_.pop_back();
    return p;
  }
  void give(Projectors* p) {
    std::lock_guard<std::mutex> lock(mu_);
    free_.push_back(p);
  }
  const Shape::Impl& s_;
  std::mutex mu_;
  std::vector<Projectors*> free_;
  std::vector<std::unique_ptr<Projectors>> owned_;
};

/// Vertices: a node whose CAD faces include three of a vertex's faces, within the tolerance of it;
/// the nearest such node per vertex.
void place_on_vertices(const Shape::Impl& s, const mesh::Mesh& m, const BoundaryNodes& b,
                       const std::vector<std::vector<int>>& vertex_faces, const SnapOptions& opt, Targets& t) {
  std::map<int, std::pair<double, int>> best;  // vertex -> (distance, node)
  for (int v : b.nodes) {
    if (b.cand[v].size() < 3 || (!opt.face_only.empty() && opt.face_only[v])) continue;
    const Eigen::Vector3d p = m.V.row(v).transpose();
    for (int x = 1; x <= s.vertices.Extent(); ++x) {
      if (intersect_count(vertex_faces[x], b.cand[v]) < 3) continue;
      const gp_Pnt q = BRep_Tool::Pnt(TopoDS::Vertex(s.vertices(x)));
      const double d = (p - Eigen::Vector3d(q.X(), q.Y(), q.Z())).norm();
      if (d > opt.edge_tolerance * b.shortest[v]) continue;
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
    t.point.row(v) << q.X(), q.Y(), q.Z();
    t.placed[v] = 1;
    t.r.kind[v] = SnapKind::Vertex;
    t.r.entity[v] = dx.second;
  }
}

/// Edges: the nodes not on a vertex batched per candidate edge (an edge between two of the node's
/// faces); each keeps the nearest edge within the tolerance.
void place_on_edges(const Shape& shape, const mesh::Mesh& m, const BoundaryNodes& b, const FacePairEdges& pair_edges,
                    const SnapOptions& opt, Targets& t) {
  std::map<int, std::vector<int>> per_edge;
  for (int v : b.nodes) {
    if (t.placed[v] || b.cand[v].size() < 2 || (!opt.face_only.empty() && opt.face_only[v])) continue;
    std::set<int> edges;
    for (auto a = b.cand[v].begin(); a != b.cand[v].end(); ++a)
      for (auto c = std::next(a); c != b.cand[v].end(); ++c) {
        auto it = pair_edges.find({*a, *c});
        if (it != pair_edges.end()) edges.insert(it->second.begin(), it->second.end());
      }
    for (int e : edges) per_edge[e].push_back(v);
  }
  std::vector<double> best(m.num_nodes(), std::numeric_limits<double>::infinity());
  for (const auto& [e, nodes] : per_edge) {
    check_interrupt("snap");
    Eigen::MatrixXd P(nodes.size(), 3);
    for (size_t i = 0; i < nodes.size(); ++i) P.row(i) = m.V.row(nodes[i]);
    const Projection pr = project_to_edge(shape, e, P);
    for (size_t i = 0; i < nodes.size(); ++i) {
      const int v = nodes[i];
      if (pr.distance(i) < best[v] && pr.distance(i) <= opt.edge_tolerance * b.shortest[v]) {
        best[v] = pr.distance(i);
        t.point.row(v) = pr.points.row(i);
        t.r.kind[v] = SnapKind::Edge;
        t.r.entity[v] = e;
      }
    }
  }
  for (int v : b.nodes)
    if (t.r.kind[v] == SnapKind::Edge) t.placed[v] = 1;
}

/// Faces: the nodes on no vertex or edge go onto the nearest of their CAD faces, trimmed. A face's
/// nodes are taken in Morton order of their position, each searched locally from the previous one's
/// parameters (FaceProjector::nearest_from) when that node is near; the local result is kept only
/// when no nearer than the previous node's point, otherwise the whole face is searched.
void place_on_faces(const mesh::Mesh& m, const BoundaryNodes& b, Projectors& projectors, Targets& t) {
  std::map<int, std::vector<int>> per_face;
  for (int v : b.nodes)
    if (!t.placed[v])
      for (int f : b.cand[v]) per_face[f].push_back(v);
  if (per_face.empty()) return;
  // Morton keys on a 2^20 grid over the boundary's box.
  Eigen::RowVector3d lo = m.V.row(b.nodes[0]), hi = lo;
  for (int v : b.nodes) lo = lo.cwiseMin(m.V.row(v)), hi = hi.cwiseMax(m.V.row(v));
  const double extent = std::max((hi - lo).maxCoeff(), 1e-300);
  auto morton = [&](int v) {
    uint64_t key = 0;
    uint32_t c[3];
    for (int k = 0; k < 3; ++k) c[k] = static_cast<uint32_t>(std::min(1048575.0, (m.V(v, k) - lo(k)) / extent * 1048575.0));
    for (int bit = 19; bit >= 0; --bit)
      for (int k = 0; k < 3; ++k) key = (key << 1) | ((c[k] >> bit) & 1u);
    return key;
  };
  std::vector<uint64_t> key(m.num_nodes(), 0);
  for (int v : b.nodes) key[v] = morton(v);
  std::vector<double> best(m.num_nodes(), std::numeric_limits<double>::infinity());
  for (auto& [f, nodes] : per_face) {
    std::sort(nodes.begin(), nodes.end(), [&](int x, int y) { return key[x] < key[y]; });
    FaceProjector& face = projectors.face(f);
    int previous = -1;
    gp_Pnt previous_q;
    gp_Pnt2d previous_uv;
    for (int v : nodes) {
      check_interrupt("snap");
      const gp_Pnt p(m.V(v, 0), m.V(v, 1), m.V(v, 2));
      gp_Pnt q;
      gp_Pnt2d uv;
      double d = std::numeric_limits<double>::infinity();
      const bool near = previous >= 0 && (m.V.row(v) - m.V.row(previous)).norm() <= 3 * b.shortest[v];
      if (!near || !face.nearest_local(p, previous_uv, q, d, uv) || d > p.Distance(previous_q) + 1e-12)
        face.nearest(p, q, d, uv);
      if (!std::isfinite(d)) continue;
      previous = v, previous_q = q, previous_uv = uv;
      if (d < best[v]) {
        best[v] = d;
        t.point.row(v) << q.X(), q.Y(), q.Z();
        t.r.kind[v] = SnapKind::Face;
        t.r.entity[v] = f;
        t.uv[v] = uv;
      }
    }
  }
}

// The mesh restored after moving the boundary to the B-rep in `steps` steps (see SnapOptions),
// with the worst SJ and inverted cells right after the last move.
struct Restored {
  mesh::Mesh mesh;
  double worst_snapped = 0;
  int inverted_snapped = 0;
};

/// The restoration of the interior after the boundary nodes move to their targets: improve with
/// the boundary held, or sliding on its CAD faces and edges (SnapOptions::slide). The faces and
/// edge curves the sliding nodes project onto are built once per thread, on first use, for all
/// runs; each face or edge node starts its projection from where its last one ended (its own entry).
class Restoration {
 public:
  Restoration(const mesh::Mesh& m, const std::vector<int>& boundary, const Targets& target, const SnapOptions& opt,
              const Shape::Impl& s, Projectors& projectors)
      : m_(m), boundary_(boundary), target_(target.point), r_(target.r), opt_(opt), s_(s), projectors_(s, projectors),
        uv_(m.num_nodes()), has_uv_(m.num_nodes(), 0), t_(m.num_nodes(), 0.0), has_t_(m.num_nodes(), 0) {
    for (const auto& [v, uv] : target.uv) uv_[v] = uv, has_uv_[v] = 1;
  }

  /// Whether the options ask for a restoration at all (otherwise the nodes only move).
  bool enabled() const { return opt_.smooth > 0 || opt_.optimize > 0; }

  /// The boundary moved in `steps` equal steps, the interior restored with the boundary held after
  /// each but the last, then restored once more, every cell that gets worse kept at or above `floor`.
  Restored run(int steps, double floor) {
    const bool restore = enabled();
    Restored out;
    mesh::Mesh w = m_;
    const Eigen::MatrixXd start = m_.V;
    for (int k = 1; restore && k < steps; ++k) {
      const double a = static_cast<double>(k) / steps;
      optimize::ImproveOptions io;
      io.optimised_at = w.V;  // the input, or the restoration of the step before
      for (int v : boundary_) w.V.row(v) = start.row(v) + a * (target_.row(v) - start.row(v));
      io.smooth = opt_.smooth;
      io.optimize = opt_.optimize;
      io.floor = floor;
      io.fixed_nodes = boundary_;
      io.threads = opt_.threads;
      w = optimize::improve(w, io).mesh;
    }
    Eigen::MatrixXd optimised = restore ? w.V : Eigen::MatrixXd();
    for (int v : boundary_) w.V.row(v) = target_.row(v);
    out.worst_snapped = worst_sj(w, &out.inverted_snapped);
    if (restore) {
      optimize::ImproveOptions io;
      io.optimised_at = std::move(optimised);
      io.smooth = opt_.smooth;
      io.optimize = opt_.optimize;
      io.floor = floor;
      io.mean_after = true;  // the smoothing costs the mean improve reached
      io.max_edge_ratio = opt_.max_edge_ratio;
      io.threads = opt_.threads;
      for (int v : boundary_)
        if (!opt_.slide || r_.kind[v] == SnapKind::Vertex) io.fixed_nodes.push_back(v);
      if (opt_.slide) {
        io.project = [this, &w](int v, const Eigen::Vector3d& x) -> Eigen::Vector3d {
          Eigen::Vector3d q;
          return project(v, x, q) ? q : Eigen::Vector3d(w.V.row(v).transpose());  // stays where it is
        };
        io.project_concurrent = true;  // a pool of projectors, and each node's own starting point
      }
      w = optimize::improve(w, io).mesh;
    }
    out.mesh = std::move(w);
    return out;
  }

  /// The distance from x to the CAD face, edge or vertex boundary node v was put on (infinity when
  /// the projection fails): at least its distance to the B-rep.
  double distance(int v, const Eigen::Vector3d& x) {
    Eigen::Vector3d q;
    return project(v, x, q) ? (q - x).norm() : std::numeric_limits<double>::infinity();
  }

 private:
  /// q: x projected onto the CAD face, edge or vertex node v was put on; false when that fails.
  bool project(int v, const Eigen::Vector3d& x, Eigen::Vector3d& out) {
    const gp_Pnt p(x(0), x(1), x(2));
    gp_Pnt q;
    double d = std::numeric_limits<double>::infinity();
    const int id = r_.entity[v];
    if (r_.kind[v] == SnapKind::Face) {
      const ProjectorPool::Lease projectors(projectors_);
      FaceProjector& face = (*projectors).face(id);
      // From the node's last place on the face: the optimiser's candidates lie near it.
      if (!has_uv_[v]) face.nearest(p, q, d, uv_[v]);
      else face.nearest_from(p, uv_[v], q, d, uv_[v]);
      has_uv_[v] = 1;
    } else if (r_.kind[v] == SnapKind::Edge) {
      const ProjectorPool::Lease projectors(projectors_);
      const EdgeCurve& curve = (*projectors).curve(id);
      const bool found = has_t_[v] ? nearest_on_edge_from(curve, p, t_[v], q, t_[v], d) : nearest_on_edge(curve, p, q, t_[v], d);
      if (!found) d = std::numeric_limits<double>::infinity();
      has_t_[v] = found;
    } else if (r_.kind[v] == SnapKind::Vertex) {
      q = BRep_Tool::Pnt(TopoDS::Vertex(s_.vertices(id)));
      d = 0;
    }
    if (!std::isfinite(d)) return false;
    out = Eigen::Vector3d(q.X(), q.Y(), q.Z());
    return true;
  }

  const mesh::Mesh& m_;
  const std::vector<int>& boundary_;
  const Eigen::MatrixXd& target_;
  const SnapResult& r_;
  const SnapOptions& opt_;
  const Shape::Impl& s_;
  ProjectorPool projectors_;
  std::vector<gp_Pnt2d> uv_;  // face nodes: parameters of their last projection (has_uv_)
  std::vector<char> has_uv_;
  std::vector<double> t_;  // edge nodes: parameter of their last projection (has_t_)
  std::vector<char> has_t_;
};

/// The restoration kept: the direct one; the progressive snap where the direct one leaves inverted
/// cells or ends below both the worst SJ before and `keep` (fewer inverted cells first, then the
/// better worst cell); then, where cells stay inverted, the restoration without the floor `keep`
/// if it does better.
Restored best_restoration(Restoration& restoration, double keep, double worst_before, const SnapOptions& opt) {
  const bool restore = restoration.enabled();
  char line[320];
  Restored best = restoration.run(1, keep);
  if (restore && opt.steps > 1) {
    // The progressive snap where the direct one costs quality below the bar: fewer inverted cells
    // first, then the better worst cell. Above it, a second whole restoration is not worth its time.
    int inv_best = 0;
    const double w_best = worst_sj(best.mesh, &inv_best);
    const double bar = keep > -2 ? keep : worst_before;  // keep: min(SnapOptions::keep, worst before)
    if (inv_best > 0 || w_best < bar - 1e-3) {
      Restored other = restoration.run(opt.steps, keep);
      int inv_other = 0;
      const double w_other = worst_sj(other.mesh, &inv_other);
      std::snprintf(line, sizeof line, "snap: direct worst SJ %.4f (%d inverted), in %d steps %.4f (%d inverted)", w_best,
                    inv_best, opt.steps, w_other, inv_other);
      say(opt, line);
      if (inv_other < inv_best || (inv_other == inv_best && w_other > w_best)) best = std::move(other);
    }
  }
  if (restore && keep > -2) {
    // The floor can stall untangling (its path may need good cells to give way): then without it.
    int inv_best = 0;
    const double w_best = worst_sj(best.mesh, &inv_best);
    if (inv_best > 0) {
      Restored other = restoration.run(1, -2);
      int inv_other = 0;
      const double w_other = worst_sj(other.mesh, &inv_other);
      std::snprintf(line, sizeof line, "snap: with the floor worst SJ %.4f (%d inverted), without %.4f (%d inverted)",
                    w_best, inv_best, w_other, inv_other);
      say(opt, line);
      if (inv_other < inv_best || (inv_other == inv_best && w_other > w_best)) best = std::move(other);
    }
  }
  return best;
}

/// Boundary nodes onto the CAD vertices, edges and faces their tessellation triangles name, then the
/// interior restored (see snap_to_brep).
SnapResult snap(const Shape& shape, const mesh::Mesh& input, const mesh::SurfaceMesh& tess, const SnapOptions& opt) {
  const Shape::Impl& s = shape.impl();
  check_input(s, input, tess);
  if (!opt.face_only.empty() && static_cast<int>(opt.face_only.size()) != input.num_nodes())
    throw InputError(s.source, 0, "snap_to_brep: face_only has " + std::to_string(opt.face_only.size()) + " entries for " +
                                      std::to_string(input.num_nodes()) + " mesh nodes");

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
  const BoundaryNodes b = boundary_nodes(m, tess);
  const std::vector<int>& boundary = b.nodes;
  rep.boundary_nodes = static_cast<int>(boundary.size());
  if (boundary.empty()) {
    r.mesh = std::move(m);
    r.quality = quality::quality_report(r.mesh);
    return r;
  }
  // The projection: vertices first, then edges, then faces.
  const std::vector<std::vector<int>> edge_faces = faces_of(s, TopAbs_EDGE, s.edges);
  const std::vector<std::vector<int>> vertex_faces = faces_of(s, TopAbs_VERTEX, s.vertices);
  const FacePairEdges pair_edges = edges_between_faces(s, edge_faces);
  Targets target{m.V, std::vector<char>(nn, 0), r, {}};
  Projectors projectors(s);
  place_on_vertices(s, m, b, vertex_faces, opt, target);
  place_on_edges(shape, m, b, pair_edges, opt, target);
  place_on_faces(m, b, projectors, target);
  r.faces.assign(nn, {});
  for (int v : boundary) {
    const int e = r.entity[v];
    if (r.kind[v] == SnapKind::Face) r.faces[v] = {e};
    else if (r.kind[v] == SnapKind::Edge && e > 0 && e < static_cast<int>(edge_faces.size())) r.faces[v] = edge_faces[e];
    else if (r.kind[v] == SnapKind::Vertex && e > 0 && e < static_cast<int>(vertex_faces.size())) r.faces[v] = vertex_faces[e];
  }
  for (int v : boundary) {
    const double move = (target.point.row(v) - m.V.row(v)).norm();
    rep.max_move = std::max(rep.max_move, move);
    rep.max_before = std::max(rep.max_before, move);
    rep.mean_before += move / boundary.size();
    rep.face_nodes += r.kind[v] == SnapKind::Face;
    rep.edge_nodes += r.kind[v] == SnapKind::Edge;
    rep.vertex_nodes += r.kind[v] == SnapKind::Vertex;
  }
  rep.seconds_project = seconds_since(t0);

  // Restoration. Every cell that gets worse stays at or above min(keep, worst before the snap).
  const double keep = opt.keep < 0 ? -2.0 : std::min(opt.keep, rep.worst_sj_before);
  Restoration restoration(m, boundary, target, opt, s, projectors);
  const auto t1 = Clock::now();
  Restored best = best_restoration(restoration, keep, rep.worst_sj_before, opt);
  m = std::move(best.mesh);
  rep.worst_sj_snapped = best.worst_snapped;
  rep.inverted_snapped = best.inverted_snapped;
  char line[320];
  std::snprintf(line, sizeof line,
                "snap: %d boundary nodes onto %d faces, %d edges, %d vertices (largest move %.3g); worst SJ %.4f -> %.4f, "
                "%d inverted",
                rep.boundary_nodes, rep.face_nodes, rep.edge_nodes, rep.vertex_nodes, rep.max_move, rep.worst_sj_before,
                rep.worst_sj_snapped, rep.inverted_snapped);
  say(opt, line);
  rep.seconds_restore = seconds_since(t1);
  rep.worst_sj = worst_sj(m, &rep.inverted);

  for (int v : boundary) {
    const double d = restoration.distance(v, m.V.row(v).transpose());
    rep.max_after = std::max(rep.max_after, d);
    rep.mean_after += d / boundary.size();
  }
  r.quality = quality::quality_report(m, thread_count(opt.threads));
  r.mesh = std::move(m);
  std::snprintf(line, sizeof line,
                "snap: B-rep distance max %.3g -> %.3g (%.2e of the diagonal), mean %.3g -> %.3g; worst SJ %.4f, %d inverted",
                rep.max_before, rep.max_after, rep.diagonal > 0 ? rep.max_after / rep.diagonal : 0.0, rep.mean_before,
                rep.mean_after, rep.worst_sj, rep.inverted);
  say(opt, line);
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
