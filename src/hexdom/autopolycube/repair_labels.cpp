#include "hexdom/autopolycube/repair_labels.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <set>

#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::autopolycube {

std::string kind_name(ProblemKind k) {
  switch (k) {
    case ProblemKind::OppositeNeighbours: return "opposite_neighbours";
    case ProblemKind::ClosedCurve: return "closed_curve";
    case ProblemKind::Pinch: return "pinch";
    case ProblemKind::FewCorners: return "few_corners";
    case ProblemKind::MissingAxis: return "missing_axis";
    case ProblemKind::ZeroLengthEdge: return "zero_length_edge";
    case ProblemKind::BadTurning: return "bad_turning";
  }
  return "?";
}

namespace {

std::string vertex_text(const mesh::SurfaceMesh& s, int v) {
  char b[160];
  std::snprintf(b, sizeof b, "vertex %d (%g, %g, %g)", v + 1, s.V(v, 0), s.V(v, 1), s.V(v, 2));
  return b;
}

// Charts of the triangles around vertex v.
std::vector<int> charts_at(const ChartGraph& g, const std::vector<std::vector<int>>& vt, int v) {
  std::set<int> cs;
  for (int f : vt[v]) cs.insert(g.chart(f));
  return {cs.begin(), cs.end()};
}

}  // namespace

std::vector<ChartProblem> chart_problems(const mesh::SurfaceMesh& s, const ChartGraph& g, const PlaneGroups& pg) {
  std::vector<ChartProblem> out;
  std::vector<std::vector<int>> vt(s.V.rows());
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) vt[s.F(f, k)].push_back(f);
  auto name = [&](int c) { return chart_name(g, c); };
  for (const auto& c : g.curves) {
    const int v = c.vertices.front();
    if (segmentation::are_opposite(g.label[c.left], g.label[c.right]))
      out.push_back({ProblemKind::OppositeNeighbours, {c.left, c.right}, v,
                     name(c.left) + " and " + name(c.right) + " have opposite labels and share a curve at " + vertex_text(s, v)});
    else if (c.closed)
      out.push_back({ProblemKind::ClosedCurve, {c.left, c.right}, v,
                     name(c.left) + " and " + name(c.right) + " meet along a loop without corners through " + vertex_text(s, v)});
  }
  for (int v : g.pinches) {
    auto cs = charts_at(g, vt, v);
    std::string m;
    for (int c : cs) m += (m.empty() ? "" : ", ") + name(c);
    out.push_back({ProblemKind::Pinch, cs, v, "a chart meets itself at " + vertex_text(s, v) + " (charts " + m + ")"});
  }
  for (int c = 0; c < g.num_charts(); ++c)
    for (const auto& loop : g.loop_corners[c])
      if (!loop.empty() && loop.size() < 4) {
        out.push_back({ProblemKind::FewCorners, {c}, loop.front(),
                       name(c) + " has a boundary loop with " + std::to_string(loop.size()) +
                           " corners (a polycube face needs at least 4) at " + vertex_text(s, loop.front())});
      }
  for (int v : g.corners)
    for (int a = 0; a < 3; ++a)
      if (pg.of_vertex(v, a) < 0) {
        auto cs = charts_at(g, vt, v);
        std::string m;
        for (int c : cs) m += (m.empty() ? "" : ", ") + name(c);
        out.push_back({ProblemKind::MissingAxis, cs, v,
                       "corner " + vertex_text(s, v) + " has no chart facing " + "XYZ"[a] + " (charts " + m + ")"});
        break;
      }
  for (const auto& c : g.curves) {
    if (c.closed) continue;
    const int al = (g.label[c.left] - 1) / 2, ar = (g.label[c.right] - 1) / 2;
    if (al == ar) continue;
    const int ax = 3 - al - ar, p = c.vertices.front(), q = c.vertices.back();
    const int gp = pg.of_vertex(p, ax), gq = pg.of_vertex(q, ax);
    if (gp >= 0 && gp == gq)
      out.push_back({ProblemKind::ZeroLengthEdge, {c.left, c.right}, p,
                     "the curve between " + name(c.left) + " and " + name(c.right) + " from " + vertex_text(s, p) + " to " +
                         vertex_text(s, q) + " would have zero length: both ends lie in one plane of " + "XYZ"[ax]});
  }
  // Turning of each chart's loops, with every curve running the way it runs in the input.
  auto direction = [&](int signed_curve) {  // unit axis vector of a curve as the loop runs it
    const bool rev = signed_curve < 0;
    const auto& c = g.curves[rev ? ~signed_curve : signed_curve];
    const int ax = 3 - (g.label[c.left] - 1) / 2 - (g.label[c.right] - 1) / 2;
    const double d = s.V(c.vertices.back(), ax) - s.V(c.vertices.front(), ax);
    Eigen::Vector3i u = Eigen::Vector3i::Zero();
    u(ax) = (d >= 0) != rev ? 1 : -1;
    return u;
  };
  for (int c = 0; c < g.num_charts(); ++c) {
    if (!std::all_of(g.loop_corners[c].begin(), g.loop_corners[c].end(), [](const auto& l) { return l.size() >= 4; })) continue;
    const int a = (g.label[c] - 1) / 2, sg = g.label[c] % 2 == 1 ? 1 : -1, b = (a + 1) % 3, cc = (a + 2) % 3;
    int outer = 0;
    bool bad = false;
    std::string what;
    std::set<int> blame{c};
    for (size_t l = 0; l < g.loop_curves[c].size(); ++l) {
      const auto& loop = g.loop_curves[c][l];
      const int n = static_cast<int>(loop.size());
      int turn = 0;
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3i u = direction(loop[i]), w = direction(loop[(i + 1) % n]);
        const int cross = u(b) * w(cc) - u(cc) * w(b);
        if (cross == 0 && u.dot(w) < 0) {
          bad = true;
          const int v = g.loop_corners[c][l][(i + 1) % n];
          if (what.empty()) what = "turns back at " + vertex_text(s, v);
          for (int sc : {loop[i], loop[(i + 1) % n]}) {
            const auto& cv = g.curves[sc < 0 ? ~sc : sc];
            blame.insert(cv.left == c ? cv.right : cv.left);
          }
        }
        turn += sg * cross;
      }
      if (turn == 4) ++outer;
      else if (turn != -4 && what.empty()) what = "has a loop turning by " + std::to_string(90 * turn) + " degrees";
      if (turn != 4 && turn != -4) bad = true;
    }
    if (!bad && outer != 1) {
      bad = true;
      what = "has " + std::to_string(outer) + " outer loops";
    }
    if (!bad) continue;
    if (blame.size() == 1)
      for (int ci : g.chart_curves[c]) blame.insert(g.curves[ci].left == c ? g.curves[ci].right : g.curves[ci].left);
    out.push_back({ProblemKind::BadTurning, {blame.begin(), blame.end()}, g.loop_corners[c].empty() || g.loop_corners[c][0].empty() ? -1 : g.loop_corners[c][0][0],
                   name(c) + " cannot be a polycube face: its boundary " + what});
  }
  return out;
}

namespace {

// Area-weighted n . axis of each label over the chart's triangles (index label - 1).
std::array<double, 6> label_fit(const mesh::SurfaceMesh& s, const ChartGraph& g, int chart) {
  std::array<double, 6> fit{};
  for (int f = 0; f < s.F.rows(); ++f) {
    if (g.chart(f) != chart) continue;
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
    const Eigen::Vector3d n = 0.5 * (b - a).cross(d - a);
    for (int l = 1; l <= 6; ++l) fit[l - 1] += n.dot(segmentation::label_axis(l));
  }
  return fit;
}

}  // namespace

Eigen::VectorXi relabel_chart(const mesh::SurfaceMesh& s, const ChartGraph& g, int chart, int problems) {
  // Candidates: the neighbours' labels (joining one of them) and every other label facing the chart's
  // way. Each is tried: a label that leaves fewer problems wins (then joining, then fitting the
  // normals best); when none does, the chart joins the neighbour whose label fits best, so that the
  // number of charts always drops.
  const std::array<double, 6> fit = label_fit(s, g, chart);
  std::set<int> joins;
  for (int ci : g.chart_curves[chart]) {
    const auto& c = g.curves[ci];
    joins.insert(g.label[c.left == chart ? c.right : c.left]);
  }
  joins.erase(g.label[chart]);
  if (joins.empty()) throw GeometryError(chart_name(g, chart) + " has no neighbour with another label to join");
  int best_join = *joins.begin();
  for (int l : joins)
    if (fit[l - 1] > fit[best_join - 1]) best_join = l;
  int best = best_join;
  if (problems > 0) {
    long best_key[3] = {problems, 0, 0};
    bool found = false;
    mesh::SurfaceMesh t = s;
    for (int l = 1; l <= 6; ++l) {
      if (l == g.label[chart] || (!joins.count(l) && fit[l - 1] <= 0)) continue;
      for (int f = 0; f < s.F.rows(); ++f) t.patch(f) = g.chart(f) == chart ? l : s.patch(f);
      const ChartGraph tg = chart_graph(t);
      const long n = static_cast<long>(chart_problems(t, tg, plane_groups(t, tg)).size());
      const long key[3] = {n, joins.count(l) ? 0 : 1, -static_cast<long>(std::llround(1e6 * fit[l - 1] / std::max(g.area[chart], 1e-300)))};
      if (n < problems && (!found || std::lexicographical_compare(key, key + 3, best_key, best_key + 3))) {
        found = true;
        std::copy(key, key + 3, best_key);
        best = l;
      }
    }
  }
  Eigen::VectorXi label = s.patch;
  for (int f = 0; f < s.F.rows(); ++f)
    if (g.chart(f) == chart) label(f) = best;
  return label;
}

RepairResult repair_labels(const mesh::SurfaceMesh& labels, const RepairOptions& opt) {
  mesh::SurfaceMesh s = labels;
  RepairResult r;
  for (;;) {
    const ChartGraph g = chart_graph(s);
    const PlaneGroups pg = plane_groups(s, g);
    auto problems = chart_problems(s, g, pg);
    if (problems.empty() || r.relabelled >= opt.max_relabels) {
      r.remaining = std::move(problems);
      break;
    }
    // The smallest chart named by any problem.
    int chart = -1;
    const ChartProblem* why = nullptr;
    for (const auto& p : problems)
      for (int c : p.charts)
        if (chart < 0 || g.area[c] < g.area[chart]) { chart = c; why = &p; }
    if (opt.log) opt.log(0, "relabelling " + chart_name(g, chart) + ": " + why->message);
    s.patch = relabel_chart(s, g, chart, static_cast<int>(problems.size()));
    ++r.relabelled;
  }
  r.label = s.patch;
  return r;
}

}  // namespace hexdom::autopolycube
