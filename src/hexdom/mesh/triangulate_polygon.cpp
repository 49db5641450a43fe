#include "hexdom/mesh/triangulate_polygon.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace hexdom::mesh {

namespace {

using P2 = Eigen::Vector2d;

double cross(const P2& a, const P2& b, const P2& c) { return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(); }

double signed_area(const std::vector<P2>& loop) {
  double a = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const P2& p = loop[i];
    const P2& q = loop[(i + 1) % loop.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

/// Orientation of c against the line a-b, with values within `eps` of the line counted as on it.
int orient(const P2& a, const P2& b, const P2& c, double eps) {
  const double d = cross(a, b, c);
  const double tol = eps * (b - a).norm();
  return d > tol ? 1 : (d < -tol ? -1 : 0);
}

bool on_segment(const P2& a, const P2& b, const P2& p, double eps) {
  return p.x() >= std::min(a.x(), b.x()) - eps && p.x() <= std::max(a.x(), b.x()) + eps &&
         p.y() >= std::min(a.y(), b.y()) - eps && p.y() <= std::max(a.y(), b.y()) + eps;
}

/// Segments a-b and c-d cross or touch (within eps).
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d, double eps) {
  const int o1 = orient(a, b, c, eps), o2 = orient(a, b, d, eps), o3 = orient(c, d, a, eps), o4 = orient(c, d, b, eps);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) {
    if (o1 != 0 || o2 != 0) return true;
  }
  if (o1 == 0 && on_segment(a, b, c, eps)) return true;
  if (o2 == 0 && on_segment(a, b, d, eps)) return true;
  if (o3 == 0 && on_segment(c, d, a, eps)) return true;
  if (o4 == 0 && on_segment(c, d, b, eps)) return true;
  return false;
}

/// Segments c-d that cross the open segment a-b properly (not at a shared endpoint).
bool crosses_properly(const P2& a, const P2& b, const P2& c, const P2& d, double eps) {
  if (c == a || c == b || d == a || d == b) return false;
  return segments_meet(a, b, c, d, eps);
}

double loops_scale(const std::vector<std::vector<P2>>& loops) {
  Eigen::AlignedBox2d box;
  for (const auto& l : loops)
    for (const P2& p : l) box.extend(p);
  return box.isEmpty() ? 1.0 : std::max(box.diagonal().norm(), 1e-300);
}

double cr(const P2& u, const P2& v) { return u.x() * v.y() - u.y() * v.x(); }

/// Whether the direction from p to q lies inside the polygon's angle at p (from the direction to
/// `next` counter-clockwise to the direction to `prev`: the interior of a counter-clockwise polygon).
bool inside_cone(const P2& prev, const P2& p, const P2& next, const P2& q) {
  const P2 a = prev - p, b = next - p, d = q - p;
  if (cr(b, a) > 0) return cr(b, d) > 0 && cr(d, a) > 0;  // convex corner
  return !(cr(a, d) >= 0 && cr(d, b) >= 0);                // reflex: anything outside the outer wedge
}

/// Joins hole `hole` (clockwise, point ids) into `poly` (counter-clockwise, point ids) by a bridge from
/// the hole's rightmost point to the nearest point of `poly` seen from it. False when none is seen.
bool bridge_hole(std::vector<int>& poly, const std::vector<int>& hole, const std::vector<std::vector<int>>& others,
                 const std::vector<P2>& pts, double eps) {
  int m = 0;
  for (size_t i = 1; i < hole.size(); ++i) {
    const P2 &a = pts[hole[i]], &b = pts[hole[m]];
    if (a.x() > b.x() || (a.x() == b.x() && a.y() < b.y())) m = static_cast<int>(i);
  }
  const P2 M = pts[hole[m]];
  std::vector<int> order(poly.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return (pts[poly[a]] - M).squaredNorm() < (pts[poly[b]] - M).squaredNorm(); });
  auto blocked_by = [&](const std::vector<int>& loop, const P2& P) {
    for (size_t i = 0; i < loop.size(); ++i)
      if (crosses_properly(M, P, pts[loop[i]], pts[loop[(i + 1) % loop.size()]], eps)) return true;
    return false;
  };
  for (int k : order) {
    const int n = static_cast<int>(poly.size());
    const P2& P = pts[poly[k]];
    if (P == M) continue;
    if (!inside_cone(pts[poly[(k + n - 1) % n]], P, pts[poly[(k + 1) % n]], M)) continue;
    if (blocked_by(poly, P) || blocked_by(hole, P)) continue;
    bool free = true;
    for (const auto& o : others) free = free && !blocked_by(o, P);
    if (!free) continue;
    std::vector<int> joined(poly.begin(), poly.begin() + k + 1);
    for (size_t i = 0; i <= hole.size(); ++i) joined.push_back(hole[(m + i) % hole.size()]);
    joined.push_back(poly[k]);
    joined.insert(joined.end(), poly.begin() + k + 1, poly.end());
    poly.swap(joined);
    return true;
  }
  return false;
}

bool point_in_triangle(const P2& a, const P2& b, const P2& c, const P2& p, double eps) {
  return orient(a, b, p, eps) >= 0 && orient(b, c, p, eps) >= 0 && orient(c, a, p, eps) >= 0;
}

/// Ear clipping of a simple counter-clockwise polygon (point ids; a bridge repeats two of them).
bool clip_ears(const std::vector<int>& poly, const std::vector<P2>& pts, double eps,
               std::vector<std::array<int, 3>>& out) {
  const int n = static_cast<int>(poly.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
  auto is_ear = [&](int i) {
    const P2 &a = pts[poly[prev[i]]], &b = pts[poly[i]], &c = pts[poly[next[i]]];
    if (orient(a, b, c, eps) <= 0) return false;
    for (int j = next[next[i]]; j != prev[i]; j = next[j]) {
      const P2& p = pts[poly[j]];
      if (p == a || p == b || p == c) continue;
      if (point_in_triangle(a, b, c, p, eps)) return false;
    }
    return true;
  };
  int left = n, i = 0, misses = 0;
  while (left > 3) {
    if (is_ear(i)) {
      out.push_back({poly[prev[i]], poly[i], poly[next[i]]});
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      i = prev[i];
      --left;
      misses = 0;
      continue;
    }
    i = next[i];
    if (++misses > left) return false;
  }
  if (orient(pts[poly[prev[i]]], pts[poly[i]], pts[poly[next[i]]], eps) <= 0) return false;
  out.push_back({poly[prev[i]], poly[i], poly[next[i]]});
  return true;
}

}  // namespace

bool loops_intersect(const std::vector<std::vector<Eigen::Vector2d>>& loops, std::string* where) {
  struct Seg {
    P2 a, b;
    int loop, index;
  };
  std::vector<Seg> segs;
  for (size_t l = 0; l < loops.size(); ++l)
    for (size_t i = 0; i < loops[l].size(); ++i)
      segs.push_back({loops[l][i], loops[l][(i + 1) % loops[l].size()], static_cast<int>(l), static_cast<int>(i)});
  const double eps = 1e-12 * loops_scale(loops);
  std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return std::min(s.a.x(), s.b.x()) < std::min(t.a.x(), t.b.x()); });
  for (size_t i = 0; i < segs.size(); ++i) {
    const Seg& s = segs[i];
    const double max_x = std::max(s.a.x(), s.b.x()) + eps;
    for (size_t j = i + 1; j < segs.size() && std::min(segs[j].a.x(), segs[j].b.x()) <= max_x; ++j) {
      const Seg& t = segs[j];
      if (s.loop == t.loop) {
        const int n = static_cast<int>(loops[s.loop].size());
        const int d = std::abs(s.index - t.index);
        if (d == 1 || d == n - 1) continue;  // consecutive: they share a point
      }
      if (segments_meet(s.a, s.b, t.a, t.b, eps)) {
        if (where)
          *where = "segment " + std::to_string(s.index + 1) + " of loop " + std::to_string(s.loop + 1) + " meets segment " +
                   std::to_string(t.index + 1) + " of loop " + std::to_string(t.loop + 1);
        return true;
      }
    }
  }
  return false;
}

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<std::vector<Eigen::Vector2d>>& loops,
                                                    std::string* why) {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return std::vector<std::array<int, 3>>{};
  };
  std::vector<P2> pts;
  std::vector<std::vector<int>> ids(loops.size());
  std::vector<double> areas;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (loops[l].size() < 3) return fail("loop " + std::to_string(l + 1) + " has fewer than three points");
    for (const P2& p : loops[l]) {
      if (!p.allFinite()) return fail("loop " + std::to_string(l + 1) + " has a point that is not finite");
      ids[l].push_back(static_cast<int>(pts.size()));
      pts.push_back(p);
    }
    areas.push_back(signed_area(loops[l]));
  }
  if (loops.empty()) return fail("no loops");
  const double scale = loops_scale(loops), eps = 1e-12 * scale;
  size_t outer = 0;
  for (size_t l = 1; l < loops.size(); ++l)
    if (std::abs(areas[l]) > std::abs(areas[outer])) outer = l;
  for (size_t l = 0; l < loops.size(); ++l)
    if (std::abs(areas[l]) <= 1e-14 * scale * scale) return fail("loop " + std::to_string(l + 1) + " has no area");
  std::string where;
  if (loops_intersect(loops, &where)) return fail("the loops cross or touch (" + where + ")");
  // Outer counter-clockwise, holes clockwise; holes bridged in from the rightmost one on.
  std::vector<int> poly = ids[outer];
  if (areas[outer] < 0) std::reverse(poly.begin(), poly.end());
  std::vector<std::vector<int>> holes;
  for (size_t l = 0; l < loops.size(); ++l) {
    if (l == outer) continue;
    holes.push_back(ids[l]);
    if (areas[l] > 0) std::reverse(holes.back().begin(), holes.back().end());
  }
  auto max_x = [&](const std::vector<int>& h) {
    double x = -INFINITY;
    for (int i : h) x = std::max(x, pts[i].x());
    return x;
  };
  std::sort(holes.begin(), holes.end(), [&](const auto& a, const auto& b) { return max_x(a) > max_x(b); });
  for (size_t h = 0; h < holes.size(); ++h) {
    const std::vector<std::vector<int>> rest(holes.begin() + h + 1, holes.end());
    if (!bridge_hole(poly, holes[h], rest, pts, eps)) return fail("a hole cannot be joined to the outer loop");
  }
  std::vector<std::array<int, 3>> tris;
  if (!clip_ears(poly, pts, eps, tris)) return fail("ear clipping found no ear (the loops are not simple)");
  return tris;
}

}  // namespace hexdom::mesh
