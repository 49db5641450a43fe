#include "hexdom/mesh/remesh_triangles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "hexdom/common/disjoint_sets.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/remesh_surface.h"

namespace hexdom::mesh {

namespace {

using remesh::Kind;
using remesh::RVertex;


/// A polyline where two faces meet, from corner to corner (or a closed loop).
struct Chain {
  std::vector<int> vertices;  ///< input vertex ids, first == last for a loop
  double length = 0;
};

/// The input triangles as the remesher's geometry: faces are the face ids' triangles, curves the
/// chains of feature edges.
class TriangleGeometry : public remesh::RemeshGeometry {
 public:
  TriangleGeometry(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& face, int nfaces,
                   std::vector<Chain> chains, std::vector<double> corner_size, double max_size)
      : V_(V), chains_(std::move(chains)), corner_size_(std::move(corner_size)), max_size_(max_size) {
    std::vector<std::vector<int>> rows(nfaces);
    for (int t = 0; t < F.rows(); ++t) rows[face[t]].push_back(t);
    planar_.assign(nfaces, 1);
    for (int f = 0; f < nfaces; ++f) {
      Eigen::MatrixXi Ff(rows[f].size(), 3);
      Eigen::Vector3d n0 = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < rows[f].size(); ++i) {
        Ff.row(i) = F.row(rows[f][i]);
        const Eigen::Vector3d a = V.row(F(rows[f][i], 0)), b = V.row(F(rows[f][i], 1)), c = V.row(F(rows[f][i], 2));
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        if (i == 0) n0 = n;
        else if (n.dot(n0) < 1 - 1e-10) planar_[f] = 0;
      }
      projectors_.push_back(std::make_unique<TriangleProjector>(V, Ff));
    }
  }

  bool project_to_face(RVertex& v, const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d q = projectors_[v.owner]->project(p);
    if (!q.allFinite()) return false;
    v.p = q;
    return true;
  }

  bool project_to_curve(RVertex& v, const Eigen::Vector3d& p) const override {
    const Chain& c = chains_[v.owner];
    double best = std::numeric_limits<double>::infinity(), arc = 0, t = 0;
    Eigen::Vector3d q = p;
    for (size_t i = 0; i + 1 < c.vertices.size(); ++i) {
      const Eigen::Vector3d a = V_.row(c.vertices[i]), b = V_.row(c.vertices[i + 1]);
      const Eigen::Vector3d x = closest_point_on_segment(p, a, b);
      const double d = (x - p).squaredNorm();
      if (d < best) best = d, q = x, t = arc + (x - a).norm();
      arc += (b - a).norm();
    }
    if (!std::isfinite(best)) return false;
    v.p = q;
    v.t = t;
    return true;
  }

  double size_at(const RVertex& v) const override {
    if (v.kind == Kind::Corner) return std::min(max_size_, corner_size_[v.owner]);
    if (v.kind == Kind::Curve) return std::min(max_size_, chains_[v.owner].length);
    return max_size_;
  }

  bool is_planar(int f) const override { return planar_[f] != 0; }

 private:
  const Eigen::MatrixXd& V_;
  std::vector<Chain> chains_;
  std::vector<double> corner_size_;
  double max_size_;
  std::vector<char> planar_;
  std::vector<std::unique_ptr<TriangleProjector>> projectors_;
};

std::string vertex_pair(int a, int b) { return "(" + std::to_string(a + 1) + ", " + std::to_string(b + 1) + ")"; }

/// The target edge length: the option's, or for 0 the bounding-box diagonal / 30. InputError for
/// a size that is negative or not finite, or a surface without extent.
double target_size(const Eigen::MatrixXd& V, const RemeshTrianglesOptions& options) {
  double size = options.size;
  if (!(size >= 0) || !std::isfinite(size)) throw InputError("remesh: the size must be positive");
  if (size == 0) size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm() / 30.0;
  if (!(size > 0)) throw InputError("remesh: the surface has no extent");
  return size;
}

/// The triangle of each directed edge. InputError unless the surface is closed, 2-manifold and
/// consistently oriented (every directed edge once, its reverse once), with valid vertex indices
/// and no zero-area triangle.
std::unordered_map<EdgeKey, int> directed_edges(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const int nv = static_cast<int>(V.rows()), nt = static_cast<int>(F.rows());
  std::unordered_map<EdgeKey, int> directed;  // directed edge -> triangle
  directed.reserve(3 * nt);
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3);
      if (a < 0 || a >= nv) throw InputError("remesh: triangle " + std::to_string(t + 1) + " names vertex " +
                                             std::to_string(a + 1) + " of " + std::to_string(nv));
      if (a == b) throw InputError("remesh: triangle " + std::to_string(t + 1) + " is degenerate");
      if (!directed.emplace(directed_edge(a, b), t).second)
        throw InputError("remesh: edge " + vertex_pair(a, b) +
                         " is used twice in one direction (non-manifold or inconsistently oriented)");
    }
    const Eigen::Vector3d a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    if ((b - a).cross(c - a).norm() == 0) throw InputError("remesh: triangle " + std::to_string(t + 1) + " has zero area");
  }
  for (const auto& [k, t] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
    if (!directed.count(directed_edge(b, a)))
      throw InputError("remesh: the surface is open: edge " + vertex_pair(a, b) + " has one triangle");
  }
  return directed;
}

/// Feature edges, the faces they bound and the corners where they meet.
struct Features {
  std::vector<int> face;                       ///< per triangle: its face (region)
  std::vector<int> ids;                        ///< per face: its input id
  std::vector<std::vector<int>> feature_nb;    ///< per vertex: its neighbours along feature edges
  std::vector<std::vector<int>> faces_at;      ///< per vertex: the faces around it
  std::vector<char> corner;                    ///< per vertex
};

// Feature edges: between two face ids, or (feature angle) sharper than the angle. The faces the
// remesher works on are the regions of one id that feature edges bound, so that a sharp edge
// inside a part is a curve between two faces, as a CAD edge is.
Features find_features(const SurfaceMesh& s, const std::unordered_map<EdgeKey, int>& directed, double cos_feature) {
  const Eigen::MatrixXd& V = s.V;
  const Eigen::MatrixXi& F = s.F;
  const int nv = static_cast<int>(V.rows()), nt = static_cast<int>(F.rows());
  auto unit_normal = [&](int t) -> Eigen::Vector3d {
    const Eigen::Vector3d a = V.row(F(t, 0)), b = V.row(F(t, 1)), c = V.row(F(t, 2));
    return (b - a).cross(c - a).normalized();
  };
  std::vector<std::pair<int, int>> feature_edges;
  DisjointSets smooth(nt);  // triangles joined across edges that are not features
  for (const auto& [k, t] : directed) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffff);
    if (a > b) continue;
    const int u = directed.at(directed_edge(b, a));
    if (s.patch(t) != s.patch(u) || unit_normal(t).dot(unit_normal(u)) < cos_feature)
      feature_edges.emplace_back(a, b);
    else
      smooth.unite(t, u);
  }
  Features ft;
  ft.face.assign(nt, -1);  // region per triangle; the input id per region
  {
    std::unordered_map<int, int> region;
    for (int t = 0; t < nt; ++t) {
      auto [it, fresh] = region.emplace(smooth.find(t), static_cast<int>(ft.ids.size()));
      if (fresh) ft.ids.push_back(s.patch(t));
      ft.face[t] = it->second;
    }
  }
  ft.feature_nb.resize(nv);
  for (const auto& [a, b] : feature_edges) ft.feature_nb[a].push_back(b), ft.feature_nb[b].push_back(a);
  ft.faces_at.resize(nv);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      auto& fa = ft.faces_at[F(t, k)];
      if (std::find(fa.begin(), fa.end(), ft.face[t]) == fa.end()) fa.push_back(ft.face[t]);
    }
  ft.corner.assign(nv, 0);
  for (int v = 0; v < nv; ++v) {
    const std::vector<int>& nb = ft.feature_nb[v];
    ft.corner[v] = (!nb.empty() && nb.size() != 2) || ft.faces_at[v].size() >= 3;
    if (!ft.corner[v] && nb.size() == 2 && cos_feature > -2) {
      const Eigen::Vector3d in = (V.row(v) - V.row(nb[0])).normalized();
      const Eigen::Vector3d out = (V.row(nb[1]) - V.row(v)).normalized();
      ft.corner[v] = in.dot(out) < cos_feature;
    }
  }
  return ft;
}

// Chains from corner to corner, then the loops that have no corner (one of their vertices
// becomes one).
std::vector<Chain> feature_chains(const Eigen::MatrixXd& V, Features& ft) {
  const int nv = static_cast<int>(V.rows());
  const std::vector<std::vector<int>>& feature_nb = ft.feature_nb;
  std::vector<char>& corner = ft.corner;
  std::vector<Chain> chains;
  std::unordered_map<EdgeKey, int> edge_chain;  // undirected (min, max) -> chain
  auto walk = [&](int start, int next) {
    Chain c;
    c.vertices = {start};
    int prev = start, cur = next;
    edge_chain[undirected_edge(prev, cur)] = static_cast<int>(chains.size());
    while (true) {
      c.length += (V.row(cur) - V.row(prev)).norm();
      c.vertices.push_back(cur);
      if (corner[cur] || cur == start) break;
      const int nxt = feature_nb[cur][0] == prev ? feature_nb[cur][1] : feature_nb[cur][0];
      prev = cur, cur = nxt;
      edge_chain[undirected_edge(prev, cur)] = static_cast<int>(chains.size());
    }
    chains.push_back(std::move(c));
  };
  for (int v = 0; v < nv; ++v)
    if (corner[v])
      for (int w : feature_nb[v])
        if (!edge_chain.count(undirected_edge(v, w))) walk(v, w);
  for (int v = 0; v < nv; ++v)
    for (int w : feature_nb[v])
      if (!edge_chain.count(undirected_edge(v, w))) {
        corner[v] = 1;
        walk(v, w);
      }
  return chains;
}

/// The input vertices as the remesher's: corners (each with the length of its shortest chain),
/// curve vertices (chain and arc length along it) and face vertices.
struct Vertices {
  std::vector<RVertex> RV;
  std::vector<double> corner_size;  ///< per corner
};

Vertices remesh_vertices(const Eigen::MatrixXd& V, const Features& ft, const std::vector<Chain>& chains) {
  const int nv = static_cast<int>(V.rows());
  Vertices out;
  std::vector<RVertex>& RV = out.RV;
  std::vector<double>& corner_size = out.corner_size;
  std::vector<int> corner_id(nv, -1);
  RV.resize(nv);
  for (int v = 0; v < nv; ++v) {
    RV[v].p = V.row(v);
    if (ft.corner[v]) {
      corner_id[v] = static_cast<int>(corner_size.size());
      corner_size.push_back(std::numeric_limits<double>::infinity());
      RV[v].kind = Kind::Corner;
      RV[v].owner = corner_id[v];
    } else if (!ft.feature_nb[v].empty()) {
      RV[v].kind = Kind::Curve;
    } else {
      RV[v].kind = Kind::Face;
      RV[v].owner = ft.faces_at[v][0];
    }
  }
  for (int c = 0; c < static_cast<int>(chains.size()); ++c) {
    const Chain& ch = chains[c];
    double arc = 0;
    for (size_t i = 0; i < ch.vertices.size(); ++i) {
      const int v = ch.vertices[i];
      if (i > 0) arc += (V.row(v) - V.row(ch.vertices[i - 1])).norm();
      if (RV[v].kind == Kind::Curve) RV[v].owner = c, RV[v].t = arc;
      else corner_size[corner_id[v]] = std::min(corner_size[corner_id[v]], ch.length);
    }
  }
  return out;
}

}  // namespace

SurfaceMesh remesh_triangles(const SurfaceMesh& input, const RemeshTrianglesOptions& options) {
  const int nt = static_cast<int>(input.F.rows());
  if (nt == 0) throw InputError("remesh: the surface has no triangles");
  if (input.patch.size() != nt)
    throw InputError("remesh: " + std::to_string(input.patch.size()) + " face ids for " + std::to_string(nt) + " triangles");
  // Checked as given (errors name its vertices), then without the vertices no triangle uses.
  std::unordered_map<EdgeKey, int> directed = directed_edges(input.V, input.F);
  const SurfaceMesh s = drop_unused_vertices(input);
  if (s.V.rows() != input.V.rows()) directed = directed_edges(s.V, s.F);
  const Eigen::MatrixXd& V = s.V;
  const Eigen::MatrixXi& F = s.F;
  const double size = target_size(V, options);

  const double cos_feature = options.feature_angle > 0 ? std::cos(options.feature_angle * 3.14159265358979323846 / 180) : -2;
  Features ft = find_features(s, directed, cos_feature);
  const std::vector<Chain> chains = feature_chains(V, ft);
  Vertices rv = remesh_vertices(V, ft, chains);
  const std::vector<int>& face = ft.face;
  const std::vector<int>& ids = ft.ids;
  const std::vector<double>& corner_size = rv.corner_size;

  std::vector<std::array<int, 3>> RF(nt);
  for (int t = 0; t < nt; ++t) RF[t] = {F(t, 0), F(t, 1), F(t, 2)};
  const int nfaces = static_cast<int>(ids.size());
  TriangleGeometry geometry(V, F, face, nfaces, chains, corner_size, size);
  remesh::RemeshParams rp;
  rp.max_size = size;
  rp.iterations = options.iterations;
  rp.log = options.log;
  remesh::SurfaceRemesher remesher(std::move(rv.RV), RF, face, geometry, rp);
  for (int c = 0; c < static_cast<int>(chains.size()); ++c)
    if (chains[c].vertices.size() == 2) remesher.set_corner_edge(chains[c].vertices[0], chains[c].vertices[1], c);
  remesher.run();

  SurfaceMesh out;
  Eigen::VectorXi f;
  remesher.extract(out.V, out.F, f);
  out.patch.resize(f.size());
  for (Eigen::Index t = 0; t < f.size(); ++t) out.patch(t) = ids[f(t)];
  if (options.log)
    options.log(0, "remesh: " + std::to_string(nt) + " -> " + std::to_string(out.F.rows()) + " triangles of about " +
                       std::to_string(size) + " on " + std::to_string(nfaces) + " faces, " +
                       std::to_string(chains.size()) + " curves, " + std::to_string(corner_size.size()) + " corners");
  return out;
}

}  // namespace hexdom::mesh
