#include "hexdom/autopolycube/repair/repair_labels.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstdio>
#include <set>

#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/mesh/triangle_adjacency.h"

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
    case ProblemKind::MixedConvexity: return "mixed_convexity";
  }
  return "?";
}

namespace {

std::string vertex_text(const mesh::SurfaceMesh& s, int v) {
  char b[160];
  std::snprintf(b, sizeof b, "vertex %d (%g, %g, %g)", v + 1, s.V(v, 0), s.V(v, 1), s.V(v, 2));
  return b;
}

// Normals more than this far apart make a sharp edge for MixedConvexity.
constexpr double kSharpAngleDegrees = 35.0;

// The triangles around each vertex.
std::vector<std::vector<int>> vertex_triangles(const mesh::SurfaceMesh& s) {
  std::vector<std::vector<int>> vt(s.V.rows());
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) vt[s.F(f, k)].push_back(f);
  return vt;
}

// Each of the convex and the concave part of a mixed curve is at least this share of its length
// (and at least the minimum length given).
constexpr double kMixedShare = 0.1;

// The sharp edges of a curve between two charts: the vertices of its convex and of its concave
// edges, and their lengths. Convex: the right chart's triangle lies below the left one's plane.
struct CurveConvexity {
  std::vector<int> convex, concave;  // vertices of the convex / concave sharp edges
  double convex_length = 0, concave_length = 0, length = 0;
  bool mixed(double min_length) const {
    const double least = std::max(kMixedShare * length, min_length);
    return length > 0 && convex_length >= least && concave_length >= least;
  }
};

CurveConvexity curve_convexity(const mesh::SurfaceMesh& s, const ChartGraph& g, const std::vector<std::vector<int>>& vt,
                               const ChartCurve& c) {
  CurveConvexity out;
  const double cos_sharp = std::cos(kSharpAngleDegrees * M_PI / 180.0);
  auto normal = [&](int f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
    return Eigen::Vector3d((b - a).cross(d - a).normalized());
  };
  for (size_t i = 0; i + 1 < c.vertices.size(); ++i) {
    const int u = c.vertices[i], v = c.vertices[i + 1];
    int fl = -1, fr = -1;
    for (int f : vt[u])
      if (s.F(f, 0) == v || s.F(f, 1) == v || s.F(f, 2) == v) (g.region(f) == c.left ? fl : fr) = f;
    const double len = (s.V.row(u) - s.V.row(v)).norm();
    out.length += len;
    if (fl < 0 || fr < 0) continue;
    const Eigen::Vector3d nl = normal(fl), nr = normal(fr);
    if (nl.dot(nr) >= cos_sharp) continue;
    int opposite = s.F(fr, 0);
    for (int k = 0; k < 3; ++k)
      if (s.F(fr, k) != u && s.F(fr, k) != v) opposite = s.F(fr, k);
    const bool convex = nl.dot(s.V.row(opposite).transpose() - s.V.row(u).transpose()) < 0;
    (convex ? out.convex_length : out.concave_length) += len;
    auto& part = convex ? out.convex : out.concave;
    part.push_back(u);
    part.push_back(v);
  }
  return out;
}

// The triangle adjacency of s, whose graph g is: g's (built on s), or paired again when g carries none.
Eigen::MatrixXi adjacency_of(const mesh::SurfaceMesh& s, const ChartGraph& g) {
  return g.adjacency.rows() == s.F.rows() ? g.adjacency : mesh::triangle_adjacency(s.F);
}

// Charts of the triangles around vertex v.
std::vector<int> charts_at(const ChartGraph& g, const std::vector<std::vector<int>>& vt, int v) {
  std::set<int> cs;
  for (int f : vt[v]) cs.insert(g.region(f));
  return {cs.begin(), cs.end()};
}

}  // namespace

std::vector<ChartProblem> chart_problems(const mesh::SurfaceMesh& s, const ChartGraph& g, const PlaneGroups& pg) {
  std::vector<ChartProblem> out;
  const std::vector<std::vector<int>> vt = vertex_triangles(s);
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
    for (const auto& lp : g.loops[c])
      if (const auto& loop = lp.corners; !loop.empty() && loop.size() < 4) {
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
  // A curve between opposite labels (reported above) runs along no axis: the loops it is on have no
  // turning to judge.
  auto along_an_axis = [&](int signed_curve) {
    const auto& cv = g.curves[signed_curve < 0 ? ~signed_curve : signed_curve];
    return (g.label[cv.left] - 1) / 2 != (g.label[cv.right] - 1) / 2;
  };
  for (int c = 0; c < g.num_charts(); ++c) {
    if (!std::all_of(g.loops[c].begin(), g.loops[c].end(), [](const auto& l) { return l.corners.size() >= 4; })) continue;
    if (!std::all_of(g.loops[c].begin(), g.loops[c].end(), [&](const auto& l) {
          return std::all_of(l.curves.begin(), l.curves.end(), along_an_axis);
        }))
      continue;
    const int a = (g.label[c] - 1) / 2, sg = g.label[c] % 2 == 1 ? 1 : -1, b = (a + 1) % 3, cc = (a + 2) % 3;
    int outer = 0;
    bool bad = false;
    std::string what;
    std::set<int> blame{c};
    for (size_t l = 0; l < g.loops[c].size(); ++l) {
      const auto& loop = g.loops[c][l].curves;
      const int n = static_cast<int>(loop.size());
      int turn = 0;
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3i u = direction(loop[i]), w = direction(loop[(i + 1) % n]);
        const int cross = u(b) * w(cc) - u(cc) * w(b);
        if (cross == 0 && u.dot(w) < 0) {
          bad = true;
          const int v = g.loops[c][l].corners[(i + 1) % n];
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
      for (int ci : g.region_curves[c]) blame.insert(g.curves[ci].left == c ? g.curves[ci].right : g.curves[ci].left);
    std::vector<int> charts{c};  // the chart itself first, then the neighbours to blame
    for (int b : blame)
      if (b != c) charts.push_back(b);
    out.push_back({ProblemKind::BadTurning, charts, g.loops[c].empty() || g.loops[c][0].corners.empty() ? -1 : g.loops[c][0].corners[0],
                   name(c) + " cannot be a polycube face: its boundary " + what});
  }
  return out;
}

std::vector<ChartProblem> mixed_convexity_problems(const mesh::SurfaceMesh& s, const ChartGraph& g, double min_length) {
  std::vector<ChartProblem> out;
  if (min_length <= 0 && s.V.rows()) min_length = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm() / 30.0;
  const std::vector<std::vector<int>> vt = vertex_triangles(s);
  for (const auto& c : g.curves) {
    const CurveConvexity cc = curve_convexity(s, g, vt, c);
    if (!cc.mixed(min_length)) continue;
    char b[120];
    std::snprintf(b, sizeof b, " (%.3g convex, %.3g concave of %.3g)", cc.convex_length, cc.concave_length, cc.length);
    out.push_back({ProblemKind::MixedConvexity, {c.left, c.right}, cc.concave.front(),
                   "the curve between " + chart_name(g, c.left) + " and " + chart_name(g, c.right) +
                       " is a convex edge in part and a concave one in part" + b + ", concave from " +
                       vertex_text(s, cc.concave.front())});
  }
  return out;
}

namespace {

// Area-weighted n . axis of each label over the chart's triangles (index label - 1).
std::array<double, 6> label_fit(const mesh::SurfaceMesh& s, const ChartGraph& g, int chart) {
  std::array<double, 6> fit{};
  for (int f = 0; f < s.F.rows(); ++f) {
    if (g.region(f) != chart) continue;
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
  for (int ci : g.region_curves[chart]) {
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
    const Eigen::MatrixXi TT = adjacency_of(s, g);
    for (int l = 1; l <= 6; ++l) {
      if (l == g.label[chart] || (!joins.count(l) && fit[l - 1] <= 0)) continue;
      for (int f = 0; f < s.F.rows(); ++f) t.patch(f) = g.region(f) == chart ? l : s.patch(f);
      const ChartGraph tg = chart_graph(t, TT);
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
    if (g.region(f) == chart) label(f) = best;
  return label;
}

Eigen::VectorXi relabel_band(const mesh::SurfaceMesh& s, const ChartGraph& g, int chart, const std::vector<int>& curve,
                             double width) {
  const segmentation::TriangleGeometry geo = segmentation::triangle_geometry(s);
  const Eigen::MatrixXi TT = adjacency_of(s, g);
  const int axis = (g.label[chart] - 1) / 2;
  std::set<int> on_curve(curve.begin(), curve.end());
  auto distance = [&](int f) {
    double d = std::numeric_limits<double>::infinity();
    for (int v : curve) d = std::min(d, (geo.centroid.row(f) - s.V.row(v)).norm());
    return d;
  };
  Eigen::VectorXi label = s.patch;
  std::vector<char> seen(s.F.rows(), 0);
  std::vector<int> stack;
  for (int f = 0; f < s.F.rows(); ++f)
    if (g.region(f) == chart)
      for (int k = 0; k < 3; ++k)
        if (on_curve.count(s.F(f, k)) && !seen[f]) { seen[f] = 1; stack.push_back(f); }
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    int best = -1;
    double best_fit = -std::numeric_limits<double>::infinity();
    for (int l = 1; l <= 6; ++l) {
      if ((l - 1) / 2 == axis) continue;
      const double fit = geo.normal.row(f).dot(segmentation::label_axis(l));
      if (fit > best_fit) { best_fit = fit; best = l; }
    }
    label(f) = best;
    for (int k = 0; k < 3; ++k) {
      const int h = TT(f, k);
      if (h >= 0 && !seen[h] && g.region(h) == chart && distance(h) <= width) { seen[h] = 1; stack.push_back(h); }
    }
  }
  return label;
}

namespace {

// Curves (or crease sides) tried per round of the band repairs.
constexpr size_t kMaxBandCurves = 4;
// Where a TimeoutError says the repair stopped.
const char* const kWhere = "autopolycube (label repair)";

// Area-weighted loss of normal fit, sum of area * (n . axis(old) - n . axis(new)), of a relabelling.
double fit_loss(const mesh::SurfaceMesh& s, const Eigen::VectorXi& label) {
  double loss = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (label(f) == s.patch(f)) continue;
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
    const Eigen::Vector3d n = 0.5 * (b - a).cross(d - a);
    loss += n.dot(segmentation::label_axis(s.patch(f))) - n.dot(segmentation::label_axis(label(f)));
  }
  return loss;
}

// Triangle-level repair of two charts of opposite labels that share a curve: a band of triangles
// along the curve, on either side, takes the best-fitting label of the other two axes (a bend of
// the polycube between the two charts). The band that leaves the fewest problems wins, then the
// one losing the least normal fit per unit area (to 0.01), then the widest (a longer bend leaves
// more material between a hole's wall and the face it leaves); an empty result when none leaves
// fewer than `problems`.
Eigen::VectorXi repair_opposite_band(const mesh::SurfaceMesh& s, const ChartGraph& g, const ChartCurve& c, int problems,
                                     double width, std::string* what, const Deadline& deadline) {
  Eigen::VectorXi best;
  long best_n = problems;
  double best_loss = 0;
  mesh::SurfaceMesh t = s;
  const Eigen::MatrixXi TT = adjacency_of(s, g);
  for (int chart : {c.left, c.right})
    for (double w : {0.5 * width, width, 2.0 * width, 4.0 * width}) {
      deadline.check(kWhere);
      t.patch = relabel_band(s, g, chart, c.vertices, w);
      const ChartGraph tg = chart_graph(t, TT);
      const long n = static_cast<long>(chart_problems(t, tg, plane_groups(t, tg)).size());
      double area = 0;
      for (int f = 0; f < s.F.rows(); ++f)
        if (t.patch(f) != s.patch(f)) {
          const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), d = s.V.row(s.F(f, 2));
          area += 0.5 * (b - a).cross(d - a).norm();
        }
      const double loss = std::round(100.0 * fit_loss(s, t.patch) / std::max(area, 1e-300)) - 1e-3 * w / width;
      if (n < best_n || (n == best_n && best.size() && loss < best_loss)) {
        best = t.patch;
        best_n = n;
        best_loss = loss;
        if (what) *what = "a band of " + chart_name(g, chart) + " along its curve with " + chart_name(g, chart == c.left ? c.right : c.left);
      }
    }
  return best;
}

// Triangle-level repair of a chart folded over a sharp crease (two of its triangles that share an
// edge and whose normals differ by more than `crease_angle`, e.g. a hole's wall given the label of
// the face it leaves): on one side of the creases, a band of the chart takes the best-fitting
// label of the other two axes. Sides are the parts of the chart between its creases; the band that
// leaves the fewest problems wins, then the one losing the least normal fit; an empty result when
// none leaves fewer than `problems`. Only creases at least `width` long count, and only in the
// charts marked in `only` when given.
Eigen::VectorXi repair_crease_band(const mesh::SurfaceMesh& s, const ChartGraph& g, int problems, double width,
                                   double crease_angle, std::string* what, const std::vector<char>* only,
                                   const Deadline& deadline) {
  const segmentation::TriangleGeometry geo = segmentation::triangle_geometry(s);
  const Eigen::MatrixXi TT = adjacency_of(s, g);
  const double cos_crease = std::cos(crease_angle * M_PI / 180.0);
  const int nf = static_cast<int>(s.F.rows());
  auto crease = [&](int f, int k) {
    const int h = TT(f, k);
    return h >= 0 && g.region(h) == g.region(f) && geo.normal.row(f).dot(geo.normal.row(h)) < cos_crease;
  };
  // Sides: parts of each chart between its creases.
  std::vector<int> side(nf, -1);
  std::vector<std::vector<int>> side_crease_vertices;
  std::vector<int> side_chart;
  std::vector<double> side_crease_length;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (side[f0] >= 0) continue;
    const int id = static_cast<int>(side_chart.size());
    side_chart.push_back(g.region(f0));
    side_crease_vertices.emplace_back();
    side_crease_length.push_back(0);
    std::vector<int> stack{f0};
    side[f0] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int h = TT(f, k);
        if (h < 0 || g.region(h) != g.region(f)) continue;
        if (crease(f, k)) {
          side_crease_vertices[id].push_back(s.F(f, k));
          side_crease_vertices[id].push_back(s.F(f, (k + 1) % 3));
          side_crease_length[id] += (s.V.row(s.F(f, k)) - s.V.row(s.F(f, (k + 1) % 3))).norm();
        } else if (side[h] < 0) {
          side[h] = id;
          stack.push_back(h);
        }
      }
    }
  }
  // At most kMaxBandCurves sides, those with the longest creases (each try rebuilds the chart graph).
  std::vector<std::pair<double, int>> sides;
  for (size_t id = 0; id < side_chart.size(); ++id)
    if (!side_crease_vertices[id].empty() && side_crease_length[id] >= width && (!only || (*only)[side_chart[id]]))
      sides.emplace_back(-side_crease_length[id], static_cast<int>(id));
  std::sort(sides.begin(), sides.end());
  if (sides.size() > kMaxBandCurves) sides.resize(kMaxBandCurves);
  Eigen::VectorXi best;
  long best_n = problems;
  double best_loss = 0;
  mesh::SurfaceMesh t = s;
  for (const auto& [key, id] : sides) {
    // The band grows from the crease inside this side only: a chart made of the side's triangles.
    ChartGraph sg = g;
    for (int f = 0; f < nf; ++f)
      if (g.region(f) == side_chart[id] && side[f] != static_cast<int>(id)) sg.region(f) = -1;
    for (double w : {0.5 * width, width, 2.0 * width}) {
      deadline.check(kWhere);
      t.patch = relabel_band(s, sg, side_chart[id], side_crease_vertices[id], w);
      const ChartGraph tg = chart_graph(t, TT);
      const long n = static_cast<long>(chart_problems(t, tg, plane_groups(t, tg)).size());
      const double loss = fit_loss(s, t.patch);
      if (n < best_n || (n == best_n && best.size() && loss < best_loss)) {
        best = t.patch;
        best_n = n;
        best_loss = loss;
        if (what) *what = "a band of " + chart_name(g, side_chart[id]) + " along a crease inside it";
      }
    }
  }
  return best;
}

// Triangle-level repair of a curve that is convex in part and concave in part (see MixedConvexity):
// a band of one of its two charts along one of the two parts takes the other chart's label. The
// band grows from the part inside the chart, over triangles within `width` of the part's vertices,
// nearer to them than to the chart's other curves and touching none of those, so that it ends where
// the part ends (at a cusp it takes the tip of the chart that the other wraps around). Bands that leave more than
// `problems` chart problems are refused; of the others, the one leaving the fewest chart problems,
// then the fewest mixed curves, then losing the least normal fit wins; an empty result when none
// leaves fewer chart problems or as many and fewer than `mixed_curves` mixed curves.
Eigen::VectorXi repair_mixed_band(const mesh::SurfaceMesh& s, const ChartGraph& g, int problems, int mixed_curves,
                                  double width, std::string* what, const Deadline& deadline) {
  const std::vector<std::vector<int>> vt = vertex_triangles(s);
  std::vector<std::pair<double, int>> mixed;  // the longest curves first
  std::vector<CurveConvexity> parts(g.curves.size());
  for (size_t ci = 0; ci < g.curves.size(); ++ci) {
    parts[ci] = curve_convexity(s, g, vt, g.curves[ci]);
    if (parts[ci].mixed(width)) mixed.emplace_back(-parts[ci].length, static_cast<int>(ci));
  }
  std::sort(mixed.begin(), mixed.end());
  if (mixed.size() > kMaxBandCurves) mixed.resize(kMaxBandCurves);
  const segmentation::TriangleGeometry geo = segmentation::triangle_geometry(s);
  const Eigen::MatrixXi TT = adjacency_of(s, g);
  auto distance = [&](int f, const std::vector<int>& vs) {
    double d = std::numeric_limits<double>::infinity();
    for (int v : vs) d = std::min(d, (geo.centroid.row(f) - s.V.row(v)).norm());
    return d;
  };
  Eigen::VectorXi best;
  long best_n = problems, best_m = mixed_curves;
  double best_loss = 0;
  mesh::SurfaceMesh t = s;
  for (const auto& [key, ci] : mixed) {
    const ChartCurve& c = g.curves[ci];
    const std::set<int> on_curve(c.vertices.begin(), c.vertices.end());
    for (int chart : {c.left, c.right}) {
      const int other = chart == c.left ? c.right : c.left;
      std::vector<int> others;  // vertices of the chart's other curves
      for (int cj : g.region_curves[chart])
        if (cj != ci)
          for (int v : g.curves[cj].vertices)
            if (!on_curve.count(v)) others.push_back(v);
      const std::set<int> blocked(others.begin(), others.end());
      auto touches_others = [&](int f) {
        return blocked.count(s.F(f, 0)) || blocked.count(s.F(f, 1)) || blocked.count(s.F(f, 2));
      };
      for (const std::vector<int>* part : {&parts[ci].concave, &parts[ci].convex})
        for (double w : {width, 2.0 * width}) {
          deadline.check(kWhere);
          const std::set<int> seeds(part->begin(), part->end());
          t.patch = s.patch;
          std::vector<char> seen(s.F.rows(), 0);
          std::vector<int> stack;
          for (int f = 0; f < s.F.rows(); ++f)
            if (g.region(f) == chart)
              for (int k = 0; k < 3; ++k)
                if (seeds.count(s.F(f, k)) && !seen[f] && !touches_others(f)) { seen[f] = 1; stack.push_back(f); }
          while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            t.patch(f) = g.label[other];
            for (int k = 0; k < 3; ++k) {
              const int h = TT(f, k);
              if (h < 0 || seen[h] || g.region(h) != chart || touches_others(h)) continue;
              const double d = distance(h, *part);
              if (d <= w && d < distance(h, others)) { seen[h] = 1; stack.push_back(h); }
            }
          }
          const ChartGraph tg = chart_graph(t, TT);
          const long n = static_cast<long>(chart_problems(t, tg, plane_groups(t, tg)).size());
          if (n > problems) continue;
          const long m = static_cast<long>(mixed_convexity_problems(t, tg, width).size());
          const double loss = fit_loss(s, t.patch);
          if (n < best_n || (n == best_n && m < best_m) || (n == best_n && m == best_m && best.size() && loss < best_loss)) {
            best = t.patch;
            best_n = n;
            best_m = m;
            best_loss = loss;
            if (what)
              *what = "a band of " + chart_name(g, chart) + " along the " + (part == &parts[ci].concave ? "concave" : "convex") +
                      " part of its curve with " + chart_name(g, other);
          }
        }
    }
  }
  return best;
}

}  // namespace

RepairResult repair_labels(const mesh::SurfaceMesh& labels, const RepairOptions& opt) {
  mesh::SurfaceMesh s = labels;
  RepairResult r;
  const double diag = s.V.rows() ? (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm() : 0.0;
  const double width = opt.band_width > 0 ? opt.band_width : diag / 30.0;
  // Labellings met so far (FNV-1a hashes): a repair that comes back to one of them cycles.
  std::set<std::uint64_t> seen;
  auto hash = [](const Eigen::VectorXi& l) {
    std::uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < l.size(); ++i) h = (h ^ static_cast<std::uint64_t>(l(i))) * 1099511628211ull;
    return h;
  };
  for (;;) {
    opt.deadline.check(kWhere);
    const ChartGraph g = chart_graph(s);
    const PlaneGroups pg = plane_groups(s, g);
    auto problems = chart_problems(s, g, pg);
    const bool fresh = seen.insert(hash(s.patch)).second;
    if (problems.empty() && fresh && r.relabelled < opt.max_relabels) {
      // A labelling that is otherwise a polycube's: curves of mixed convexity get a band.
      const auto mixed = mixed_convexity_problems(s, g, width);
      std::string what;
      Eigen::VectorXi band =
          mixed.empty() ? Eigen::VectorXi() : repair_mixed_band(s, g, 0, static_cast<int>(mixed.size()), width, &what, opt.deadline);
      if (band.size()) {
        if (opt.log) opt.log(0, "relabelling " + what + ": " + mixed.front().message);
        s.patch = band;
        ++r.relabelled;
        ++r.banded;
        continue;
      }
      if (!mixed.empty() && opt.log) opt.log(0, "no band repairs " + mixed.front().message);
    }
    if (problems.empty() || r.relabelled >= opt.max_relabels || !fresh) {
      r.remaining = std::move(problems);
      break;
    }
    // The smallest chart named by any problem.
    int chart = -1;
    const ChartProblem* why = nullptr;
    for (const auto& p : problems)
      for (int c : p.charts)
        if (chart < 0 || g.area[c] < g.area[chart]) { chart = c; why = &p; }
    // Slivers narrower than a band are whole-chart repairs; between wider charts, bands first.
    if (g.area[chart] >= width * width) {
      // Opposite charts side by side: a band along their curve (a bend), not a whole chart.
      // At most kMaxBandCurves curves per round, those between the widest charts (each try rebuilds
      // the chart graph).
      bool banded = false;
      std::vector<std::pair<double, int>> opposite;
      for (size_t ci = 0; ci < g.curves.size(); ++ci) {
        const auto& c = g.curves[ci];
        if (!segmentation::are_opposite(g.label[c.left], g.label[c.right])) continue;
        const double narrow = std::min(g.area[c.left], g.area[c.right]);
        if (narrow >= width * width) opposite.emplace_back(-narrow, static_cast<int>(ci));
      }
      std::sort(opposite.begin(), opposite.end());
      if (opposite.size() > kMaxBandCurves) opposite.resize(kMaxBandCurves);
      for (const auto& [key, ci] : opposite) {
        const auto& c = g.curves[ci];
        std::string what;
        Eigen::VectorXi band = repair_opposite_band(s, g, c, static_cast<int>(problems.size()), width, &what, opt.deadline);
        if (band.size() == 0) continue;
        if (opt.log) opt.log(0, "relabelling " + what);
        s.patch = band;
        banded = true;
        break;
      }
      if (!banded) {
        // A chart that cannot be a polycube face because it is folded over a crease: a band on one
        // side of the crease.
        std::string what;
        std::vector<char> named(g.num_charts(), 0);
        for (const auto& p : problems)
          if (p.kind == ProblemKind::BadTurning) named[p.charts.front()] = 1;
        Eigen::VectorXi band =
            repair_crease_band(s, g, static_cast<int>(problems.size()), width, opt.crease_angle, &what, &named, opt.deadline);
        if (band.size()) {
          if (opt.log) opt.log(0, "relabelling " + what);
          s.patch = band;
          banded = true;
        }
      }
      if (banded) {
        ++r.relabelled;
        ++r.banded;
        continue;
      }
    }
    if (opt.log) opt.log(0, "relabelling " + chart_name(g, chart) + ": " + why->message);
    s.patch = relabel_chart(s, g, chart, static_cast<int>(problems.size()));
    ++r.relabelled;
  }
  r.label = s.patch;
  return r;
}

}  // namespace hexdom::autopolycube
