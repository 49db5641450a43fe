#include "hexdom/segmentation/edit_patches.h"

#include <algorithm>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::segmentation {

namespace {

void require_shape(const mesh::SurfaceMesh& s) {
  if (s.patch.rows() != s.F.rows())
    throw InputError("the patch map has " + std::to_string(s.patch.rows()) + " ids for " + std::to_string(s.F.rows()) +
                     " triangles");
}

void require_id(const Eigen::VectorXi& patch, int id) {
  for (int f = 0; f < patch.rows(); ++f)
    if (patch(f) == id) return;
  throw InputError("no patch has id " + std::to_string(id));
}

/// Connected components of triangles with equal id, not crossing the edges in `cut`.
Eigen::VectorXi components(const Eigen::MatrixXi& F, const Eigen::MatrixXi& TT, const Eigen::VectorXi& patch,
                           const std::unordered_set<long long>& cut) {
  std::vector<int> comp;
  mesh::triangle_components(
      TT,
      [&](int f, int k) {
        return patch(TT(f, k)) == patch(f) &&
               (cut.empty() || !cut.count(mesh::undirected_edge(F(f, k), F(f, (k + 1) % 3))));
      },
      comp);
  return Eigen::Map<const Eigen::VectorXi>(comp.data(), static_cast<Eigen::Index>(comp.size()));
}

}  // namespace

Eigen::VectorXi number_patches(const mesh::SurfaceMesh& s) {
  require_shape(s);
  Eigen::VectorXi comp = components(s.F, mesh::triangle_adjacency(s.F), s.patch, {});
  return comp.array() + 1;
}

Eigen::VectorXi reassign_triangles(const mesh::SurfaceMesh& s, const std::vector<int>& triangles, int id) {
  require_shape(s);
  Eigen::VectorXi out = s.patch;
  if (id <= 0) id = (out.size() ? out.maxCoeff() : 0) + 1;
  for (int t : triangles) {
    if (t < 0 || t >= out.size())
      throw InputError("triangle " + std::to_string(t) + " (0-based) does not exist: the surface has " +
                       std::to_string(out.size()) + " triangles");
    out(t) = id;
  }
  return out;
}

Eigen::VectorXi merge_patches(const mesh::SurfaceMesh& s, int a, int b) {
  require_shape(s);
  if (a == b) throw InputError("cannot merge patch " + std::to_string(a) + " with itself");
  require_id(s.patch, a);
  require_id(s.patch, b);
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  bool touch = false;
  for (int f = 0; f < s.F.rows() && !touch; ++f)
    if (s.patch(f) == a)
      for (int k = 0; k < 3; ++k)
        if (TT(f, k) >= 0 && s.patch(TT(f, k)) == b) touch = true;
  if (!touch)
    throw GeometryError("patches " + std::to_string(a) + " and " + std::to_string(b) +
                        " share no edge: merging them would not make one patch");
  Eigen::VectorXi out = s.patch;
  for (int f = 0; f < out.size(); ++f)
    if (out(f) == b) out(f) = a;
  return out;
}

Eigen::VectorXi split_patch(const mesh::SurfaceMesh& s, int id, const std::vector<int>& path) {
  require_shape(s);
  require_id(s.patch, id);
  if (path.size() < 2) throw InputError("a split path needs at least 2 vertices, got " + std::to_string(path.size()));
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  for (int v : path)
    if (v < 0 || v >= nv)
      throw InputError("vertex " + std::to_string(v) + " (0-based) does not exist: the surface has " +
                       std::to_string(nv) + " vertices");
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  // The patch's interior edges (both triangles in the patch) as a graph; vertices on the patch.
  std::vector<std::vector<std::pair<int, double>>> adj(nv);
  std::vector<char> on_patch(nv, 0);
  for (int f = 0; f < nf; ++f) {
    if (s.patch(f) != id) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3), g = TT(f, k);
      on_patch[a] = 1;
      if (g > f && s.patch(g) == id) {
        const double len = (s.V.row(a) - s.V.row(b)).norm();
        adj[a].emplace_back(b, len);
        adj[b].emplace_back(a, len);
      }
    }
  }
  for (int v : path)
    if (!on_patch[v]) throw GeometryError("vertex " + std::to_string(v) + " is not on patch " + std::to_string(id));
  std::unordered_set<long long> cut;
  std::vector<double> dist(nv);
  std::vector<int> prev(nv);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int from = path[i], to = path[i + 1];
    if (from == to) continue;
    std::fill(dist.begin(), dist.end(), 1e300);
    std::fill(prev.begin(), prev.end(), -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
    dist[from] = 0;
    q.emplace(0.0, from);
    while (!q.empty()) {
      auto [d, v] = q.top();
      q.pop();
      if (d > dist[v]) continue;
      if (v == to) break;
      for (auto [w, len] : adj[v])
        if (d + len < dist[w]) {
          dist[w] = d + len;
          prev[w] = v;
          q.emplace(dist[w], w);
        }
    }
    if (prev[to] < 0)
      throw GeometryError("vertices " + std::to_string(from) + " and " + std::to_string(to) +
                          " cannot be joined through the inside of patch " + std::to_string(id));
    for (int v = to; v != from; v = prev[v]) cut.insert(mesh::undirected_edge(v, prev[v]));
  }
  const Eigen::VectorXi before = components(s.F, TT, s.patch, {});
  const Eigen::VectorXi after = components(s.F, TT, s.patch, cut);
  // Parts of each split region: the one with the region's first triangle keeps the id.
  std::unordered_map<int, int> keeper;  // region -> component of its first triangle
  std::unordered_map<int, int> new_id;  // component -> new id
  int next = s.patch.maxCoeff() + 1;
  Eigen::VectorXi out = s.patch;
  for (int f = 0; f < nf; ++f) {
    if (s.patch(f) != id) continue;
    auto [it, first] = keeper.try_emplace(before(f), after(f));
    if (first || it->second == after(f)) continue;
    auto [jt, fresh] = new_id.try_emplace(after(f), next);
    if (fresh) ++next;
    out(f) = jt->second;
  }
  if (new_id.empty())
    throw GeometryError("the path does not split patch " + std::to_string(id) +
                        ": it must cross the patch from boundary to boundary or close on itself");
  return out;
}

}  // namespace hexdom::segmentation
