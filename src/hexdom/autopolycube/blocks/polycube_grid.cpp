#include "hexdom/autopolycube/blocks/polycube_grid.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace hexdom::autopolycube {

namespace {
int ival(double x) { return static_cast<int>(std::lround(x)); }
}  // namespace

PolycubeGrid polycube_grid(const mesh::SurfaceMesh& s, const ChartGraph& g, const PlaneGroups& pg, const PolycubeMap& m) {
  (void)s;
  PolycubeGrid out;
  std::set<int> bad;
  std::string problem;
  auto fail = [&](const std::string& what, std::initializer_list<int> charts) {
    for (int c : charts) bad.insert(c);
    if (problem.empty()) problem = what;
  };

  // ---- rasterise each chart: winding number of square centres against its straight curves
  struct Seg {  // a curve segment along in-plane axis 2 (the "c" axis) at in-plane coordinate b
    int b, c0, c1;
  };
  std::vector<std::vector<Seg>> segs(g.num_charts());
  std::vector<std::array<int, 4>> box(g.num_charts(), {INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN});
  for (const auto& cv : g.curves) {
    const int p = cv.vertices.front(), q = cv.vertices.back();
    for (int side = 0; side < 2; ++side) {
      const int c = side == 0 ? cv.left : cv.right;
      const int a = (g.label[c] - 1) / 2, ab = (a + 1) % 3, ac = (a + 2) % 3;
      const int from = side == 0 ? p : q, to = side == 0 ? q : p;
      const int b0 = ival(m.D(from, ab)), c0 = ival(m.D(from, ac)), b1 = ival(m.D(to, ab)), c1 = ival(m.D(to, ac));
      auto& bx = box[c];
      bx = {std::min({bx[0], b0, b1}), std::min({bx[1], c0, c1}), std::max({bx[2], b0, b1}), std::max({bx[3], c0, c1})};
      if (b0 == b1 && c0 != c1) segs[c].push_back({b0, c0, c1});
    }
  }
  std::map<std::array<int, 4>, int> owner;
  for (int c = 0; c < g.num_charts(); ++c) {
    const int a = (g.label[c] - 1) / 2, sg = g.label[c] % 2 == 1 ? 1 : -1;
    const int plane = m.plane(pg.of_chart[c]);
    const auto& bx = box[c];
    int count = 0;
    for (int j = bx[1]; j < bx[3]; ++j) {
      // Crossings of the row c = j + 1/2, sorted by b, with their winding contributions.
      std::vector<std::pair<int, int>> cross;
      for (const auto& sgm : segs[c])
        if (std::min(sgm.c0, sgm.c1) <= j && j < std::max(sgm.c0, sgm.c1)) cross.push_back({sgm.b, sgm.c1 > sgm.c0 ? 1 : -1});
      std::sort(cross.begin(), cross.end());
      // Winding of (i + 1/2, j + 1/2): sum over crossings to its right.
      int total = 0;
      for (const auto& x : cross) total += x.second;
      size_t k = 0;
      int left = 0;  // sum over crossings with b <= i
      for (int i = bx[0]; i < bx[2]; ++i) {
        while (k < cross.size() && cross[k].first <= i) left += cross[k++].second;
        const int wind = total - left;
        if (wind == 0) continue;
        if (wind != sg) {
          fail("the plane polygon of " + chart_name(g, c) + " overlaps itself (winding " + std::to_string(wind) + ")", {c});
          continue;
        }
        const std::array<int, 4> key{a, plane, i, j};
        auto [it, fresh] = owner.emplace(key, c);
        if (!fresh) {
          fail(chart_name(g, it->second) + " and " + chart_name(g, c) + " overlap in the polycube", {it->second, c});
          continue;
        }
        GridSquare q;
        q.axis = a;
        q.sign = sg;
        q.plane = plane;
        q.i = i;
        q.j = j;
        q.chart = c;
        out.squares.push_back(q);
        ++count;
      }
    }
    if (count == 0) fail(chart_name(g, c) + " covers no grid square (its polygon has no area)", {c});
  }
  std::sort(out.squares.begin(), out.squares.end(), [](const GridSquare& x, const GridSquare& y) {
    return std::tie(x.axis, x.plane, x.i, x.j) < std::tie(y.axis, y.plane, y.i, y.j);
  });
  for (size_t k = 0; k < out.squares.size(); ++k) {
    const auto& q = out.squares[k];
    out.square_of[{q.axis, q.plane, q.i, q.j}] = static_cast<int>(k);
  }

  // ---- cells: along each grid row in x, X squares toggle inside/outside
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> rows;  // (y, z) -> (plane, sign)
  for (const auto& q : out.squares)
    if (q.axis == 0) rows[{q.i, q.j}].push_back({q.plane, q.sign});
  std::set<std::array<int, 3>> inside;
  for (auto& [yz, ev] : rows) {
    std::sort(ev.begin(), ev.end());
    int depth = 0;
    for (size_t k = 0; k < ev.size(); ++k) {
      depth -= ev[k].second;  // a -X square is entered, a +X square left
      if (depth < 0 || depth > 1) {
        const int c = out.squares[out.square_of.at({0, ev[k].first, yz.first, yz.second})].chart;
        fail("the polycube's surface crosses itself at " + chart_name(g, c), {c});
        depth = std::clamp(depth, 0, 1);
      }
      if (depth == 1 && k + 1 < ev.size())
        for (int x = ev[k].first; x < ev[k + 1].first; ++x) inside.insert({x, yz.first, yz.second});
    }
    if (depth != 0) {
      const int c = out.squares[out.square_of.at({0, ev.back().first, yz.first, yz.second})].chart;
      fail("the polycube's surface is not closed along a grid row ending at " + chart_name(g, c), {c});
    }
  }
  out.cells.assign(inside.begin(), inside.end());

  // ---- the cells' boundary squares must be the charts' squares, with the same orientation
  std::set<std::array<int, 4>> matched;
  for (const auto& cell : out.cells)
    for (int a = 0; a < 3; ++a)
      for (int sg = -1; sg <= 1; sg += 2) {
        std::array<int, 3> nb = cell;
        nb[a] += sg;
        if (inside.count(nb)) continue;
        const int plane = cell[a] + (sg > 0 ? 1 : 0);
        const std::array<int, 4> key{a, plane, cell[(a + 1) % 3], cell[(a + 2) % 3]};
        auto it = out.square_of.find(key);
        if (it == out.square_of.end()) {
          // Name the charts of the nearest squares in that plane.
          int near = -1;
          for (const auto& q : out.squares)
            if (q.axis == a && q.plane == plane) { near = q.chart; break; }
          fail(std::string("a face of the polycube's cells in plane ") + "XYZ"[a] + " = " + std::to_string(plane) +
                   " is covered by no chart", {});
          if (near >= 0) bad.insert(near);
          continue;
        }
        const auto& q = out.squares[it->second];
        if (q.sign != sg) fail(chart_name(g, q.chart) + " faces into the polycube", {q.chart});
        matched.insert(key);
      }
  for (const auto& q : out.squares)
    if (!matched.count({q.axis, q.plane, q.i, q.j}))
      fail(chart_name(g, q.chart) + " has a square inside the polycube's cells", {q.chart});
  out.bad_charts.assign(bad.begin(), bad.end());
  out.problem = problem;
  return out;
}

}  // namespace hexdom::autopolycube
