#include "hexdom/mesh/remesh_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <queue>

#include "hexdom/common/interrupt.h"

namespace hexdom::mesh::remesh {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// Smallest interior angle of a triangle, radians (0 for a degenerate one): the angle opposite
/// the shortest side.
double min_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (ab == 0 || bc == 0 || ca == 0) return 0;
  Eigen::Vector3d u, v;  // the two sides meeting opposite the shortest one
  if (ab <= bc && ab <= ca) {
    u = a - c, v = b - c;
  } else if (bc <= ca) {
    u = b - a, v = c - a;
  } else {
    u = a - b, v = c - b;
  }
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

int rank(Kind k) { return k == Kind::Face ? 0 : k == Kind::Curve ? 1 : 2; }

}  // namespace

SurfaceRemesher::SurfaceRemesher(std::vector<RVertex> V, const std::vector<std::array<int, 3>>& F,
                                 std::vector<int> face, const RemeshGeometry& geometry, RemeshParams params)
    : V_(std::move(V)), F_(F), face_(std::move(face)), alive_(F.size(), 1), vt_(V_.size()),
      geom_(geometry), params_(std::move(params)) {
  for (int t = 0; t < static_cast<int>(F_.size()); ++t)
    for (int v : F_[t]) vt_[v].push_back(t);
  for (auto& v : V_) {
    v.size = std::min(geom_.size_at(v), params_.max_size);
    v.h = v.size;
  }
  // Planar faces: the outward normal, from the (mostly right) start triangles' area-weighted sum.
  int nfaces = 0;
  for (int f : face_) nfaces = std::max(nfaces, f + 1);
  plane_normal_.assign(nfaces, Eigen::Vector3d::Zero());
  for (int t = 0; t < static_cast<int>(F_.size()); ++t)
    if (geom_.is_planar(face_[t])) plane_normal_[face_[t]] += normal(V_[F_[t][0]].p, V_[F_[t][1]].p, V_[F_[t][2]].p);
  for (auto& n : plane_normal_)
    if (n.norm() > 0) n.normalize();
}

bool SurfaceRemesher::is_valid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               int face) const {
  const Eigen::Vector3d& n = plane_normal_[face];
  if (n.squaredNorm() == 0) return true;
  const Eigen::Vector3d nt = normal(a, b, c);
  return nt.dot(n) > 1e-12 * std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
}

void SurfaceRemesher::set_corner_edge(int a, int b, int cad_edge) {
  corner_edge_[{std::min(a, b), std::max(a, b)}] = cad_edge;
}

// ---- topology helpers ----

bool SurfaceRemesher::edge_tris(int a, int b, int& t_ab, int& t_ba) const {
  t_ab = t_ba = -1;
  for (int t : vt_[a]) {
    const Tri& T = F_[t];
    for (int k = 0; k < 3; ++k)
      if (T[k] == a) {
        if (T[(k + 1) % 3] == b) t_ab = t;
        if (T[(k + 2) % 3] == b) t_ba = t;
      }
  }
  return t_ab >= 0 && t_ba >= 0;
}

int SurfaceRemesher::third(int t, int a, int b) const {
  for (int v : F_[t])
    if (v != a && v != b) return v;
  return -1;
}

bool SurfaceRemesher::has_edge(int a, int b) const {
  for (int t : vt_[a])
    for (int v : F_[t])
      if (v == b) return true;
  return false;
}

void SurfaceRemesher::neighbours(int v, std::vector<int>& out) const {
  out.clear();
  for (int t : vt_[v])
    for (int w : F_[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

Eigen::Vector3d SurfaceRemesher::normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const Eigen::Vector3d& c) const {
  return (b - a).cross(c - a);
}

double SurfaceRemesher::target(int a, int b) const { return 0.5 * (V_[a].h + V_[b].h); }

std::vector<std::pair<int, int>> SurfaceRemesher::edges() const {
  std::vector<std::pair<int, int>> out;
  out.reserve(F_.size() * 3 / 2);
  for (int t = 0; t < static_cast<int>(F_.size()); ++t) {
    if (!alive_[t]) continue;
    for (int k = 0; k < 3; ++k) {
      int a = F_[t][k], b = F_[t][(k + 1) % 3];
      if (a < b) out.emplace_back(a, b);
    }
  }
  return out;
}

int SurfaceRemesher::add_triangle(const Tri& tri, int face) {
  const int t = static_cast<int>(F_.size());
  F_.push_back(tri);
  face_.push_back(face);
  alive_.push_back(1);
  for (int v : tri) vt_[v].push_back(t);
  return t;
}

void SurfaceRemesher::remove_from(int v, int t) {
  auto& l = vt_[v];
  l.erase(std::remove(l.begin(), l.end(), t), l.end());
}

void SurfaceRemesher::replace_in_triangle(int t, int from, int to) {
  for (int& v : F_[t])
    if (v == from) v = to;
  remove_from(from, t);
  vt_[to].push_back(t);
}

// ---- operations ----

bool SurfaceRemesher::split(int a, int b, int depth) {
  int t1, t2;
  if (!edge_tris(a, b, t1, t2)) return false;
  const int c = third(t1, a, b), d = third(t2, a, b);
  const Eigen::Vector3d pa = V_[a].p, pb = V_[b].p, mid = 0.5 * (pa + pb);
  const double len = (pb - pa).norm();
  RVertex m;
  if (face_[t1] != face_[t2]) {
    // A CAD edge: the new vertex goes on its curve.
    const RVertex &va = V_[a], &vb = V_[b];
    int e = -1;
    if (va.kind == Kind::Curve && vb.kind == Kind::Curve) {
      e = va.owner;
      m.t = 0.5 * (va.t + vb.t);
    } else if (va.kind == Kind::Curve) {
      e = va.owner, m.t = va.t;
    } else if (vb.kind == Kind::Curve) {
      e = vb.owner, m.t = vb.t;
    } else {
      auto it = corner_edge_.find({std::min(a, b), std::max(a, b)});
      if (it != corner_edge_.end()) e = it->second;
    }
    if (e < 0) return false;
    m.kind = Kind::Curve;
    m.owner = e;
    if (!geom_.project_to_curve(m, mid)) return false;
  } else {
    m.kind = Kind::Face;
    m.owner = face_[t1];
    for (int v : {a, b, c, d})
      if (V_[v].kind == Kind::Face && V_[v].has_uv) {
        m.uv = V_[v].uv;
        m.has_uv = true;
        break;
      }
    if (!geom_.project_to_face(m, mid)) return false;
  }
  if ((m.p - mid).norm() > 0.5 * len) return false;
  const Eigen::Vector3d pc = V_[c].p, pd = V_[d].p;
  const int f1 = face_[t1], f2 = face_[t2];
  const bool planar1 = !plane_normal_[f1].isZero(), planar2 = !plane_normal_[f2].isZero();
  const Eigen::Vector3d n1 = normal(pa, pb, pc), n2 = normal(pb, pa, pd);
  if (!planar1 && (normal(pa, m.p, pc).dot(n1) <= 0 || normal(m.p, pb, pc).dot(n1) <= 0)) return false;
  if (!planar2 && (normal(pb, m.p, pd).dot(n2) <= 0 || normal(m.p, pa, pd).dot(n2) <= 0)) return false;
  for (int x : {a, b, c, d})
    if ((V_[x].p - m.p).norm() < 1e-3 * len) return false;
  // Planar faces: count triangles against the plane's normal before and after.
  auto invalid = [&](int t) {
    return plane_normal_[face_[t]].isZero() ? 0 : !is_valid(V_[F_[t][0]].p, V_[F_[t][1]].p, V_[F_[t][2]].p, face_[t]);
  };
  const int before = (planar1 ? invalid(t1) : 0) + (planar2 ? invalid(t2) : 0);
  m.size = std::min(geom_.size_at(m), params_.max_size);
  // Graded from the edge's ends (h may grow by `gradation` per unit of distance), not their mean:
  // the mean of two small sizes at the ends of a long edge would fill its whole length with them.
  // Graded from the edge's ends (h may grow by `gradation` per unit of distance), not their mean:
  // the mean of two small sizes at the ends of a long edge would fill its whole length with them.
  m.h = std::min({m.size, V_[a].h + params_.gradation * (m.p - pa).norm(), V_[b].h + params_.gradation * (m.p - pb).norm()});
  const int mi = static_cast<int>(V_.size());
  V_.push_back(m);
  vt_.emplace_back();
  replace_in_triangle(t1, b, mi);  // (a b c) -> (a m c)
  add_triangle({mi, b, c}, f1);
  replace_in_triangle(t2, a, mi);  // (b a d) -> (b m d)
  add_triangle({mi, a, d}, f2);
  if (!planar1 && !planar2) return true;
  auto count_around = [&](int v) {
    int n = 0;
    for (int t : vt_[v]) n += invalid(t);
    return n;
  };
  if (count_around(mi) <= before) return true;
  // The curve's point uncovered a face vertex that lay between the chord and the curve (a thin
  // face, a cusp): move the opposite face vertices back inside, or undo the split.
  const RVertex saved_c = V_[c], saved_d = V_[d];
  const int around_c = count_around(c), around_d = count_around(d);
  if (V_[c].kind == Kind::Face) relax_vertex(c);
  if (V_[d].kind == Kind::Face) relax_vertex(d);
  if (count_around(mi) <= before && count_around(c) <= around_c && count_around(d) <= around_d) return true;
  V_[c] = saved_c;
  V_[d] = saved_d;
  collapse(mi, a);  // gives back (a b c) and (b a d)
  // Last resort: remove an opposite face vertex, then try again.
  if (depth >= 2) return false;
  for (int v : {c, d}) {
    if (V_[v].kind != Kind::Face) continue;
    std::vector<int> nb;
    neighbours(v, nb);
    std::stable_partition(nb.begin(), nb.end(), [&](int x) { return x == a || x == b; });
    for (int x : nb)
      if (can_collapse(v, x, false)) {
        collapse(v, x);
        return split(a, b, depth + 1);
      }
  }
  return false;
}

bool SurfaceRemesher::can_collapse(int a, int b, bool strict_length) const {
  const RVertex &va = V_[a], &vb = V_[b];
  if (va.kind == Kind::Corner) return false;
  int t1, t2;
  if (!edge_tris(a, b, t1, t2)) return false;
  const bool feature = face_[t1] != face_[t2];
  if (va.kind == Kind::Curve) {
    if (!feature || vb.kind == Kind::Face) return false;
    if (vb.kind == Kind::Curve && vb.owner != va.owner) return false;
  } else if (feature) {
    return false;
  }
  const int c = third(t1, a, b), d = third(t2, a, b);
  if (c == d || degree(c) <= 3 || degree(d) <= 3) return false;
  // Geometry first (cheapest to fail): no triangle of a's fan turns over, degenerates or gets an
  // edge longer than 4/3 of its target.
  double new_min = kPi;
  for (int t : vt_[a]) {
    if (t == t1 || t == t2) continue;
    Eigen::Vector3d p[3], q[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = V_[F_[t][k]].p;
      q[k] = F_[t][k] == a ? vb.p : p[k];
    }
    if (strict_length)
      for (int k = 0; k < 3; ++k)
        if (F_[t][k] != a && (q[k] - vb.p).squaredNorm() > 16.0 / 9.0 * std::pow(target(F_[t][k], b), 2)) return false;
    const Eigen::Vector3d n_new = normal(q[0], q[1], q[2]);
    if (n_new.norm() <= 1e-14 * (q[1] - q[0]).squaredNorm()) return false;
    if (!plane_normal_[face_[t]].isZero()) {
      if (!is_valid(q[0], q[1], q[2], face_[t])) return false;
    } else if (n_new.normalized().dot(normal(p[0], p[1], p[2]).normalized()) < 0.5) {
      return false;
    }
    new_min = std::min(new_min, min_angle(q[0], q[1], q[2]));
  }
  // Not much worse than the worst triangle it replaces (unless everything stays above 20 degrees).
  if (new_min < 20 * kDeg) {
    double old_min = kPi;
    for (int v : {a, b})
      for (int t : vt_[v]) old_min = std::min(old_min, min_angle(V_[F_[t][0]].p, V_[F_[t][1]].p, V_[F_[t][2]].p));
    if (new_min < old_min) return false;
  }
  // Topology: a and b share exactly the neighbours c and d (link condition) ...
  std::vector<int>& na = scratch_a_;
  std::vector<int>& nb = scratch_b_;
  neighbours(a, na);
  neighbours(b, nb);
  int common = 0;
  for (int x : na)
    if (std::binary_search(nb.begin(), nb.end(), x)) {
      if (x != c && x != d) return false;
      ++common;
    }
  if (common != 2) return false;
  // ... and every CAD edge keeps at least two segments: a's other neighbour along its curve must
  // not be a corner when b is one.
  if (va.kind == Kind::Curve && vb.kind == Kind::Corner)
    for (int x : na) {
      if (x == b || V_[x].kind != Kind::Corner) continue;
      int s1, s2;
      if (edge_tris(a, x, s1, s2) && face_[s1] != face_[s2]) return false;
    }
  return true;
}

void SurfaceRemesher::collapse(int a, int b) {
  int t1, t2;
  edge_tris(a, b, t1, t2);
  for (int t : {t1, t2}) {
    for (int v : F_[t]) remove_from(v, t);
    alive_[t] = 0;
  }
  const std::vector<int> fan = vt_[a];
  for (int t : fan) replace_in_triangle(t, a, b);
  vt_[a].clear();
  V_[a].alive = false;
}

bool SurfaceRemesher::flip_improves(int a, int b, double min_gain) const {
  int t1, t2;
  if (!edge_tris(a, b, t1, t2) || face_[t1] != face_[t2]) return false;
  const int c = third(t1, a, b), d = third(t2, a, b);
  if (c == d || degree(a) <= 3 || degree(b) <= 3 || has_edge(c, d)) return false;
  const Eigen::Vector3d &pa = V_[a].p, &pb = V_[b].p, &pc = V_[c].p, &pd = V_[d].p;
  const Eigen::Vector3d m1 = normal(pc, pa, pd), m2 = normal(pd, pb, pc);
  if (m1.norm() == 0 || m2.norm() == 0) return false;
  const int f = face_[t1];
  const bool planar = !plane_normal_[f].isZero();
  if (planar) {
    // Planar faces: a flip that unfolds triangles is always taken, one that folds never.
    const int invalid_before = !is_valid(pa, pb, pc, f) + !is_valid(pb, pa, pd, f);
    const int invalid_after = !is_valid(pc, pa, pd, f) + !is_valid(pd, pb, pc, f);
    if (invalid_after < invalid_before) return true;
    if (invalid_after > 0) return false;
  }
  // A Delaunay edge (opposite angles summing to at most 180 degrees) already gives the larger
  // smallest angle of the two diagonals of a flat convex quad: skip the exact test.
  const Eigen::Vector3d ca = pa - pc, cb = pb - pc, da = pa - pd, db = pb - pd;
  const double cot_c = ca.dot(cb) / ca.cross(cb).norm(), cot_d = da.dot(db) / da.cross(db).norm();
  if (std::isfinite(cot_c) && std::isfinite(cot_d) && cot_c + cot_d >= 0) return false;
  const double before = std::min(min_angle(pa, pb, pc), min_angle(pb, pa, pd));
  const double after = std::min(min_angle(pc, pa, pd), min_angle(pd, pb, pc));
  if (after <= before + min_gain) return false;
  if (planar) return true;
  const Eigen::Vector3d n1 = normal(pa, pb, pc).normalized(), n2 = normal(pb, pa, pd).normalized();
  const Eigen::Vector3d u1 = m1.normalized(), u2 = m2.normalized(), avg = (n1 + n2).normalized();
  if (u1.dot(avg) < 0.5 || u2.dot(avg) < 0.5) return false;
  // On curved faces, do not trade a flat pair for a folded one.
  if (u1.dot(u2) < std::min(n1.dot(n2), std::cos(20 * kDeg))) return false;
  return true;
}

void SurfaceRemesher::flip(int a, int b) {
  int t1, t2;
  edge_tris(a, b, t1, t2);
  const int c = third(t1, a, b), d = third(t2, a, b);
  F_[t1] = {c, a, d};
  F_[t2] = {d, b, c};
  remove_from(b, t1);
  vt_[d].push_back(t1);
  remove_from(a, t2);
  vt_[c].push_back(t2);
}

bool SurfaceRemesher::relax_vertex(int v) {
  RVertex& rv = V_[v];
  if (rv.kind == Kind::Corner || vt_[v].empty()) return false;
  RVertex moved = rv;
  Eigen::Vector3d q;
  if (rv.kind == Kind::Face) {
    // Density-weighted centroid of the fan (density 1/h^2), moved in the tangent plane.
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), sum = Eigen::Vector3d::Zero();
    double wsum = 0;
    for (int t : vt_[v]) {
      const Tri& T = F_[t];
      const Eigen::Vector3d nt = normal(V_[T[0]].p, V_[T[1]].p, V_[T[2]].p);
      const double h = (V_[T[0]].h + V_[T[1]].h + V_[T[2]].h) / 3.0;
      const double w = 0.5 * nt.norm() / (h * h);
      n += nt;
      sum += w * (V_[T[0]].p + V_[T[1]].p + V_[T[2]].p) / 3.0;
      wsum += w;
    }
    if (wsum <= 0 || n.norm() == 0) return false;
    n.normalize();
    const Eigen::Vector3d c = sum / wsum;
    q = rv.p + (c - rv.p) - n * n.dot(c - rv.p);
    if (!geom_.project_to_face(moved, q)) return false;
  } else {
    // Midway between its two neighbours along the CAD edge.
    std::vector<int> nb, along;
    neighbours(v, nb);
    for (int x : nb) {
      int s1, s2;
      if (edge_tris(v, x, s1, s2) && face_[s1] != face_[s2]) along.push_back(x);
    }
    if (along.size() != 2) return false;
    q = 0.5 * (V_[along[0]].p + V_[along[1]].p);
    if (!geom_.project_to_curve(moved, q)) return false;
  }
  if ((moved.p - q).norm() > 0.5 * rv.h) return false;
  double old_min = kPi, new_min = kPi;
  int invalid_before = 0, invalid_after = 0;
  for (int t : vt_[v]) {
    Eigen::Vector3d p[3], r[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = V_[F_[t][k]].p;
      r[k] = F_[t][k] == v ? moved.p : p[k];
    }
    if (!plane_normal_[face_[t]].isZero()) {
      invalid_before += !is_valid(p[0], p[1], p[2], face_[t]);
      invalid_after += !is_valid(r[0], r[1], r[2], face_[t]);
    } else {
      const Eigen::Vector3d n_old = normal(p[0], p[1], p[2]), n_new = normal(r[0], r[1], r[2]);
      if (n_new.norm() == 0 || n_new.normalized().dot(n_old.normalized()) < 0.5) return false;
    }
    old_min = std::min(old_min, min_angle(p[0], p[1], p[2]));
    new_min = std::min(new_min, min_angle(r[0], r[1], r[2]));
  }
  // Accept a move that unfolds triangles of a planar face; otherwise one that keeps them valid and
  // does not make the worst angle worse (unless it stays above 20 degrees).
  if (invalid_after > invalid_before) return false;
  if (invalid_after == invalid_before && new_min < std::min(old_min, 20 * kDeg)) return false;
  moved.size = std::min(geom_.size_at(moved), params_.max_size);
  rv = moved;
  return true;
}

// ---- passes ----

int SurfaceRemesher::split_long_edges() {
  int total = 0;
  for (int pass = 0; pass < 12; ++pass) {
    check_interrupt("tessellate (remesh)");
    std::vector<std::pair<double, std::pair<int, int>>> todo;
    for (auto [a, b] : edges()) {
      const double r = (V_[a].p - V_[b].p).norm() / target(a, b);
      if (r > 4.0 / 3.0) todo.push_back({-r, {a, b}});
    }
    std::sort(todo.begin(), todo.end());
    int n = 0;
    for (auto& [r, e] : todo) {
      auto [a, b] = e;
      if ((V_[a].p - V_[b].p).norm() <= 4.0 / 3.0 * target(a, b)) continue;
      if (split(a, b)) ++n;
    }
    total += n;
    splits_ += n;
    if (n == 0) break;
  }
  return total;
}

int SurfaceRemesher::collapse_short_edges(bool strict_length) {
  int total = 0;
  for (int pass = 0; pass < 4; ++pass) {
    check_interrupt("tessellate (remesh)");
    std::vector<std::pair<double, std::pair<int, int>>> todo;
    for (auto [a, b] : edges()) {
      const double r = (V_[a].p - V_[b].p).norm() / target(a, b);
      if (r < 0.8) todo.push_back({r, {a, b}});
    }
    std::sort(todo.begin(), todo.end());
    int n = 0;
    for (auto& [r, e] : todo) {
      auto [a, b] = e;
      if (!V_[a].alive || !V_[b].alive || !has_edge(a, b)) continue;
      if ((V_[a].p - V_[b].p).norm() >= 0.8 * target(a, b)) continue;
      if (rank(V_[a].kind) > rank(V_[b].kind)) std::swap(a, b);  // remove the freer vertex
      if (can_collapse(a, b, strict_length)) {
        collapse(a, b);
        ++n;
      } else if (can_collapse(b, a, strict_length)) {
        collapse(b, a);
        ++n;
      }
    }
    total += n;
    if (n == 0) break;
  }
  return total;
}

int SurfaceRemesher::flip_edges() {
  int total = 0;
  // The vertices stay where they are here, so the test of edge (x, y) (flip_improves) changes its
  // answer only when a flip changes one of its two triangles or the degree of x or y (a flip whose
  // four vertices include x or y), or takes away the edge between its opposite vertices c, d (a flip
  // of edge (c, d), whose end points have x and y as neighbours); a new edge (c, d) only turns a yes
  // into a no. So an edge whose last test said no is tested again only when, since the pass before,
  // x or y was in a flip or both were neighbours of a flipped edge's end points. The flips made are
  // the same as when every edge is tested in every pass.
  std::vector<int> in_flip(V_.size(), -2), beside_flip(V_.size(), -2);  // the last pass of each
  std::vector<int> ring;
  for (int pass = 0; pass < 20; ++pass) {
    check_interrupt("tessellate (remesh)");
    auto recent = [&](const std::vector<int>& when, int v) { return when[v] >= pass - 1; };
    int n = 0;
    for (auto [a, b] : edges()) {
      if (pass > 0 && !recent(in_flip, a) && !recent(in_flip, b) && !(recent(beside_flip, a) && recent(beside_flip, b)))
        continue;
      if (!flip_improves(a, b, 1e-3)) continue;
      int t1, t2;
      edge_tris(a, b, t1, t2);
      for (int v : {a, b, third(t1, a, b), third(t2, a, b)}) in_flip[v] = pass;
      for (int v : {a, b}) {
        neighbours(v, ring);
        for (int w : ring) beside_flip[w] = pass;
      }
      flip(a, b);
      ++n;
    }
    total += n;
    if (n == 0) break;
  }
  return total;
}

void SurfaceRemesher::relax() {
  check_interrupt("tessellate (remesh)");
  for (int v = 0; v < static_cast<int>(V_.size()); ++v)
    if (V_[v].alive) relax_vertex(v);
}

void SurfaceRemesher::grade_sizes() {
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int v = 0; v < static_cast<int>(V_.size()); ++v) {
    if (!V_[v].alive) continue;
    V_[v].h = std::min(V_[v].size, params_.max_size);
    queue.push({V_[v].h, v});
  }
  while (!queue.empty()) {
    auto [h, v] = queue.top();
    queue.pop();
    if (h > V_[v].h) continue;
    for (int t : vt_[v])
      for (int w : F_[t]) {
        if (w == v) continue;
        const double cand = h + params_.gradation * (V_[v].p - V_[w].p).norm();
        if (cand < V_[w].h) {
          V_[w].h = cand;
          queue.push({cand, w});
        }
      }
  }
}

int SurfaceRemesher::repair_small_angles(double threshold_deg) {
  const double threshold = threshold_deg * kDeg;
  int fixed = 0;
  const int nt = static_cast<int>(F_.size());
  for (int t = 0; t < nt; ++t) {
    if (!alive_[t]) continue;
    const Tri T = F_[t];
    const Eigen::Vector3d p0 = V_[T[0]].p, p1 = V_[T[1]].p, p2 = V_[T[2]].p;
    if (min_angle(p0, p1, p2) >= threshold) continue;
    // The shortest edge: collapse it if allowed (either way), without the length limit.
    int k_short = 0;
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      const double l = (V_[T[k]].p - V_[T[(k + 1) % 3]].p).norm();
      if (l < best) best = l, k_short = k;
    }
    int a = T[k_short], b = T[(k_short + 1) % 3];
    if (rank(V_[a].kind) > rank(V_[b].kind)) std::swap(a, b);
    if (can_collapse(a, b, false)) {
      collapse(a, b);
      ++fixed;
      continue;
    }
    if (can_collapse(b, a, false)) {
      collapse(b, a);
      ++fixed;
      continue;
    }
    // Otherwise relax its vertices.
    for (int v : T)
      if (relax_vertex(v)) ++fixed;
  }
  return fixed;
}

void SurfaceRemesher::run() {
  if (params_.iterations <= 0) return;  // BRepMesh's triangles as they are
  grade_sizes();
  for (int it = 0; it < params_.iterations; ++it) {
    check_interrupt("tessellate (remesh)");
    const int s = split_long_edges();
    grade_sizes();
    const int c = collapse_short_edges(true);
    const int f = flip_edges();
    relax();
    grade_sizes();
    if (params_.log)
      params_.log(0, "remesh sweep " + std::to_string(it + 1) + ": " + std::to_string(s) + " splits, " +
                         std::to_string(c) + " collapses, " + std::to_string(f) + " flips");
  }
  for (int k = 0; k < 3; ++k) {
    flip_edges();
    relax();
  }
  for (int k = 0; k < 4; ++k) {
    const int r = repair_small_angles(25);
    const int f = flip_edges();
    relax();
    if (r + f == 0) break;
  }
  flip_edges();
}

void SurfaceRemesher::extract(Eigen::MatrixXd& V, Eigen::MatrixXi& F, Eigen::VectorXi& face) const {
  std::vector<int> index(V_.size(), -1);
  int nv = 0, nf = 0;
  for (int t = 0; t < static_cast<int>(F_.size()); ++t) {
    if (!alive_[t]) continue;
    ++nf;
    for (int v : F_[t])
      if (index[v] < 0) index[v] = nv++;
  }
  V.resize(nv, 3);
  for (int v = 0; v < static_cast<int>(V_.size()); ++v)
    if (index[v] >= 0) V.row(index[v]) = V_[v].p.transpose();
  F.resize(nf, 3);
  face.resize(nf);
  int i = 0;
  for (int t = 0; t < static_cast<int>(F_.size()); ++t) {
    if (!alive_[t]) continue;
    for (int k = 0; k < 3; ++k) F(i, k) = index[F_[t][k]];
    face(i++) = face_[t];
  }
}

}  // namespace hexdom::mesh::remesh
