#include "hexdom/segmentation/check_patches.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/patch_graph.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::segmentation {

namespace {

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

struct Context {
  const mesh::SurfaceMesh& s;
  const PatchGraph& g;
  std::string vertex(int v) const {
    return "vertex " + std::to_string(v + 1) + " (" + fmt(s.V(v, 0)) + ", " + fmt(s.V(v, 1)) + ", " + fmt(s.V(v, 2)) + ")";
  }
  std::string patch(int r) const {
    return "patch " + std::to_string(r + 1) + " (part " + std::to_string(s.patch(g.layout.patches[r].triangles[0])) +
           ", " + label_name(g.axis(r)) + ")";
  }
  Violation make(ViolationKind kind, std::vector<int> patches0, int v, std::string message) const {
    Violation x;
    x.kind = kind;
    for (int r : patches0) x.patches.push_back(r + 1);
    x.vertex = v;
    if (v >= 0) x.location = s.V.row(v).transpose();
    x.message = std::move(message);
    return x;
  }
  /// The vertex of patch r nearest to its centroid.
  int central_vertex(int r) const {
    int best = -1;
    double best_d = 1e300;
    for (int f : g.layout.patches[r].triangles)
      for (int k = 0; k < 3; ++k) {
        const double d = (s.V.row(s.F(f, k)) - g.centroid.row(r)).squaredNorm();
        if (d < best_d) { best_d = d; best = s.F(f, k); }
      }
    return best;
  }
};

/// Turning angle (degrees) of the curve at each vertex, from chords to the points `h` before and
/// after it along the curve (closed curves wrap). Vertices that cannot see h both ways get 0.
std::vector<double> turning(const mesh::SurfaceMesh& s, const std::vector<int>& vs, bool closed, double h) {
  const int n = static_cast<int>(vs.size());
  std::vector<double> arc(n, 0.0), turn(n, 0.0);
  for (int i = 1; i < n; ++i) arc[i] = arc[i - 1] + (s.V.row(vs[i]) - s.V.row(vs[i - 1])).norm();
  const double total = arc[n - 1];
  if (total <= 0 || (!closed && total < 2 * h) || (closed && total < 3 * h)) return turn;
  auto point_at = [&](double t) -> Eigen::Vector3d {
    if (closed) t = std::fmod(std::fmod(t, total) + total, total);
    t = std::clamp(t, 0.0, total);
    const int j = static_cast<int>(std::upper_bound(arc.begin(), arc.end(), t) - arc.begin());
    if (j <= 0) return s.V.row(vs[0]).transpose();
    if (j >= n) return s.V.row(vs[n - 1]).transpose();
    const double len = arc[j] - arc[j - 1], w = len > 0 ? (t - arc[j - 1]) / len : 0;
    return ((1 - w) * s.V.row(vs[j - 1]) + w * s.V.row(vs[j])).transpose();
  };
  for (int i = closed ? 0 : 1; i < n - 1; ++i) {  // a closed curve repeats its first vertex last
    if (!closed && (arc[i] < h || total - arc[i] < h)) continue;
    const Eigen::Vector3d p = s.V.row(vs[i]).transpose();
    const Eigen::Vector3d a = p - point_at(arc[i] - h), b = point_at(arc[i] + h) - p;
    if (a.norm() == 0 || b.norm() == 0) continue;
    turn[i] = std::acos(std::clamp(a.dot(b) / (a.norm() * b.norm()), -1.0, 1.0)) * 180.0 / M_PI;
  }
  return turn;
}

/// One report per patch: its id, axis, normal, area, size, first loop's corners and curves.
std::vector<PatchReport> patch_reports(const mesh::SurfaceMesh& s, const PatchGraph& g, const CheckOptions& opt) {
  std::vector<PatchReport> out;
  const std::set<int> tri_ids(opt.triangular_ids.begin(), opt.triangular_ids.end());
  for (int r = 0; r < g.num_patches(); ++r) {
    const auto& p = g.layout.patches[r];
    PatchReport pr;
    pr.patch = r + 1;
    pr.id = s.patch(p.triangles[0]);
    pr.orientation = g.axis(r);
    pr.normal = g.normal.row(r).transpose();
    pr.area = g.area(r);
    pr.triangles = static_cast<int>(p.triangles.size());
    pr.curves = static_cast<int>(g.patch_curves(r).size());
    pr.loops = p.num_loops;
    pr.euler = g.euler[r];
    for (int c : p.corners) pr.corners.push_back(p.loop[c]);
    for (int c : g.patch_curves(r)) {
      const PatchCurve& cv = g.curves[c >= 0 ? c : ~c];
      pr.neighbours.push_back((c >= 0 ? cv.right : cv.left) + 1);
    }
    pr.triangular = tri_ids.empty() ? pr.curves == 3 : tri_ids.count(pr.id) > 0;
    out.push_back(std::move(pr));
  }
  return out;
}

}  // namespace

std::string kind_name(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::OppositeOrientations: return "opposite_orientations";
    case ViolationKind::TwoPatchCorner: return "two_patch_corner";
    case ViolationKind::CurveCount: return "curve_count";
    case ViolationKind::NotDisk: return "not_disk";
  }
  return "?";
}

PatchCheck check_patches(const mesh::SurfaceMesh& s, const CheckOptions& opt) {
  check_surface(s);
  const PatchGraph g = patch_graph(s);
  const Context cx{s, g};
  const auto& L = g.layout;
  const int np = g.num_patches(), nf = static_cast<int>(s.F.rows()), nv = static_cast<int>(s.V.rows());
  const Eigen::MatrixXi TT = mesh::triangle_adjacency(s.F);
  PatchCheck out;
  out.corners = L.corners;
  out.curves = static_cast<int>(g.curves.size());

  out.patches = patch_reports(s, g, opt);

  // 1) Opposite orientations sharing a boundary.
  std::map<std::pair<int, int>, std::vector<int>> shared;  // patch pair -> vertices of shared edges
  std::vector<int> boundary_degree(nv, 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int h = TT(f, k);
      if (h < f || L.region(h) == L.region(f)) continue;
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      ++boundary_degree[a];
      ++boundary_degree[b];
      auto& vs = shared[{std::min(L.region(f), L.region(h)), std::max(L.region(f), L.region(h))}];
      vs.push_back(a);
      vs.push_back(b);
    }
  const double cos_opposite = std::cos(opt.opposite_angle * M_PI / 180.0);
  for (const auto& [pair, vs] : shared) {
    const auto [a, b] = pair;
    if (!are_opposite(g.axis(a), g.axis(b))) continue;
    if (g.normal.row(a).dot(g.normal.row(b)) >= cos_opposite) continue;
    const int v = vs[vs.size() / 2];
    out.violations.push_back(cx.make(ViolationKind::OppositeOrientations, {a, b}, v,
        cx.patch(a) + " and " + cx.patch(b) + " have opposite orientations and share a boundary of " +
        std::to_string(vs.size() / 2) + " edge" + (vs.size() > 2 ? "s" : "") + " at " + cx.vertex(v)));
  }

  // 2) Corners shared by fewer than three patches: where boundary curves branch between two
  // patches only, closed curves with no corner, and curves that turn sharply between two patches.
  std::vector<std::vector<int>> vpatches(nv);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      auto& v = vpatches[s.F(f, k)];
      if (std::find(v.begin(), v.end(), L.region(f)) == v.end()) v.push_back(L.region(f));
    }
  for (int v = 0; v < nv; ++v)
    if (boundary_degree[v] >= 3 && vpatches[v].size() < 3) {
      std::vector<int> ps = vpatches[v];
      std::sort(ps.begin(), ps.end());
      out.violations.push_back(cx.make(ViolationKind::TwoPatchCorner, ps, v,
          cx.vertex(v) + " joins " + std::to_string(boundary_degree[v]) + " boundary curves but only " +
          std::to_string(ps.size()) + " patches (" + cx.patch(ps[0]) + (ps.size() > 1 ? " and " + cx.patch(ps[1]) : "") +
          "): a corner needs 3"));
    }
  std::vector<double> angle_sum(nv, 0.0);
  std::vector<char> used(nv, 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k);
      const Eigen::Vector3d u = s.V.row(s.F(f, (k + 1) % 3)) - s.V.row(a), w = s.V.row(s.F(f, (k + 2) % 3)) - s.V.row(a);
      angle_sum[a] += std::atan2(u.cross(w).norm(), u.dot(w));
      used[a] = 1;
    }
  for (int v = 0; v < nv; ++v) {
    const double defect = 360.0 - angle_sum[v] * 180.0 / M_PI;
    if (!used[v] || vpatches[v].size() >= 3 || !(std::abs(defect) > opt.corner_defect)) continue;
    std::vector<int> ps = vpatches[v];
    std::sort(ps.begin(), ps.end());
    std::string who = ps.size() == 1 ? "only in " + cx.patch(ps[0]) : "only " + cx.patch(ps[0]) + " and " + cx.patch(ps[1]) + " meet";
    out.violations.push_back(cx.make(ViolationKind::TwoPatchCorner, ps, v,
        cx.vertex(v) + " is a corner of the shape (angle defect " + fmt(std::round(defect)) + " degrees) but " + who +
        " there: a corner needs 3 patches"));
  }
  double mean_edge = 0;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) mean_edge += (s.V.row(s.F(f, k)) - s.V.row(s.F(f, (k + 1) % 3))).norm();
  mean_edge /= 3.0 * nf;
  for (const PatchCurve& c : g.curves) {
    const auto pair = std::vector<int>{std::min(c.left, c.right), std::max(c.left, c.right)};
    const std::string between = "the boundary between " + cx.patch(pair[0]) + " and " + cx.patch(pair[1]);
    if (c.closed) {
      const int v = c.vertices[c.vertices.size() / 2];
      out.violations.push_back(cx.make(ViolationKind::TwoPatchCorner, pair, v,
          between + " is a closed curve without corners (no third patch meets it), through " + cx.vertex(v)));
    }
    if (!(opt.corner_angle > 0)) continue;
    const std::vector<double> turn = turning(s, c.vertices, c.closed, opt.turn_window * mean_edge);
    // One report per run of vertices above the threshold, at its sharpest vertex.
    for (size_t i = 0; i < turn.size();) {
      if (turn[i] <= opt.corner_angle) { ++i; continue; }
      size_t best = i;
      for (; i < turn.size() && turn[i] > opt.corner_angle; ++i)
        if (turn[i] > turn[best]) best = i;
      const int v = c.vertices[best];
      out.violations.push_back(cx.make(ViolationKind::TwoPatchCorner, pair, v,
          between + " turns by " + fmt(std::round(turn[best])) + " degrees at " + cx.vertex(v) +
          ", a corner that only these 2 patches share"));
    }
  }

  // 3) Boundary curves per patch, and disks.
  for (int r = 0; r < np; ++r) {
    const PatchReport& pr = out.patches[r];
    if (pr.loops == 0) {
      out.violations.push_back(cx.make(ViolationKind::NotDisk, {r}, cx.central_vertex(r),
          cx.patch(r) + " has no boundary: it covers a whole closed surface"));
      continue;
    }
    if (pr.loops > 1 || pr.euler != 1) {
      const int v = cx.central_vertex(r);
      std::string what = pr.loops > 1 ? "has " + std::to_string(pr.loops) + " boundary loops (holes)"
                                      : "is not a disk (Euler characteristic " + std::to_string(pr.euler) +
                                            ": it touches itself or wraps a handle)";
      out.violations.push_back(cx.make(ViolationKind::NotDisk, {r}, v, cx.patch(r) + " " + what + "; near " + cx.vertex(v)));
      continue;
    }
    const int expected = pr.triangular ? 3 : 4;
    if (pr.curves != expected) {
      const int v = cx.central_vertex(r);
      std::string corners;
      for (size_t i = 0; i < pr.corners.size() && i < 8; ++i) corners += (i ? ", " : "") + std::to_string(pr.corners[i] + 1);
      if (pr.corners.size() > 8) corners += ", ...";
      out.violations.push_back(cx.make(ViolationKind::CurveCount, {r}, v,
          cx.patch(r) + " has " + std::to_string(pr.curves) + " boundary curve" + (pr.curves == 1 ? "" : "s") +
          (pr.triangular ? ": a triangular patch needs 3" : ": a quadrilateral patch needs 4, a triangular one 3") +
          (corners.empty() ? "" : " (corners at vertices " + corners + ")") + "; near " + cx.vertex(v)));
    }
  }
  return out;
}

std::string to_text(const PatchCheck& c, bool list_patches) {
  std::string s;
  int quads = 0, tris = 0;
  for (const auto& p : c.patches) (p.curves == 3 ? tris : quads) += (p.curves == 3 || p.curves == 4);
  if (c.is_valid()) {
    s += "valid: " + std::to_string(c.patches.size()) + " patches (" + std::to_string(quads) + " quadrilateral, " +
         std::to_string(tris) + " triangular), " + std::to_string(c.corners.size()) + " corners, " +
         std::to_string(c.curves) + " boundary curves\n";
  } else {
    s += std::to_string(c.violations.size()) + " violation" + (c.violations.size() == 1 ? "" : "s") + " in " +
         std::to_string(c.patches.size()) + " patches:\n";
    for (const auto& v : c.violations) s += "  [" + kind_name(v.kind) + "] " + v.message + "\n";
  }
  if (list_patches) {
    s += "patch   part  axis  type        curves  loops  triangles  area\n";
    char buf[200];
    for (const auto& p : c.patches) {
      std::snprintf(buf, sizeof buf, "%5d %6d  %4s  %-10s  %6d  %5d  %9d  %.6g\n", p.patch, p.id, label_name(p.orientation).c_str(),
                    p.triangular ? "triangle" : "quad", p.curves, p.loops, p.triangles, p.area);
      s += buf;
    }
  }
  return s;
}

namespace {
std::string json_string(const std::string& t) {
  std::string o = "\"";
  for (char ch : t) {
    if (ch == '"' || ch == '\\') { o += '\\'; o += ch; }
    else if (static_cast<unsigned char>(ch) < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", ch); o += b; }
    else o += ch;
  }
  return o + "\"";
}
std::string json_num(double x) {
  if (!std::isfinite(x)) return "null";
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}
template <class C>
std::string json_ints(const C& v) {
  std::string o = "[";
  bool first = true;
  for (int x : v) { o += (first ? "" : ", ") + std::to_string(x); first = false; }
  return o + "]";
}
}  // namespace

std::string to_json(const PatchCheck& c) {
  std::string s = "{\"valid\": " + std::string(c.is_valid() ? "true" : "false") + ", \"patches\": [";
  for (size_t i = 0; i < c.patches.size(); ++i) {
    const auto& p = c.patches[i];
    s += std::string(i ? ", " : "") + "{\"patch\": " + std::to_string(p.patch) + ", \"id\": " + std::to_string(p.id) +
         ", \"orientation\": " + json_string(label_name(p.orientation)) + ", \"normal\": [" + json_num(p.normal(0)) + ", " +
         json_num(p.normal(1)) + ", " + json_num(p.normal(2)) + "], \"area\": " + json_num(p.area) +
         ", \"triangles\": " + std::to_string(p.triangles) + ", \"type\": " +
         json_string(p.triangular ? "triangle" : "quad") + ", \"curves\": " + std::to_string(p.curves) +
         ", \"loops\": " + std::to_string(p.loops) + ", \"euler\": " + std::to_string(p.euler) +
         ", \"corners\": " + json_ints(p.corners) + ", \"neighbours\": " + json_ints(p.neighbours) + "}";
  }
  s += "], \"corners\": " + json_ints(c.corners) + ", \"curves\": " + std::to_string(c.curves) + ", \"violations\": [";
  for (size_t i = 0; i < c.violations.size(); ++i) {
    const auto& v = c.violations[i];
    s += std::string(i ? ", " : "") + "{\"kind\": " + json_string(kind_name(v.kind)) + ", \"patches\": " +
         json_ints(v.patches) + ", \"vertex\": " + std::to_string(v.vertex) + ", \"location\": [" +
         json_num(v.location(0)) + ", " + json_num(v.location(1)) + ", " + json_num(v.location(2)) +
         "], \"message\": " + json_string(v.message) + "}";
  }
  return s + "]}";
}

}  // namespace hexdom::segmentation
