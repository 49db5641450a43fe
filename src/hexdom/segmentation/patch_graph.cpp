#include "hexdom/segmentation/patch_graph.h"

#include <algorithm>
#include <unordered_map>

#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::segmentation {

namespace {
long long undirected(int a, int b) {
  return (static_cast<long long>(std::min(a, b)) << 32) | static_cast<unsigned>(std::max(a, b));
}
long long directed(int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); }
}  // namespace

PatchGraph patch_graph(const mesh::SurfaceMesh& s) {
  PatchGraph g;
  g.layout = polycube::patch_layout(s);
  const auto& L = g.layout;
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  const int np = g.num_patches();

  // Geometry per patch.
  const TriangleGeometry geo = triangle_geometry(s);
  g.normal = Eigen::MatrixXd::Zero(np, 3);
  g.centroid = Eigen::MatrixXd::Zero(np, 3);
  g.area = Eigen::VectorXd::Zero(np);
  g.axis.resize(np);
  for (int f = 0; f < nf; ++f) {
    const int r = L.region(f);
    g.normal.row(r) += geo.area(f) * geo.normal.row(f);
    g.centroid.row(r) += geo.area(f) * geo.centroid.row(f);
    g.area(r) += geo.area(f);
  }
  for (int r = 0; r < np; ++r) {
    if (g.area(r) > 0) g.centroid.row(r) /= g.area(r);
    const double n = g.normal.row(r).norm();
    if (n > 0) g.normal.row(r) /= n;
    g.axis(r) = nearest_label(g.normal.row(r).transpose());
  }

  // Which triangle holds each directed edge.
  std::unordered_map<long long, int> tri_of;
  tri_of.reserve(3 * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) tri_of[directed(s.F(f, k), s.F(f, (k + 1) % 3))] = f;
  auto across = [&](int a, int b) {  // patch on the other side of the patch edge a -> b
    auto it = tri_of.find(directed(b, a));
    return it == tri_of.end() ? -1 : L.region(it->second);
  };

  // Euler characteristic per patch.
  g.euler.assign(np, 0);
  std::vector<int> stamp(nv, -1), boundary_edges(np, 0), vertices(np, 0), tris(np, 0);
  for (int r = 0; r < np; ++r)
    for (int f : L.patches[r].triangles) {
      ++tris[r];
      for (int k = 0; k < 3; ++k) {
        const int v = s.F(f, k);
        if (stamp[v] != r) { stamp[v] = r; ++vertices[r]; }
        if (across(v, s.F(f, (k + 1) % 3)) != r) ++boundary_edges[r];
      }
    }
  for (int r = 0; r < np; ++r) g.euler[r] = vertices[r] - (3 * tris[r] + boundary_edges[r]) / 2 + tris[r];

  // Curves along each patch's first loop, split at corners; each stored once.
  std::unordered_map<long long, int> curve_of;  // smallest undirected edge of a curve -> curve
  g.patch_curves.assign(np, {});
  for (int r = 0; r < np; ++r) {
    const auto& loop = L.patches[r].loop;
    const int m = static_cast<int>(loop.size());
    if (m == 0) continue;
    std::vector<int> cuts = L.patches[r].corners;
    const bool closed = cuts.empty();
    if (closed) cuts.push_back(0);
    for (size_t i = 0; i < cuts.size(); ++i) {
      const int from = cuts[i], to = (i + 1 < cuts.size()) ? cuts[i + 1] : cuts[0] + m;
      PatchCurve c;
      c.left = r;
      long long smallest = -1;
      for (int j = from; j <= to; ++j) {
        c.vertices.push_back(loop[j % m]);
        if (j > from) {
          const long long e = undirected(loop[(j - 1) % m], loop[j % m]);
          if (smallest < 0 || e < smallest) smallest = e;
        }
      }
      c.right = across(c.vertices[0], c.vertices[1]);
      auto [it, inserted] = curve_of.try_emplace(smallest, static_cast<int>(g.curves.size()));
      if (inserted) {
        g.patch_curves[r].push_back(it->second);
        g.curves.push_back(std::move(c));
      } else {
        g.patch_curves[r].push_back(~it->second);
      }
    }
  }
  return g;
}

}  // namespace hexdom::segmentation
