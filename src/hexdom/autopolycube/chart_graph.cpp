#include "hexdom/autopolycube/chart_graph.h"

#include <algorithm>
#include <unordered_map>

#include "hexdom/common/error.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::autopolycube {

namespace {
struct HalfEdge {
  int chart, to, across;
};
}  // namespace

ChartGraph chart_graph(const mesh::SurfaceMesh& s) {
  polycube::check_closed_manifold(s);
  const int nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  if (s.patch.rows() != nf)
    throw GeometryError("the surface has " + std::to_string(nf) + " triangles but " + std::to_string(s.patch.rows()) + " labels");
  for (int f = 0; f < nf; ++f)
    if (s.patch(f) < 1 || s.patch(f) > 6)
      throw GeometryError("triangle " + std::to_string(f + 1) + " has label " + std::to_string(s.patch(f)) +
                          ": axis labels are 1..6 (+X, -X, +Y, -Y, +Z, -Z), as `hexdom segment` writes them");
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  ChartGraph g;

  // Charts by flood fill.
  g.chart = Eigen::VectorXi::Constant(nf, -1);
  for (int f0 = 0; f0 < nf; ++f0) {
    if (g.chart(f0) >= 0) continue;
    const int c = g.num_charts();
    g.label.push_back(s.patch(f0));
    g.first_triangle.push_back(f0);
    g.area.push_back(0);
    g.triangles.push_back(0);
    std::vector<int> stack{f0};
    g.chart(f0) = c;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
      g.area[c] += 0.5 * (b - a).cross(d - a).norm();
      g.triangles[c]++;
      for (int k = 0; k < 3; ++k) {
        const int h = TT(f, k);
        if (h >= 0 && g.chart(h) < 0 && s.patch(h) == s.patch(f)) {
          g.chart(h) = c;
          stack.push_back(h);
        }
      }
    }
  }
  const int nc = g.num_charts();

  // Fans: around each vertex, count chart changes and distinct charts.
  std::unordered_map<long long, int> tri_of;  // directed edge -> triangle
  tri_of.reserve(3 * nf);
  auto dkey = [](int a, int b) { return (static_cast<long long>(a) << 32) | static_cast<unsigned>(b); };
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) tri_of[dkey(s.F(f, k), s.F(f, (k + 1) % 3))] = f;
  std::vector<int> some_tri(nv, -1);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) some_tri[s.F(f, k)] = f;
  g.corner_of = Eigen::VectorXi::Constant(nv, -1);
  std::vector<int> fan;
  for (int v = 0; v < nv; ++v) {
    if (some_tri[v] < 0) continue;
    fan.clear();
    int f = some_tri[v];
    do {
      fan.push_back(f);
      int k = 0;
      while (s.F(f, k) != v) ++k;
      f = tri_of.at(dkey(v, s.F(f, (k + 2) % 3)));
    } while (f != some_tri[v] && fan.size() <= static_cast<size_t>(nf));
    int changes = 0;
    std::vector<int> distinct;
    for (size_t i = 0; i < fan.size(); ++i) {
      const int a = g.chart(fan[i]), b = g.chart(fan[(i + 1) % fan.size()]);
      if (a != b) ++changes;
      if (std::find(distinct.begin(), distinct.end(), a) == distinct.end()) distinct.push_back(a);
    }
    if (changes >= 3) {
      g.corner_of(v) = static_cast<int>(g.corners.size());
      g.corners.push_back(v);
    }
    if (changes > 0 && changes > static_cast<int>(distinct.size())) g.pinches.push_back(v);
  }

  // Boundary half-edges (chart on the left) leaving each vertex.
  std::vector<std::vector<HalfEdge>> out(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int h = TT(f, k);
      if (g.chart(h) != g.chart(f)) out[s.F(f, k)].push_back({g.chart(f), s.F(f, (k + 1) % 3), g.chart(h)});
    }
  std::unordered_map<long long, char> used;  // directed boundary edge -> walked
  struct Directed {
    int left, right;
    std::vector<int> vertices;
    bool closed;
  };
  std::vector<Directed> directed;
  auto walk = [&](int v0, const HalfEdge& e0, bool closed) {
    Directed d{e0.chart, e0.across, {v0, e0.to}, closed};
    used[dkey(v0, e0.to)] = 1;
    int cur = e0.to;
    while (closed ? cur != v0 : g.corner_of(cur) < 0) {
      const HalfEdge* next = nullptr;
      for (const auto& e : out[cur])
        if (e.chart == e0.chart && !used.count(dkey(cur, e.to))) { next = &e; break; }
      if (!next) break;  // a pinch: reported separately
      used[dkey(cur, next->to)] = 1;
      d.vertices.push_back(next->to);
      cur = next->to;
    }
    directed.push_back(std::move(d));
  };
  for (int v : g.corners)
    for (const auto& e : out[v])
      if (!used.count(dkey(v, e.to))) walk(v, e, false);
  for (int v = 0; v < nv; ++v)
    for (const auto& e : out[v])
      if (!used.count(dkey(v, e.to))) walk(v, e, true);

  // Each curve once (left < right); every chart lists its curves.
  g.chart_curves.assign(nc, {});
  std::vector<int> stored(directed.size(), 0);  // directed curve -> i or ~i
  std::unordered_map<long long, int> by_first_edge;
  for (size_t i = 0; i < directed.size(); ++i) {
    const auto& d = directed[i];
    if (d.left > d.right) continue;
    stored[i] = static_cast<int>(g.curves.size());
    by_first_edge[dkey(d.vertices[0], d.vertices[1])] = static_cast<int>(g.curves.size());
    ChartCurve c;
    c.left = d.left;
    c.right = d.right;
    c.vertices = d.vertices;
    c.closed = d.closed;
    const int id = static_cast<int>(g.curves.size());
    g.chart_curves[c.left].push_back(id);
    g.chart_curves[c.right].push_back(id);
    g.curves.push_back(std::move(c));
  }
  for (size_t i = 0; i < directed.size(); ++i) {
    const auto& d = directed[i];
    if (d.left < d.right) continue;
    const size_t n = d.vertices.size();
    auto it = by_first_edge.find(dkey(d.vertices[n - 1], d.vertices[n - 2]));
    stored[i] = it == by_first_edge.end() ? ~0 : ~it->second;
  }

  // Loops per chart: chain its directed curves at their end corners.
  g.loop_corners.assign(nc, {});
  g.loop_curves.assign(nc, {});
  std::vector<std::vector<int>> chart_directed(nc);
  for (size_t i = 0; i < directed.size(); ++i) chart_directed[directed[i].left].push_back(static_cast<int>(i));
  std::vector<char> taken(directed.size(), 0);
  for (int c = 0; c < nc; ++c) {
    for (int i0 : chart_directed[c]) {
      if (taken[i0]) continue;
      taken[i0] = 1;
      if (directed[i0].closed) {
        g.loop_corners[c].emplace_back();
        g.loop_curves[c].emplace_back();
        continue;
      }
      std::vector<int> loop{directed[i0].vertices.front()};
      std::vector<int> lc{stored[i0]};
      int end = directed[i0].vertices.back();
      while (end != loop.front()) {
        int next = -1;
        for (int j : chart_directed[c])
          if (!taken[j] && !directed[j].closed && directed[j].vertices.front() == end) { next = j; break; }
        if (next < 0) break;
        taken[next] = 1;
        loop.push_back(end);
        lc.push_back(stored[next]);
        end = directed[next].vertices.back();
      }
      g.loop_corners[c].push_back(std::move(loop));
      g.loop_curves[c].push_back(std::move(lc));
    }
  }
  return g;
}

std::string chart_name(const ChartGraph& g, int c) {
  return "chart " + std::to_string(c + 1) + " (" + segmentation::label_name(g.label[c]) + ", " +
         std::to_string(g.triangles[c]) + " triangle" + (g.triangles[c] == 1 ? "" : "s") + ")";
}

}  // namespace hexdom::autopolycube
