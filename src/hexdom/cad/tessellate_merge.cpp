#include "hexdom/cad/tessellate_merge.h"

#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include <map>
#include <queue>
#include <set>
#include <unordered_map>

#include "hexdom/cad/face_triangulation.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/edge_key.h"

namespace hexdom::cad {

namespace {

using mesh::remesh::Kind;
using mesh::remesh::RVertex;
using mesh::EdgeKey;

Eigen::Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

/// One face's triangulation and the map of its nodes into the merged vertices.
struct FaceNodes {
  const TopoDS_Face& face;
  int fi;                  ///< the face (0-based)
  const Handle(Poly_Triangulation)& T;
  const TopLoc_Location& loc;
  std::vector<int> g;      ///< per node of T (1-based): its vertex in Merged::V, -1 while unset
  std::set<EdgeKey> segments;  ///< its edges' segments (undirected) in merged vertices
  std::set<EdgeKey> seam_segments;
  Eigen::Vector3d node(int i) const { return vec(T->Node(i).Transformed(loc.Transformation())); }
};

/// Maps the nodes of edge E's polygon on face `f` into the merged vertices: a degenerated edge's
/// onto its vertex; an edge met for the first time gets its nodes (its end vertices, then new
/// curve vertices, or face vertices on a seam); an edge met before reuses them, reversed when the
/// polygon runs the other way. Returns "" or why the face's triangulation cannot be used; edges
/// whose nodes it made are added to `made`.
std::string map_edge_nodes(const WorkShape& w, const TopoDS_Edge& E, FaceNodes& f, Merged& out, std::vector<int>& made) {
  const int ei = w.edges.FindIndex(E) - 1;
  const Handle(Poly_PolygonOnTriangulation)& poly = BRep_Tool::PolygonOnTriangulation(E, f.T, f.loc);
  if (poly.IsNull()) return "BRepMesh left Edge" + std::to_string(ei + 1) + " without nodes on it";
  const TColStd_Array1OfInteger& nodes = poly->Nodes();
  const int n = nodes.Length(), lo = nodes.Lower();
  for (int k = 0; k < n; ++k)
    if (nodes(lo + k) < 1 || nodes(lo + k) > f.T->NbNodes())
      return "BRepMesh's polygon of Edge" + std::to_string(ei + 1) + " names a node the face does not have";
  if (BRep_Tool::Degenerated(E)) {
    const int vi = w.vertices.FindIndex(TopExp::FirstVertex(E)) - 1;
    for (int k = 0; k < n; ++k) f.g[nodes(lo + k)] = vi;
    return "";
  }
  const bool seam = BRep_Tool::IsClosed(E, f.face);
  const Handle(TColStd_HArray1OfReal)& params = poly->Parameters();
  auto param = [&](int k) { return params.IsNull() ? static_cast<double>(k) : params->Value(params->Lower() + k); };
  std::vector<int>& en = out.edge_nodes[ei];
  bool reversed = false;
  if (en.empty()) {
    if (n < 2) return "BRepMesh gave Edge" + std::to_string(ei + 1) + " fewer than 2 nodes";
    made.push_back(ei);
    en.assign(n, -1);
    std::vector<double>& ep = out.edge_params[ei];
    for (int k = 0; k < n; ++k) ep.push_back(param(k));
    TopoDS_Vertex v1, v2;
    TopExp::Vertices(E, v1, v2);
    const int i1 = w.vertices.FindIndex(v1) - 1, i2 = w.vertices.FindIndex(v2) - 1;
    const Eigen::Vector3d p0 = f.node(nodes(lo));
    const bool first_is_v1 = (p0 - out.V[i1].p).norm() <= (p0 - out.V[i2].p).norm();
    en[0] = first_is_v1 ? i1 : i2;
    en[n - 1] = first_is_v1 ? i2 : i1;
    for (int k = 1; k < n - 1; ++k) {
      RVertex v;
      v.p = f.node(nodes(lo + k));
      if (seam) {
        v.kind = Kind::Face;
        v.owner = f.fi;
        if (f.T->HasUVNodes()) {
          const gp_Pnt2d uv = f.T->UVNode(nodes(lo + k));
          v.uv = {uv.X(), uv.Y()};
          v.has_uv = true;
        }
      } else {
        v.kind = Kind::Curve;
        v.owner = ei;
        v.t = param(k);
      }
      en[k] = static_cast<int>(out.V.size());
      out.V.push_back(v);
    }
  } else {
    const std::vector<double>& ep = out.edge_params[ei];
    if (static_cast<int>(en.size()) != n)
      return "BRepMesh discretised Edge" + std::to_string(ei + 1) + " with " + std::to_string(n) + " nodes here and " +
             std::to_string(en.size()) + " in its other face";
    if (!params.IsNull() && n > 1 && std::abs(param(0) - ep[0]) > std::abs(param(0) - ep[n - 1])) reversed = true;
  }
  for (int k = 0; k < n; ++k) {
    int& slot = f.g[nodes(lo + k)];
    if (slot < 0) slot = en[reversed ? n - 1 - k : k];
    const int id = slot;
    if (k > 0) {
      const int a = f.g[nodes(lo + k - 1)];
      if (a != id) (seam ? f.seam_segments : f.segments).insert(mesh::undirected_edge(a, id));
    }
  }
  return "";
}

/// "" when `tris` (one face's triangles in merged vertices) form a proper patch: no directed edge
/// twice, every edge with one triangle is one of the face's edge segments, and every segment has a
/// triangle (a seam's, or a slit's inside the face, have one on each side).
std::string patch_problem(const std::vector<std::array<int, 3>>& tris, const FaceNodes& f) {
  std::unordered_map<EdgeKey, int> directed;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k)
      if (++directed[mesh::directed_edge(t[k], t[(k + 1) % 3])] > 1) return "its triangles overlap (an edge is used twice in one direction)";
  for (const auto& [key, n] : directed) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffff);
    if (!directed.count(mesh::directed_edge(b, a)) && !f.segments.count(mesh::undirected_edge(a, b)))
      return "its triangles leave a gap inside the face";
  }
  for (EdgeKey key : f.segments) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffff);
    if (!directed.count(mesh::directed_edge(a, b)) && !directed.count(mesh::directed_edge(b, a)))
      return "its triangles do not reach all of its edges";
  }
  return "";
}

/// Adds one face's BRepMesh triangulation: its edges' nodes through map_edge_nodes, its inner
/// nodes as new face vertices, its triangles (turned for a reversed face, degenerate ones dropped).
/// Returns "" or why the triangulation cannot be used, leaving `out` as it was.
std::string merge_face(const WorkShape& w, const TopoDS_Face& face, int fi, Merged& out) {
  TopLoc_Location loc;
  const Handle(Poly_Triangulation)& T = BRep_Tool::Triangulation(face, loc);
  if (T.IsNull() || T->NbTriangles() == 0) return "BRepMesh could not triangulate it";
  const size_t vertices_before = out.V.size();
  std::vector<int> made;
  auto undo = [&](const std::string& why) {
    out.V.resize(vertices_before);
    for (int e : made) out.edge_nodes[e].clear(), out.edge_params[e].clear();
    return why;
  };
  FaceNodes f{face, fi, T, loc, std::vector<int>(T->NbNodes() + 1, -1), {}, {}};
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const std::string why = map_edge_nodes(w, TopoDS::Edge(ex.Current()), f, out, made);
    if (!why.empty()) return undo(why);
  }
  std::vector<int>& g = f.g;
  for (int i = 1; i <= T->NbNodes(); ++i) {
    if (g[i] >= 0) continue;
    RVertex v;
    v.p = f.node(i);
    v.kind = Kind::Face;
    v.owner = fi;
    if (T->HasUVNodes()) {
      const gp_Pnt2d uv = T->UVNode(i);
      v.uv = {uv.X(), uv.Y()};
      v.has_uv = true;
    }
    g[i] = static_cast<int>(out.V.size());
    out.V.push_back(v);
  }
  const bool flip = face.Orientation() == TopAbs_REVERSED;
  std::vector<std::array<int, 3>> tris;
  int dropped = 0;
  for (int i = 1; i <= T->NbTriangles(); ++i) {
    int n1, n2, n3;
    T->Triangle(i).Get(n1, n2, n3);
    if (std::min({n1, n2, n3}) < 1 || std::max({n1, n2, n3}) > T->NbNodes()) return undo("BRepMesh's triangles name nodes it does not have");
    if (flip) std::swap(n2, n3);
    const std::array<int, 3> tri{g[n1], g[n2], g[n3]};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++dropped;
      continue;
    }
    tris.push_back(tri);
  }
  const std::string problem = patch_problem(tris, f);
  if (!problem.empty()) return undo("BRepMesh's triangles are not a proper patch: " + problem);
  out.dropped += dropped;
  for (const auto& t : tris) {
    out.F.push_back(t);
    out.face_of.push_back(fi);
  }
  return "";
}

/// Turns over the faces whose triangles run against their neighbours' across the shared edges:
/// in each connected shell, the faces are put in agreement from the first one on, and where that
/// turned over more triangles than it kept, the shell's turned and kept faces swap.
void orient_faces(const WorkShape& w, Merged& m) {
  const int nf = w.faces.Extent();
  std::unordered_map<EdgeKey, std::vector<std::pair<int, bool>>> edge_tris;  // undirected -> (triangle, a < b)
  for (size_t t = 0; t < m.F.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F[t][k], b = m.F[t][(k + 1) % 3];
      edge_tris[mesh::undirected_edge(a, b)].push_back({static_cast<int>(t), a < b});
    }
  std::map<std::pair<int, int>, std::pair<int, int>> votes;  // face pair -> (same direction, opposite)
  for (const auto& [key, uses] : edge_tris) {
    if (uses.size() != 2) continue;
    const int fa = m.face_of[uses[0].first], fb = m.face_of[uses[1].first];
    if (fa == fb) continue;
    auto& v = votes[{std::min(fa, fb), std::max(fa, fb)}];
    (uses[0].second == uses[1].second ? v.first : v.second) += 1;
  }
  std::vector<std::vector<std::pair<int, bool>>> adj(nf);  // neighbour, disagrees
  for (const auto& [pair, v] : votes) {
    const bool disagree = v.first > v.second;
    adj[pair.first].push_back({pair.second, disagree});
    adj[pair.second].push_back({pair.first, disagree});
  }
  std::vector<int> tri_count(nf, 0);
  for (int f : m.face_of) ++tri_count[f];
  std::vector<int> turn(nf, -1);
  for (int start = 0; start < nf; ++start) {
    if (turn[start] >= 0) continue;
    std::vector<int> shell{start};
    turn[start] = 0;
    std::queue<int> q;
    q.push(start);
    while (!q.empty()) {
      const int f = q.front();
      q.pop();
      for (auto [g, disagree] : adj[f])
        if (turn[g] < 0) {
          turn[g] = turn[f] ^ static_cast<int>(disagree);
          shell.push_back(g);
          q.push(g);
        }
    }
    long turned = 0, kept = 0;
    for (int f : shell) (turn[f] ? turned : kept) += tri_count[f];
    if (turned > kept)
      for (int f : shell) turn[f] ^= 1;
  }
  for (int f = 0; f < nf; ++f)
    if (turn[f] == 1)
      m.repairs.push_back(w.face_name(f) + " turned over: its triangles ran against its neighbours' (the B-rep's shell "
                                           "orients it the other way)");
  for (size_t t = 0; t < m.F.size(); ++t)
    if (turn[m.face_of[t]] == 1) std::swap(m.F[t][1], m.F[t][2]);
}

}  // namespace

std::string closed_manifold_problem(const Eigen::MatrixXi& F, int* triangle) {
  if (triangle) *triangle = -1;
  std::unordered_map<EdgeKey, int> directed;
  directed.reserve(3 * F.rows());
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3);
      if (triangle) *triangle = t;
      if (a == b) return "triangle " + std::to_string(t + 1) + " is degenerate";
      if (++directed[mesh::directed_edge(a, b)] > 1)
        return "edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ") is used twice in one direction";
    }
  if (triangle) *triangle = -1;
  for (const auto& [k, n] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
    if (!directed.count(mesh::directed_edge(b, a))) {
      if (triangle)
        for (int t = 0; t < F.rows() && *triangle < 0; ++t)
          for (int j = 0; j < 3; ++j)
            if (F(t, j) == a && F(t, (j + 1) % 3) == b) *triangle = t;
      return "edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ") has one triangle (open)";
    }
  }
  return "";
}

// Merge the face triangulations through the topology: CAD vertices first, then the nodes of
// each edge once (a seam's two polygons and an edge's polygon in each of its faces map to the
// same vertices), then each face's inner nodes. Faces whose BRepMesh triangulation cannot be used
// are triangulated here afterwards, from their edges' nodes.
Merged merge_triangulations(const WorkShape& w, const Sizes& z, const TessellateOptions& options) {
  Merged out;
  out.V.resize(w.vertices.Extent());
  for (int i = 0; i < w.vertices.Extent(); ++i) {
    out.V[i].p = vec(BRep_Tool::Pnt(TopoDS::Vertex(w.vertices(i + 1))));
    out.V[i].kind = Kind::Corner;
    out.V[i].owner = i;
  }
  out.edge_nodes.resize(w.edges.Extent());
  out.edge_params.resize(w.edges.Extent());
  std::vector<char> seen(w.faces.Extent(), 0);
  std::vector<std::pair<int, std::string>> deferred;  // faces to triangulate here, and why
  for (TopExp_Explorer fx(w.shape, TopAbs_FACE); fx.More(); fx.Next()) {
    const TopoDS_Face face = TopoDS::Face(fx.Current());
    const int fi = w.faces.FindIndex(face) - 1;
    if (seen[fi]) continue;
    seen[fi] = 1;
    const std::string why = options.brepmesh_faces ? merge_face(w, face, fi, out) : std::string("asked for");
    if (!why.empty()) deferred.push_back({fi, why});
  }
  for (const auto& [fi, why] : deferred) {
    triangulate_face(w, fi, z, out);
    if (options.brepmesh_faces) out.repairs.push_back(w.face_name(fi) + " triangulated by hexdom: " + why);
  }
  orient_faces(w, out);
  Eigen::MatrixXi F0(out.F.size(), 3);
  for (size_t t = 0; t < out.F.size(); ++t) F0.row(t) << out.F[t][0], out.F[t][1], out.F[t][2];
  int at = -1;
  const std::string problem = closed_manifold_problem(F0, &at);
  if (!problem.empty())
    throw MeshingError(w.source + ": the B-rep's initial triangulation is not closed" +
                       (at >= 0 ? " at " + w.face_name(out.face_of[at]) : std::string()) + ": " + problem);
  if (options.log) {
    for (const std::string& r : out.repairs) options.log(1, w.source + ": " + r);
    options.log(0, "BRepMesh start: " + std::to_string(out.F.size()) + " triangles, " + std::to_string(out.V.size()) +
                       " vertices (" + std::to_string(out.dropped) + " degenerate dropped)");
  }
  return out;
}

}  // namespace hexdom::cad
