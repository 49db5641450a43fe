#include "hexdom/polycube/boundary_graph.h"

#include <algorithm>
#include <string>
#include <utility>

#include "hexdom/common/error.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/surface_check.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::polycube {

namespace {

using mesh::EdgeKey;

struct HalfEdge {
  int region, to, across;
  bool walked = false;
};

/// A curve as one region's loop runs it (that region on its left).
struct Directed {
  int left, right;
  std::vector<int> vertices;
  bool closed;
};

void flood_regions(const mesh::SurfaceMesh& s, const Eigen::MatrixXi& TT, BoundaryGraph& g) {
  const int nf = static_cast<int>(s.F.rows());
  g.region = Eigen::VectorXi::Constant(nf, -1);
  for (int f0 = 0; f0 < nf; ++f0) {
    if (g.region(f0) >= 0) continue;
    const int r = g.num_regions();
    g.label.push_back(s.patch(f0));
    g.triangles.emplace_back();
    std::vector<int> stack{f0};
    g.region(f0) = r;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      g.triangles[r].push_back(f);
      for (int k = 0; k < 3; ++k) {
        const int h = TT(f, k);
        if (h >= 0 && g.region(h) < 0 && s.patch(h) == s.patch(f)) {
          g.region(h) = r;
          stack.push_back(h);
        }
      }
    }
  }
}

/// Corners and pinches from the regions around each vertex (walked as a fan: the surface is closed).
void find_corners(const mesh::SurfaceMesh& s, const Eigen::MatrixXi& TT, BoundaryGraph& g) {
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  std::vector<int> some_tri(nv, -1);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) some_tri[s.F(f, k)] = f;
  g.corner_of = Eigen::VectorXi::Constant(nv, -1);
  std::vector<int> fan, distinct;
  for (int v = 0; v < nv; ++v) {
    if (some_tri[v] < 0) continue;
    fan.clear();
    int f = some_tri[v];
    do {
      fan.push_back(f);
      int k = 0;
      while (s.F(f, k) != v) ++k;
      f = TT(f, (k + 2) % 3);  // across edge (F(f, k + 2), v): the next triangle around v
    } while (f != some_tri[v] && fan.size() <= static_cast<size_t>(nf));
    int changes = 0;
    distinct.clear();
    for (size_t i = 0; i < fan.size(); ++i) {
      const int a = g.region(fan[i]), b = g.region(fan[(i + 1) % fan.size()]);
      if (a != b) ++changes;
      if (std::find(distinct.begin(), distinct.end(), a) == distinct.end()) distinct.push_back(a);
    }
    if (changes >= 3) {
      g.corner_of(v) = static_cast<int>(g.corners.size());
      g.corners.push_back(v);
      g.corner_regions.push_back(static_cast<int>(distinct.size()));
    }
    if (changes > 0 && changes > static_cast<int>(distinct.size())) g.pinches.push_back(v);
  }
}

/// Every curve once per side: walked from the corners (ascending), then the closed ones.
std::vector<Directed> walk_curves(const mesh::SurfaceMesh& s, const Eigen::MatrixXi& TT, const BoundaryGraph& g) {
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  std::vector<std::vector<HalfEdge>> out(nv);  // boundary half-edges (region on the left) leaving each vertex
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int h = TT(f, k);
      if (g.region(h) != g.region(f)) out[s.F(f, k)].push_back({g.region(f), s.F(f, (k + 1) % 3), g.region(h)});
    }
  // Each directed boundary edge is one triangle's, so it is in one list once: walked marks it there.
  std::vector<Directed> directed;
  auto walk = [&](int v0, HalfEdge& e0, bool closed) {
    Directed d{e0.region, e0.across, {v0, e0.to}, closed};
    e0.walked = true;
    int cur = e0.to;
    while (closed ? cur != v0 : g.corner_of(cur) < 0) {
      HalfEdge* next = nullptr;
      for (auto& e : out[cur])
        if (e.region == e0.region && !e.walked) { next = &e; break; }
      if (!next) break;
      next->walked = true;
      d.vertices.push_back(next->to);
      cur = next->to;
    }
    directed.push_back(std::move(d));
  };
  for (int v : g.corners)
    for (auto& e : out[v])
      if (!e.walked) walk(v, e, false);
  for (int v = 0; v < nv; ++v)
    for (auto& e : out[v])
      if (!e.walked) walk(v, e, true);
  return directed;
}

/// Stores each curve once (as its lower region walked it); returns per directed curve i or ~i.
std::vector<int> store_curves(const std::vector<Directed>& directed, BoundaryGraph& g) {
  g.region_curves.assign(g.num_regions(), {});
  std::vector<int> stored(directed.size(), 0);
  std::vector<std::pair<EdgeKey, int>> curve_of_edge;  // (undirected edge, stored curve), sorted
  for (size_t i = 0; i < directed.size(); ++i) {
    const Directed& d = directed[i];
    if (d.left > d.right) continue;
    const int id = static_cast<int>(g.curves.size());
    stored[i] = id;
    for (size_t k = 1; k < d.vertices.size(); ++k) curve_of_edge.emplace_back(mesh::undirected_edge(d.vertices[k - 1], d.vertices[k]), id);
    g.region_curves[d.left].push_back(id);
    g.region_curves[d.right].push_back(id);
    g.curves.push_back({d.left, d.right, d.vertices, d.closed});
  }
  std::sort(curve_of_edge.begin(), curve_of_edge.end());
  for (size_t i = 0; i < directed.size(); ++i) {
    const Directed& d = directed[i];
    if (d.left < d.right) continue;
    const EdgeKey e = mesh::undirected_edge(d.vertices[0], d.vertices[1]);
    auto it = std::lower_bound(curve_of_edge.begin(), curve_of_edge.end(), std::make_pair(e, -1));
    stored[i] = it == curve_of_edge.end() || it->first != e ? ~0 : ~it->second;
  }
  return stored;
}

/// Loops per region: its directed curves chained at their end corners.
void chain_loops(const std::vector<Directed>& directed, const std::vector<int>& stored, BoundaryGraph& g) {
  const int nr = g.num_regions();
  g.loops.assign(nr, {});
  std::vector<std::vector<int>> region_directed(nr);
  for (size_t i = 0; i < directed.size(); ++i) region_directed[directed[i].left].push_back(static_cast<int>(i));
  std::vector<char> taken(directed.size(), 0);
  for (int r = 0; r < nr; ++r) {
    for (int i0 : region_directed[r]) {
      if (taken[i0]) continue;
      taken[i0] = 1;
      if (directed[i0].closed) {
        g.loops[r].push_back({{}, {stored[i0]}});
        continue;
      }
      BoundaryLoop loop;
      loop.corners.push_back(directed[i0].vertices.front());
      loop.curves.push_back(stored[i0]);
      int end = directed[i0].vertices.back();
      while (end != loop.corners.front()) {
        int next = -1;
        for (int j : region_directed[r])
          if (!taken[j] && !directed[j].closed && directed[j].vertices.front() == end) { next = j; break; }
        if (next < 0) break;
        taken[next] = 1;
        loop.corners.push_back(end);
        loop.curves.push_back(stored[next]);
        end = directed[next].vertices.back();
      }
      g.loops[r].push_back(std::move(loop));
    }
  }
}

}  // namespace

void check_closed_manifold(const mesh::SurfaceMesh& s) { mesh::check_closed_manifold(s); }

BoundaryGraph boundary_graph(const mesh::SurfaceMesh& s) {
  mesh::check_closed_manifold(s);
  return boundary_graph(s, mesh::triangle_adjacency(s.F));
}

BoundaryGraph boundary_graph(const mesh::SurfaceMesh& s, const Eigen::MatrixXi& TT) {
  const int nf = static_cast<int>(s.F.rows());
  if (s.patch.rows() != nf)
    throw GeometryError("the surface has " + std::to_string(nf) + " triangles but " + std::to_string(s.patch.rows()) + " patch ids");
  if (TT.rows() != nf || TT.cols() != 3)
    throw GeometryError("the triangle adjacency has " + std::to_string(TT.rows()) + " rows for " + std::to_string(nf) + " triangles");
  BoundaryGraph g;
  flood_regions(s, TT, g);
  find_corners(s, TT, g);
  const std::vector<Directed> directed = walk_curves(s, TT, g);
  const std::vector<int> stored = store_curves(directed, g);
  chain_loops(directed, stored, g);
  g.adjacency = TT;
  return g;
}

}  // namespace hexdom::polycube
