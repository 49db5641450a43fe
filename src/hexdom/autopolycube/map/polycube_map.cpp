#include "hexdom/autopolycube/map/polycube_map.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <Eigen/LU>
#include <map>
#include <queue>
#include <set>

#include "hexdom/autopolycube/map/untangle_plane_map.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/parametrization/harmonic_map.h"
#include "hexdom/segmentation/axis_labels.h"

namespace hexdom::autopolycube {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// Distance (grid units) within which a computed coordinate counts as lying on a grid line: vertices
// are snapped onto the line, so that cutting along the grid never leaves slivers thinner than this.
constexpr double kSnap = 1e-6;

// Two charts face each other (or away from each other) when their mean normals are opposite within
// 20 degrees: only then is the distance between their centroids a width (a wedge has none).
const double kFacing = std::cos(20.0 * M_PI / 180.0);

struct Order {  // plane group hi lies at least `gap` cells above plane group lo
  int lo, hi;
  int gap = 1;
};

struct Edge {
  int i, j;
  double w;
};

// Edges of the surface with cotangent weights, clamped from below to a small positive fraction of
// the mean so that every system below is positive definite.
std::vector<Edge> weighted_edges(const mesh::SurfaceMesh& s) {
  const Sparse L = parametrization::cotmatrix(s.V, s.F);
  std::vector<Edge> e;
  double sum = 0;
  for (int k = 0; k < L.outerSize(); ++k)
    for (Sparse::InnerIterator it(L, k); it; ++it)
      if (it.row() < it.col()) {
        e.push_back({static_cast<int>(it.row()), static_cast<int>(it.col()), it.value()});
        sum += std::abs(it.value());
      }
  const double floor = 1e-3 * sum / std::max<size_t>(e.size(), 1);
  for (auto& x : e) x.w = std::max(x.w, floor);
  return e;
}

// Orientation of triangle f in the plane of its chart (axis a, outward sign sg): twice the signed area
// of its projection onto the in-plane axes (a+1, a+2), times sg.
double plane_area(const Eigen::MatrixXd& D, const Eigen::MatrixXi& F, int f, int a, int sg) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const Eigen::RowVector3d p = D.row(F(f, 0)), q = D.row(F(f, 1)), r = D.row(F(f, 2));
  return sg * ((q(b) - p(b)) * (r(c) - p(c)) - (r(b) - p(b)) * (q(c) - p(c)));
}

// Mean-value weights (Floater), one row per vertex; not symmetric.
void mean_value_rows(const mesh::SurfaceMesh& s, const std::vector<int>& tris, std::vector<Edge>& out) {
  for (int f : tris)
    for (int k = 0; k < 3; ++k) {
      const int i = s.F(f, k), j = s.F(f, (k + 1) % 3), o = s.F(f, (k + 2) % 3);
      const Eigen::Vector3d eij = s.V.row(j) - s.V.row(i), eio = s.V.row(o) - s.V.row(i);
      const double ang = std::atan2(eij.cross(eio).norm(), eij.dot(eio));
      const double t = std::tan(0.5 * ang);
      out.push_back({i, j, t / std::max(eij.norm(), 1e-300)});
      out.push_back({i, o, t / std::max(eio.norm(), 1e-300)});
    }
}

// Moves interior vertices of folded triangles of one chart, each to the point of its star farthest
// from the lines of its opposite edges (the Chebyshev centre of the star's kernel), until nothing is
// folded or no move helps. Returns the triangles still folded.
int untangle_chart(Eigen::MatrixXd& D, const Eigen::MatrixXi& F, const std::vector<int>& tris, const std::vector<int>& slot,
                   int a, int sg, int rounds) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  std::map<int, std::vector<std::pair<int, int>>> star;  // interior vertex -> opposite edges (q, r) in order
  std::map<int, std::vector<int>> vtris;
  for (int f : tris)
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k);
      if (slot[v] < 0) continue;
      star[v].push_back({F(f, (k + 1) % 3), F(f, (k + 2) % 3)});
      vtris[v].push_back(f);
    }
  auto folded = [&]() {
    std::vector<int> out;
    for (int f : tris)
      if (plane_area(D, F, f, a, sg) <= 0) out.push_back(f);
    return out;
  };
  std::vector<int> bad = folded();
  std::set<int> active;
  for (int round = 0; round < rounds && !bad.empty(); ++round) {
    // The vertices of folded triangles, then their neighbours as rounds go by.
    for (int f : bad)
      for (int k = 0; k < 3; ++k)
        if (slot[F(f, k)] >= 0) active.insert(F(f, k));
    if (round > 0 && round % 5 == 0) {
      std::set<int> grown = active;
      for (int v : active)
        for (const auto& e : star[v])
          for (int u : {e.first, e.second})
            if (slot[u] >= 0) grown.insert(u);
      active = std::move(grown);
    }
    for (int v : active) {
      const auto& st = star[v];
      const int n = static_cast<int>(st.size());
      if (n < 3) continue;
      std::vector<Eigen::Vector2d> beta(n);
      std::vector<double> alpha(n);
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector2d q(D(st[k].first, b), D(st[k].first, c)), r(D(st[k].second, b), D(st[k].second, c));
        const Eigen::Vector2d w = q - r;
        const double L = std::max(w.norm(), 1e-300);
        beta[k] = sg * Eigen::Vector2d(w(1), -w(0)) / L;
        alpha[k] = sg * (q(0) * r(1) - q(1) * r(0)) / L;
      }
      auto worst = [&](const Eigen::Vector2d& p) {
        double t = 1e300;
        for (int k = 0; k < n; ++k) t = std::min(t, alpha[k] + beta[k].dot(p));
        return t;
      };
      Eigen::Vector2d best(D(v, b), D(v, c));
      double best_t = worst(best);
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          for (int k = j + 1; k < n; ++k) {
            Eigen::Matrix3d M;
            M << beta[i](0), beta[i](1), -1, beta[j](0), beta[j](1), -1, beta[k](0), beta[k](1), -1;
            const Eigen::Vector3d rhs(-alpha[i], -alpha[j], -alpha[k]);
            const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
            if (!lu.isInvertible()) continue;
            const Eigen::Vector3d x = lu.solve(rhs);
            const Eigen::Vector2d p = x.head<2>();
            const double t = worst(p);
            if (t > best_t + 1e-12) { best_t = t; best = p; }
          }
      D(v, b) = best(0);
      D(v, c) = best(1);
    }
    bad = folded();
  }
  return static_cast<int>(bad.size());
}

// Puts the plane groups of axis a on integers: least squares toward the continuous offsets (area
// weighted) subject to x_hi - x_lo >= gap for every order (Hildreth's method), then a push along the
// order graph for exact feasibility and rounding (which keeps differences >= gap, gaps being integers).
void quantize_axis(int a, const std::vector<Order>& ord, const PlaneGroups& pg, PolycubeMap& m,
                   const std::vector<double>& weight, double h, const ChartGraph& g) {
  const int ng = pg.num_groups();
  // Least squares toward the continuous offsets subject to x_hi - x_lo >= gap (Hildreth's method).
  std::vector<double> x(ng, 0);
  for (int gi = 0; gi < ng; ++gi) x[gi] = (m.offset(gi) - m.origin(a)) / h;
  const std::vector<double> target = x;
  double wsum = 0;
  int nga = 0;
  for (int gi = 0; gi < ng; ++gi)
    if (pg.axis[gi] == a) { wsum += weight[gi]; ++nga; }
  std::vector<double> w(ng, 1.0);
  for (int gi = 0; gi < ng; ++gi)
    if (pg.axis[gi] == a) w[gi] = std::max(weight[gi] / std::max(wsum / std::max(nga, 1), 1e-300), 1e-3);
  std::vector<double> lambda(ord.size(), 0);
  for (int sweep = 0; sweep < 5000; ++sweep) {
    double worst = 0;
    for (size_t k = 0; k < ord.size(); ++k) {
      const int lo = ord[k].lo, hi = ord[k].hi;
      const double slack = x[hi] - x[lo] - ord[k].gap;
      worst = std::max(worst, -slack);
      const double nl = std::max(0.0, lambda[k] - slack / (1.0 / w[hi] + 1.0 / w[lo]));
      const double dl = nl - lambda[k];
      lambda[k] = nl;
      x[hi] += dl / w[hi];
      x[lo] -= dl / w[lo];
    }
    if (worst < 1e-9) break;
  }
  // Exact feasibility: push along the order graph in topological order (a cycle is an error).
  std::vector<std::vector<std::pair<int, int>>> succ(ng);  // (hi, gap)
  std::vector<int> indeg(ng, 0);
  for (const auto& o : ord) { succ[o.lo].push_back({o.hi, o.gap}); ++indeg[o.hi]; }
  std::queue<int> ready;
  for (int gi = 0; gi < ng; ++gi)
    if (pg.axis[gi] == a && indeg[gi] == 0) ready.push(gi);
  int seen = 0;
  while (!ready.empty()) {
    const int u = ready.front();
    ready.pop();
    ++seen;
    for (const auto& [v, gap] : succ[u]) {
      x[v] = std::max(x[v], x[u] + gap);
      if (--indeg[v] == 0) ready.push(v);
    }
  }
  if (seen != nga) {
    std::string names;
    for (int gi = 0; gi < ng; ++gi)
      if (pg.axis[gi] == a && indeg[gi] > 0)
        for (int c : pg.charts[gi]) names += (names.empty() ? "" : ", ") + chart_name(g, c);
    throw GeometryError(std::string("the charts' curves order the ") + "XYZ"[a] + " planes in a cycle: " + names);
  }
  for (int gi = 0; gi < ng; ++gi)
    if (pg.axis[gi] == a) {
      m.plane(gi) = static_cast<int>(std::floor(x[gi] + 0.5));
      if (std::abs(m.plane(gi) - target[gi]) > 1.0) ++m.pushed;
    }
}

// The inputs every step of polycube_map reads: the surface, its charts, their plane groups and the
// options.
struct MapInputs {
  const mesh::SurfaceMesh& s;
  const ChartGraph& g;
  const PlaneGroups& pg;
  const PolycubeMapOptions& opt;
};

// Step 1, the continuous deformation: along each axis, the coordinates that keep the edges' input
// differences best (weighted least squares, a small pull toward the input) with one unknown per
// plane group for the vertices on its charts; sets m.continuous and the groups' m.offset.
void deform_continuously(const MapInputs& in, const std::vector<Edge>& edges, PolycubeMap& m) {
  const auto& [s, g, pg, opt] = in;
  const int nv = static_cast<int>(s.V.rows()), ng = pg.num_groups();
  double wmean = 0;
  for (const auto& e : edges) wmean += e.w;
  wmean /= std::max<size_t>(edges.size(), 1);
  for (int a = 0; a < 3; ++a) {
    std::vector<int> local(ng, -1);
    int nga = 0;
    for (int gi = 0; gi < ng; ++gi)
      if (pg.axis[gi] == a) local[gi] = nga++;
    std::vector<int> idx(nv, -1);
    int nfree = 0;
    for (int v = 0; v < nv; ++v)
      if (pg.of_vertex(v, a) < 0) idx[v] = nfree++;
    for (int v = 0; v < nv; ++v)
      if (pg.of_vertex(v, a) >= 0) idx[v] = nfree + local[pg.of_vertex(v, a)];
    const int n = nfree + nga;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n), z0 = Eigen::VectorXd::Zero(n), cnt = Eigen::VectorXd::Zero(n);
    for (int v = 0; v < nv; ++v) { z0(idx[v]) += s.V(v, a); cnt(idx[v]) += 1; }
    for (int i = 0; i < n; ++i) z0(i) /= std::max(cnt(i), 1.0);
    Triplets t;
    for (const auto& e : edges) {
      const int p = idx[e.i], q = idx[e.j];
      if (p == q) continue;
      const double d = s.V(e.i, a) - s.V(e.j, a);
      t.emplace_back(p, p, e.w);
      t.emplace_back(q, q, e.w);
      t.emplace_back(p, q, -e.w);
      t.emplace_back(q, p, -e.w);
      b(p) += e.w * d;
      b(q) -= e.w * d;
    }
    const double eps = 1e-8 * wmean;
    for (int i = 0; i < n; ++i) t.emplace_back(i, i, eps);
    b += eps * z0;
    Sparse A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<Sparse> solver(A);
    if (solver.info() != Eigen::Success) throw MeshingError(std::string("polycube deformation: the system along ") + "XYZ"[a] + " is singular");
    const Eigen::VectorXd z = solver.solve(b);
    if (!z.allFinite()) throw MeshingError(std::string("polycube deformation: the solve along ") + "XYZ"[a] + " failed");
    for (int v = 0; v < nv; ++v) m.continuous(v, a) = z(idx[v]);
    for (int gi = 0; gi < ng; ++gi)
      if (pg.axis[gi] == a) m.offset(gi) = z(nfree + local[gi]);
  }
}

// Step 2's first orders, per axis: every curve keeps its direction along its axis and a length of
// at least one cell (more for a curve the offsets shrank, see keep_lengths). Throws GeometryError
// for a closed curve, a curve between opposite labels and a curve without length along its axis.
std::vector<std::vector<Order>> curve_orders(const MapInputs& in, PolycubeMap& m) {
  const auto& [s, g, pg, opt] = in;
  const double h = opt.cell;
  std::vector<std::vector<Order>> order(3);
  for (const auto& c : g.curves) {
    if (c.closed) throw GeometryError(chart_name(g, c.left) + " and " + chart_name(g, c.right) + " meet along a loop without corners");
    const int al = (g.label[c.left] - 1) / 2, ar = (g.label[c.right] - 1) / 2;
    if (al == ar) throw GeometryError(chart_name(g, c.left) + " and " + chart_name(g, c.right) + " have opposite labels and share a curve");
    const int ax = 3 - al - ar, p = c.vertices.front(), q = c.vertices.back();
    const int gp = pg.of_vertex(p, ax), gq = pg.of_vertex(q, ax);
    if (gp < 0 || gq < 0 || gp == gq)
      throw GeometryError("the curve between " + chart_name(g, c.left) + " and " + chart_name(g, c.right) + " has no length along " + "XYZ"[ax]);
    // The curve's direction along its axis is the input's: the planes of its two end corners keep the
    // order they have there (a plane's offset is a compromise over its whole chart, and the input's
    // local order is what keeps the chart's polygon from folding).
    double d = s.V(q, ax) - s.V(p, ax);
    if (d == 0) d = m.offset(gq) - m.offset(gp);
    // A curve the least-squares offsets shrank to a fraction of its input chord (a cone's base rim:
    // the side charts' planes are a compromise between the base and the tip) gets more cells (see
    // keep_lengths), or its nodes are too few and the mesh cuts the round boundary between them (a
    // loss of (2 pi / n)^2 / 6 of a circle's area with n nodes around it).
    int gap = 1;
    if (opt.keep_lengths > 0) {
      double arc = 0;
      for (size_t i = 1; i < c.vertices.size(); ++i) arc += (s.V.row(c.vertices[i]) - s.V.row(c.vertices[i - 1])).norm();
      const double chord = (s.V.row(q) - s.V.row(p)).norm();
      const double span = std::abs(m.offset(gq) - m.offset(gp));
      // Only a curved curve loses volume between its nodes (a pyramid's straight base edges do not).
      double sag = 0;
      const Eigen::Vector3d P = s.V.row(p), Q = s.V.row(q);
      for (int v : c.vertices) {
        const Eigen::Vector3d x = s.V.row(v);
        sag = std::max(sag, (x - P).cross(Q - P).norm() / std::max(chord, 1e-300));
      }
      if (span < opt.keep_lengths * chord && sag >= 0.05 * chord) {
        gap = std::max(1, static_cast<int>(std::floor(opt.length_share * std::min(arc, 1.25 * chord) / h + 0.5)));
        if (gap > static_cast<int>(std::floor(span / h + 0.5)) + 1) ++m.lengthened;
        else gap = 1;
      }
    }
    order[ax].push_back(d >= 0 ? Order{gp, gq, gap} : Order{gq, gp, gap});
  }
  return order;
}

// The straight segment each curve becomes, seen from one of its charts: it lies at the plane of the
// other chart (`at`) and spans the planes of its end corners along its own axis.
struct Segment {
  int chart, other;                // the chart it bounds and the chart on the other side of the curve
  int at, axis, from, to;          // plane groups: `at` (position), `from` / `to` (ends along `axis`)
  double mean;                     // mean input coordinate of the curve along at's axis
  int curve;                       // index into g.curves
};

// Every curve's two segments, and the segments of each chart (indices into `all`).
struct Segments {
  std::vector<Segment> all;
  std::vector<std::vector<int>> of_chart;
};

Segments curve_segments(const MapInputs& in) {
  const auto& [s, g, pg, opt] = in;
  Segments out;
  std::vector<Segment>& segments = out.all;
  for (const auto& c : g.curves) {
    const int al = (g.label[c.left] - 1) / 2, ar = (g.label[c.right] - 1) / 2, ax = 3 - al - ar;
    const int p = c.vertices.front(), q = c.vertices.back();
    for (int side = 0; side < 2; ++side) {
      const int chart = side == 0 ? c.left : c.right, other = side == 0 ? c.right : c.left;
      const int pa = (g.label[other] - 1) / 2;
      double mean = 0;
      for (int v : c.vertices) mean += s.V(v, pa);
      segments.push_back({chart, other, pg.of_chart[other], ax, pg.of_vertex(p, ax), pg.of_vertex(q, ax), mean / c.vertices.size(),
                          static_cast<int>(&c - g.curves.data())});
    }
  }
  out.of_chart.resize(g.num_charts());
  for (size_t i = 0; i < segments.size(); ++i) out.of_chart[segments[i].chart].push_back(static_cast<int>(i));
  return out;
}

// Input order of two parallel segments u, w (same axis): w's position minus u's (along their plane
// axis), averaged over the input range of `axis` that both curves span, where the polylines are
// interpolated; the difference of the whole curves' means when their ranges do not overlap. The
// means alone misorder a curved curve and a short one beside it (a round rim's quarter and the
// outer wall of a bolt hole near the quarter's middle).
double input_order(const MapInputs& in, const Segment& u, const Segment& w) {
  const mesh::SurfaceMesh& s = in.s;
  const auto& cu = in.g.curves[u.curve].vertices;
  const auto& cw = in.g.curves[w.curve].vertices;
  const int ax = u.axis, pa = in.pg.axis[u.at];
  auto range = [&](const std::vector<int>& vs) {
    double lo = 1e300, hi = -1e300;
    for (int v : vs) { lo = std::min(lo, s.V(v, ax)); hi = std::max(hi, s.V(v, ax)); }
    return std::make_pair(lo, hi);
  };
  const auto [ulo, uhi] = range(cu);
  const auto [wlo, whi] = range(cw);
  const double lo = std::max(ulo, wlo), hi = std::min(uhi, whi);
  // Mean position of the polyline's crossings of the line at coordinate t along `ax` (NaN: none).
  auto at = [&](const std::vector<int>& vs, double t) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i + 1 < vs.size(); ++i) {
      const double a = s.V(vs[i], ax), b = s.V(vs[i + 1], ax);
      if (std::min(a, b) > t || std::max(a, b) < t || a == b) continue;
      const double f = (t - a) / (b - a);
      sum += (1 - f) * s.V(vs[i], pa) + f * s.V(vs[i + 1], pa);
      ++n;
    }
    return n ? sum / n : std::nan("");
  };
  double diff = 0;
  int n = 0;
  if (hi > lo) {
    constexpr int kSamples = 16;
    for (int k = 0; k < kSamples; ++k) {
      const double t = lo + (hi - lo) * (k + 0.5) / kSamples;
      const double a = at(cu, t), b = at(cw, t);
      if (std::isfinite(a) && std::isfinite(b)) { diff += b - a; ++n; }
    }
  }
  return n ? diff / n : w.mean - u.mean;
}

using Centroids = std::vector<Eigen::Vector3d>;  // per chart

// Cells between the planes of two charts of opposite labels that bound one chart from opposite
// sides and face each other across a void (a hole's two walls): their input distance along their
// common normal, centroid to centroid, in cells, at least 1. Along the normal and not along the axis,
// so that a tilted hole keeps its width (its walls' centroids are offset along its axis as well).
// A slab's faces (normals pointing away from each other) and a wedge's (normals not opposite)
// keep 1: their least-squares offsets stand.
// `centroid` and `normal`: per chart, its area centroid and mean unit normal.
int width_gap(const MapInputs& in, const Centroids& centroid, const Centroids& normal, int a, int b) {
  const double h = in.opt.cell;
  if (!in.opt.keep_widths || in.g.label[a] == in.g.label[b] || normal[a].dot(normal[b]) > -kFacing) return 1;
  if ((centroid[b] - centroid[a]).dot(normal[a]) <= 0 || (centroid[a] - centroid[b]).dot(normal[b]) <= 0) return 1;
  const Eigen::Vector3d n = (normal[a] - normal[b]).normalized();
  const double d = std::abs((centroid[b] - centroid[a]).dot(n));
  return std::max(1, static_cast<int>(std::floor(d / h + 0.5)));
}

// Step 2's integer planes: quantize every axis under the orders, then add orders where two chart
// sides fall too close, and again until nothing is added. Two parallel segments of one chart whose
// spans overlap or touch must keep their input order, at least one cell apart: otherwise the chart
// pinches (a ring around a hole, a U-shaped face). When the spans overlap and the segments lie on
// charts of opposite labels, as many cells apart as the input width between those charts
// (width_gap): the least-squares offsets of curved charts (the quarters of a round hole) shrink a
// hole or a slab to fewer cells than its width, and its boundary to too few nodes.
void settle_planes(const MapInputs& in, const Segments& segs, const Centroids& centroid, const Centroids& normal,
                   const std::vector<double>& weight, std::vector<std::vector<Order>>& order, PolycubeMap& m) {
  const auto& [s, g, pg, opt] = in;
  m.plane = Eigen::VectorXi::Zero(pg.num_groups());
  std::map<std::pair<int, int>, std::pair<int, size_t>> added;  // (lo, hi) -> (axis, index in order[axis])
  for (int round = 0;; ++round) {
    check_interrupt("autopolycube (quantisation)");
    m.pushed = 0;
    for (int a = 0; a < 3; ++a) quantize_axis(a, order[a], pg, m, weight, opt.cell, g);
    int fresh = 0;
    for (int c = 0; c < g.num_charts(); ++c) {
      const auto& cs = segs.of_chart[c];
      for (size_t i = 0; i < cs.size(); ++i)
        for (size_t j = i + 1; j < cs.size(); ++j) {
          const Segment& u = segs.all[cs[i]];
          const Segment& w = segs.all[cs[j]];
          if (u.axis != w.axis || u.at == w.at) continue;
          const int ulo = std::min(m.plane(u.from), m.plane(u.to)), uhi = std::max(m.plane(u.from), m.plane(u.to));
          const int wlo = std::min(m.plane(w.from), m.plane(w.to)), whi = std::max(m.plane(w.from), m.plane(w.to));
          // Spans that only touch count too: two holes' (or a hole's and the outer boundary's) sides
          // that end at one grid line must not fall on one plane, or the chart pinches between them.
          if (std::min(uhi, whi) < std::max(ulo, wlo) + (opt.separate_touching ? 0 : 1)) continue;  // spans apart
          const double d = input_order(in, u, w);
          if (d == 0) continue;
          const int lo = d > 0 ? u.at : w.at, hi = d > 0 ? w.at : u.at;
          // Across a void the wall below faces up (label +axis); otherwise the input order is not the
          // walls' and the width does not apply.
          const int clo = d > 0 ? u.other : w.other, chi = d > 0 ? w.other : u.other;
          const bool overlap = std::min(uhi, whi) > std::max(ulo, wlo);
          const int gap = overlap && g.label[clo] % 2 == 1 ? width_gap(in, centroid, normal, clo, chi) : 1;
          m.widened += gap > 1;
          if (m.plane(hi) - m.plane(lo) >= gap) continue;
          const auto it = added.find({lo, hi});
          if (it == added.end()) {
            added[{lo, hi}] = {pg.axis[lo], order[pg.axis[lo]].size()};
            order[pg.axis[lo]].push_back({lo, hi, gap});
          } else {
            Order& o = order[it->second.first][it->second.second];
            if (o.gap >= gap) continue;
            o.gap = gap;
          }
          ++fresh;
        }
    }
    if (fresh == 0) break;
    if (round >= 50) throw GeometryError("polycube map: the planes do not settle (separating the sides of pinched charts)");
  }
}

// Step 3's first positions: each vertex on a chart gets its plane's coordinate, and each curve's
// inner vertices lie evenly (by input arc length) between its end corners along its axis.
void place_on_planes(const MapInputs& in, PolycubeMap& m) {
  const auto& [s, g, pg, opt] = in;
  const int nv = static_cast<int>(s.V.rows());
  m.D = Eigen::MatrixXd::Constant(nv, 3, std::nan(""));
  for (int v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a)
      if (pg.of_vertex(v, a) >= 0) m.D(v, a) = m.plane(pg.of_vertex(v, a));
  for (const auto& c : g.curves) {
    const int al = (g.label[c.left] - 1) / 2, ar = (g.label[c.right] - 1) / 2, ax = 3 - al - ar;
    const auto& vs = c.vertices;
    std::vector<double> arc(vs.size(), 0);
    for (size_t i = 1; i < vs.size(); ++i) arc[i] = arc[i - 1] + (s.V.row(vs[i]) - s.V.row(vs[i - 1])).norm();
    const double d0 = m.D(vs.front(), ax), d1 = m.D(vs.back(), ax);
    for (size_t i = 1; i + 1 < vs.size(); ++i) {
      double u = d0 + (d1 - d0) * arc[i] / std::max(arc.back(), 1e-300);
      if (std::abs(u - std::round(u)) < kSnap) u = std::round(u);  // on a grid line, not a hair beside it
      m.D(vs[i], ax) = u;
    }
  }
}

// One chart in its plane: its axis a, outward sign sg, in-plane axes, triangles, and the vertices
// inside it (slot[v] is v's index in `inner` while the chart is mapped, -1 otherwise).
struct ChartPlane {
  int chart, a, sg;
  int ax[2];
  const std::vector<int>& tris;
  std::vector<int> inner;
  int flips(const Eigen::MatrixXd& D, const Eigen::MatrixXi& F) const {
    int n = 0;
    for (int f : tris) n += plane_area(D, F, f, a, sg) <= 0;
    return n;
  }
};

// The chart's inner vertices by a harmonic map with its boundary fixed: cotangent weights first, then
// mean-value weights unless nothing folds; the solution with the fewest folded triangles goes into
// `best`. Returns its folded triangles; MeshingError when both solves fail.
int harmonic_interior(const MapInputs& in, const std::vector<Edge>& edges, const ChartPlane& cp, const std::vector<int>& slot,
                      PolycubeMap& m, Eigen::MatrixXd& best) {
  const int n = static_cast<int>(cp.inner.size());
  int best_flips = -1;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Edge> rows;
    if (pass == 0) {
      for (const auto& e : edges)
        if ((slot[e.i] >= 0 || slot[e.j] >= 0)) { rows.push_back(e); rows.push_back({e.j, e.i, e.w}); }
    } else {
      mean_value_rows(in.s, cp.tris, rows);
    }
    Triplets t;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
    for (const auto& e : rows) {
      const int i = slot[e.i];
      if (i < 0) continue;
      // Only edges inside this chart: both ends are vertices of its triangles.
      t.emplace_back(i, i, e.w);
      if (slot[e.j] >= 0) t.emplace_back(i, slot[e.j], -e.w);
      else for (int q = 0; q < 2; ++q) rhs(i, q) += e.w * m.D(e.j, cp.ax[q]);
    }
    Sparse A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::MatrixXd x;
    if (pass == 0) {
      Eigen::SimplicialLDLT<Sparse> solver(A);
      if (solver.info() != Eigen::Success) continue;
      x = solver.solve(rhs);
    } else {
      Eigen::SparseLU<Sparse> solver;
      solver.analyzePattern(A);
      solver.factorize(A);
      if (solver.info() != Eigen::Success) continue;
      x = solver.solve(rhs);
    }
    if (!x.allFinite()) continue;
    for (int i = 0; i < n; ++i)
      for (int q = 0; q < 2; ++q) m.D(cp.inner[i], cp.ax[q]) = x(i, q);
    const int flips = cp.flips(m.D, in.s.F);
    if (best_flips < 0 || flips < best_flips) { best_flips = flips; best = x; }
    if (flips == 0) break;
  }
  if (best_flips < 0) throw MeshingError("polycube map: the harmonic map of " + chart_name(in.g, cp.chart) + " failed");
  return best_flips;
}

// Step 3 for chart c: its inner vertices (those on no chart boundary) mapped into its plane
// (harmonic_interior, snapped onto grid lines they lie on; untangled where it folds); the
// triangles left folded go into m.flipped[c].
void map_chart(const MapInputs& in, const std::vector<Edge>& edges, const std::vector<int>& tris,
               const std::vector<char>& on_boundary, int c, std::vector<int>& slot, PolycubeMap& m) {
  const auto& [s, g, pg, opt] = in;
  const int nv = static_cast<int>(s.V.rows());
  const int a = (g.label[c] - 1) / 2, sg = g.label[c] % 2 == 1 ? 1 : -1;
  ChartPlane cp{c, a, sg, {(a + 1) % 3, (a + 2) % 3}, tris, {}};
  std::vector<int>& inner = cp.inner;
  for (int f : tris)
    for (int k = 0; k < 3; ++k) {
      const int v = s.F(f, k);
      if (!on_boundary[v] && slot[v] < 0) { slot[v] = static_cast<int>(inner.size()); inner.push_back(v); }
    }
  if (!inner.empty()) {
    const int n = static_cast<int>(inner.size());
    Eigen::MatrixXd best;
    const int best_flips = harmonic_interior(in, edges, cp, slot, m, best);
    for (int i = 0; i < n; ++i)
      for (int q = 0; q < 2; ++q) {
        double u = best(i, q);
        const double r = std::round(u);
        if (std::abs(u - r) < kSnap) u = r;  // on a grid line, not a hair beside it
        m.D(inner[i], cp.ax[q]) = u;
      }
    if (best_flips > 0) {  // the barrier untangling, then local moves as a last resort, kept only when they help
      if (opt.untangle) {
        std::vector<char> free_vertex(nv, 0);
        for (int v : inner) free_vertex[v] = 1;
        UntangleOptions uo;
        uo.deadline = opt.deadline;
        const UntangleResult u = untangle_plane_map(s.V, s.F, tris, free_vertex, a, sg, m.D, uo);
        if (opt.log)
          opt.log(0, chart_name(g, c) + ": untangled " + std::to_string(u.folded_before) + " folded triangles to " +
                         std::to_string(u.folded_after) + " (" + std::to_string(u.folded_fixed) + " with no free vertex) in " +
                         std::to_string(u.rounds) + " rounds");
      }
      const int left = cp.flips(m.D, s.F);
      if (left > 0) {
        const Eigen::MatrixXd before = m.D;
        untangle_chart(m.D, s.F, tris, slot, a, sg, 60);
        if (cp.flips(m.D, s.F) >= left) m.D = before;
      }
      for (int v : inner)
        for (int q = 0; q < 2; ++q) {
          double& u = m.D(v, cp.ax[q]);
          const double r = std::round(u);
          if (std::abs(u - r) < kSnap) u = r;
        }
    }
  }
  m.flipped[c] = cp.flips(m.D, s.F);
  if (m.flipped[c] > 0 && opt.log)
    opt.log(1, chart_name(g, c) + ": " + std::to_string(m.flipped[c]) + " triangles stay folded in its plane");
  for (int v : inner) slot[v] = -1;
}

}  // namespace

PolycubeMap polycube_map(const mesh::SurfaceMesh& s, const ChartGraph& g, const PlaneGroups& pg,
                         const PolycubeMapOptions& opt) {
  if (!(opt.cell > 0)) throw GeometryError("the grid spacing must be positive");
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows()), ng = pg.num_groups();
  const double h = opt.cell;
  auto log = [&](const std::string& m) { if (opt.log) opt.log(0, m); };
  PolycubeMap m;
  m.cell = h;
  m.continuous = s.V;
  m.offset = Eigen::VectorXd::Zero(ng);
  const MapInputs in{s, g, pg, opt};

  // ---- 1. continuous deformation, one axis at a time
  const std::vector<Edge> edges = weighted_edges(s);
  deform_continuously(in, edges, m);
  m.origin = m.continuous.colwise().minCoeff().transpose();

  // ---- 2. planes on the grid: every curve keeps its direction and a length of at least one cell
  std::vector<std::vector<Order>> order = curve_orders(in, m);
  if (m.lengthened > 0) log("polycube map: " + std::to_string(m.lengthened) + " curves shrunk by the least-squares offsets keep the cells of their input length");
  for (const auto& sep : opt.separate) {
    if (sep.first < 0 || sep.second < 0 || sep.first >= ng || sep.second >= ng || pg.axis[sep.first] != pg.axis[sep.second])
      throw GeometryError("polycube map: plane groups " + std::to_string(sep.first) + " and " + std::to_string(sep.second) +
                          " cannot be separated");
    order[pg.axis[sep.first]].push_back({sep.first, sep.second});
  }
  std::vector<double> weight(ng, 0);
  for (int c = 0; c < g.num_charts(); ++c) weight[pg.of_chart[c]] += g.area[c];
  const Segments segments = curve_segments(in);
  // Per chart: area centroid and mean unit normal (input), for the widths of opposite charts below.
  std::vector<Eigen::Vector3d> centroid(g.num_charts(), Eigen::Vector3d::Zero()), normal(g.num_charts(), Eigen::Vector3d::Zero());
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d p = s.V.row(s.F(f, 0)), q = s.V.row(s.F(f, 1)), r = s.V.row(s.F(f, 2));
    const Eigen::Vector3d n = (q - p).cross(r - p);  // twice the area, outward
    centroid[g.region(f)] += 0.5 * n.norm() * (p + q + r) / 3.0;
    normal[g.region(f)] += 0.5 * n;
  }
  for (int c = 0; c < g.num_charts(); ++c) {
    if (g.area[c] > 0) centroid[c] /= g.area[c];
    if (normal[c].norm() > 0) normal[c].normalize();
  }
  settle_planes(in, segments, centroid, normal, weight, order, m);

  // ---- 3. positions: planes, straight curves, harmonic chart interiors
  place_on_planes(in, m);
  std::vector<std::vector<int>> chart_tris(g.num_charts());
  for (int f = 0; f < nf; ++f) chart_tris[g.region(f)].push_back(f);
  // A vertex is on a chart boundary exactly when two or more axes' planes give it a coordinate.
  std::vector<char> on_boundary(nv, 0);
  for (int v = 0; v < nv; ++v) on_boundary[v] = (pg.of_vertex.row(v).array() >= 0).count() >= 2;
  m.flipped.assign(g.num_charts(), 0);
  std::vector<int> slot(nv, -1);
  for (int c = 0; c < g.num_charts(); ++c) {
    opt.deadline.check("autopolycube (chart maps)");
    map_chart(in, edges, chart_tris[c], on_boundary, c, slot, m);
  }
  for (int v = 0; v < nv; ++v)
    if (!m.D.row(v).allFinite())
      throw MeshingError("polycube map: vertex " + std::to_string(v + 1) + " got no position (planes " +
                         std::to_string(pg.of_vertex(v, 0)) + " " + std::to_string(pg.of_vertex(v, 1)) + " " +
                         std::to_string(pg.of_vertex(v, 2)) + ", corner " + std::to_string(g.corner_of(v)) + ")");
  log("polycube map: " + std::to_string(ng) + " planes, " + std::to_string(m.pushed) + " pushed by more than a cell");
  return m;
}

mesh::SurfaceMesh polycube_surface(const mesh::SurfaceMesh& s, const PolycubeMap& m) {
  mesh::SurfaceMesh out = s;
  out.V = (m.cell * m.D).rowwise() + m.origin.transpose();
  return out;
}

}  // namespace hexdom::autopolycube
