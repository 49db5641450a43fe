#include "hexdom/mesh/surface_check.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/common/format.h"
#include "hexdom/common/interrupt.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/triangle_adjacency.h"

namespace hexdom::mesh {

namespace {

using Vec = Eigen::Vector3d;

Vec vertex(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }

// Where segment (p, q) crosses the plane of triangle (a, b, c), its ends farther than `tol` from
// it on either side, at a point of the triangle (its edges included: two surfaces crossing along a
// line often do so through the other's edges): the crossing point. An end within `tol` of the plane
// is a touch, not a crossing (scanned and remeshed surfaces come within 1e-8 of themselves).
std::optional<Vec> segment_crosses(const Vec& p, const Vec& q, const Vec& a, const Vec& b, const Vec& c, double tol,
                                   double* depth) {
  const Vec n = (b - a).cross(c - a);
  const double nn = n.norm();
  if (!(nn > 0)) return std::nullopt;
  const double dp = n.dot(p - a) / nn, dq = n.dot(q - a) / nn;
  if (!((dp > tol && dq < -tol) || (dp < -tol && dq > tol))) return std::nullopt;
  const Vec x = p + (q - p) * (dp / (dp - dq));
  *depth = std::min(std::abs(dp), std::abs(dq)) / (q - p).norm();
  const double n2 = nn * nn, slack = -1e-9;
  if ((c - b).cross(x - b).dot(n) / n2 < slack || (a - c).cross(x - c).dot(n) / n2 < slack ||
      (b - a).cross(x - a).dot(n) / n2 < slack)
    return std::nullopt;
  return x;
}

// Where triangles A and B, sharing no vertex, lie on each other: every corner of each within `tol`
// of the other's plane and the two overlapping over an area of at least 1e-3 of the smaller one
// (not only along an edge or at a point). Returns the overlap's centre (B clipped by the three
// half-spaces through A's edges, square to A's plane) and its area over the smaller triangle's.
std::optional<Vec> coplanar_overlap(const Vec A[3], const Vec B[3], double tol) {
  const Vec na = (A[1] - A[0]).cross(A[2] - A[0]), nb = (B[1] - B[0]).cross(B[2] - B[0]);
  const double la = na.norm(), lb = nb.norm();
  if (!(la > 0) || !(lb > 0)) return std::nullopt;
  for (int k = 0; k < 3; ++k)
    if (std::abs(na.dot(B[k] - A[0])) > tol * la || std::abs(nb.dot(A[k] - B[0])) > tol * lb) return std::nullopt;
  std::vector<Vec> poly(B, B + 3), next;
  for (int k = 0; k < 3 && !poly.empty(); ++k) {
    const Vec inward = na.cross(A[(k + 1) % 3] - A[k]);  // points into A from its edge k
    auto side = [&](const Vec& x) { return inward.dot(x - A[k]); };
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec &p = poly[i], &q = poly[(i + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) next.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    poly.swap(next);
  }
  if (poly.size() < 3) return std::nullopt;
  Vec twice_area = Vec::Zero(), centre = Vec::Zero();
  for (size_t i = 0; i < poly.size(); ++i) {
    twice_area += poly[i].cross(poly[(i + 1) % poly.size()]);
    centre += poly[i];
  }
  if (twice_area.norm() < 1e-3 * std::min(la, lb)) return std::nullopt;
  return centre / static_cast<double>(poly.size());
}

struct Box {
  Vec lo = Vec::Constant(INFINITY), hi = Vec::Constant(-INFINITY);
  void add(const Vec& p) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  void add(const Box& b) { lo = lo.cwiseMin(b.lo); hi = hi.cwiseMax(b.hi); }
  bool meets(const Box& b) const { return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all(); }
};

// A crossing whose edge reaches this share of its length past the other triangle's plane on both
// sides is deep: bodies overlapping. Shallower ones are local folds (a scanned or remeshed surface
// folding over itself by a fraction of its triangles), which the meshing paths take as they are.
constexpr double kDeep = 0.1;

// A bounding-box tree over the triangles, searched against itself for crossing pairs.
class CrossingSearch {
 public:
  CrossingSearch(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : V_(V), F_(F), TT_(triangle_adjacency(F)) {
    const int n = static_cast<int>(F.rows());
    box_.resize(n);
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    Box all;
    for (int f = 0; f < n; ++f) {
      for (int k = 0; k < 3; ++k) box_[f].add(vertex(V, F(f, k)));
      all.add(box_[f]);
    }
    tol_ = 1e-6 * (n > 0 ? (all.hi - all.lo).norm() : 0.0);
    ring_start_.assign(V.rows() + 1, 0);  // the triangles around each vertex, packed
    for (int f = 0; f < n; ++f)
      for (int k = 0; k < 3; ++k) ++ring_start_[F(f, k) + 1];
    for (Eigen::Index v = 0; v < V.rows(); ++v) ring_start_[v + 1] += ring_start_[v];
    ring_.resize(3 * static_cast<size_t>(n));
    std::vector<int> fill(ring_start_.begin(), ring_start_.end() - 1);
    for (int f = 0; f < n; ++f)
      for (int k = 0; k < 3; ++k) ring_[fill[F(f, k)]++] = f;
    if (n > 0) build(0, n);
  }

  // The first deep crossing, else the deepest shallow one (see Crossing::deep); coplanar() then
  // holds every pair lying on each other.
  std::optional<Crossing> find() {
    if (!nodes_.empty()) pairs(0, 0);
    return found_ ? found_ : shallow_;
  }
  int shallow_pairs() const { return shallow_count_; }
  const std::vector<Crossing>& coplanar() const { return coplanar_; }

 private:
  struct Node {
    Box box;
    int left = -1, right = -1, begin = 0, end = 0;
  };

  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Box b;
    for (int i = begin; i < end; ++i) b.add(box_[order_[i]]);
    nodes_[id].box = b;
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    if (end - begin <= 8) return id;
    int axis;
    (b.hi - b.lo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int x, int y) {
      return box_[x].lo(axis) + box_[x].hi(axis) < box_[y].lo(axis) + box_[y].hi(axis);
    });
    const int l = build(begin, mid), r = build(mid, end);
    nodes_[id].left = l;
    nodes_[id].right = r;
    return id;
  }

  void pairs(int a, int b) {
    if (found_ || !nodes_[a].box.meets(nodes_[b].box)) return;
    const Node &na = nodes_[a], &nb = nodes_[b];
    if (na.left < 0 && nb.left < 0) {
      for (int i = na.begin; i < na.end && !found_; ++i)
        for (int j = (a == b ? i + 1 : nb.begin); j < nb.end && !found_; ++j) test(order_[i], order_[j]);
      return;
    }
    if (a == b) {
      pairs(na.left, na.left);
      pairs(na.right, na.right);
      pairs(na.left, na.right);
    } else if (nb.left < 0 || (na.left >= 0 && na.end - na.begin >= nb.end - nb.begin)) {
      pairs(na.left, b);
      pairs(na.right, b);
    } else {
      pairs(a, nb.left);
      pairs(a, nb.right);
    }
  }

  // Whether the crossing at x of an edge of triangle `seg` through triangle `crossed` is a contact:
  // x on the border of `crossed` (within tol_ of a corner or an edge) where a triangle around that
  // corner, or the one across that edge, holds `seg` in its plane: the surfaces touch there, as
  // solids meeting along a face or overlapping along coplanar faces do (coplanar_overlap judges
  // those), rather than pass through each other.
  bool contact_at_border(int crossed, const Vec& x, int seg) const {
    const Vec corner[3] = {vertex(V_, F_(crossed, 0)), vertex(V_, F_(crossed, 1)), vertex(V_, F_(crossed, 2))};
    const Vec n = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
    for (int k = 0; k < 3; ++k)
      if ((x - corner[k]).norm() <= tol_) {
        const int v = F_(crossed, k);
        for (int i = ring_start_[v]; i < ring_start_[v + 1]; ++i)
          if (holds_in_plane(ring_[i], seg)) return true;
      }
    for (int k = 0; k < 3; ++k) {
      const Vec e = corner[(k + 1) % 3] - corner[k];
      if (std::abs(e.cross(x - corner[k]).dot(n)) <= tol_ * e.norm() && TT_(crossed, k) >= 0 &&
          holds_in_plane(TT_(crossed, k), seg))
        return true;
    }
    return false;
  }

  // Whether every corner of triangle `seg` lies within tol_ of the plane of triangle g.
  bool holds_in_plane(int g, int seg) const {
    const Vec g0 = vertex(V_, F_(g, 0));
    const Vec m = (vertex(V_, F_(g, 1)) - g0).cross(vertex(V_, F_(g, 2)) - g0);
    const double mn = m.norm();
    if (!(mn > 0)) return false;
    for (int i = 0; i < 3; ++i)
      if (std::abs(m.dot(vertex(V_, F_(seg, i)) - g0)) > tol_ * mn) return false;
    return true;
  }

  void test(int s, int t) {
    if (!box_[s].meets(box_[t])) return;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (F_(s, i) == F_(t, j)) return;  // neighbours: touching is not crossing
    const Vec A[3] = {vertex(V_, F_(s, 0)), vertex(V_, F_(s, 1)), vertex(V_, F_(s, 2))};
    const Vec B[3] = {vertex(V_, F_(t, 0)), vertex(V_, F_(t, 1)), vertex(V_, F_(t, 2))};
    double deepest = -1;
    Vec at;
    for (int k = 0; k < 3; ++k) {
      double depth = 0;
      if (auto p = segment_crosses(A[k], A[(k + 1) % 3], B[0], B[1], B[2], tol_, &depth);
          p && depth > deepest && !contact_at_border(t, *p, s))
        deepest = depth, at = *p;
      if (auto p = segment_crosses(B[k], B[(k + 1) % 3], A[0], A[1], A[2], tol_, &depth);
          p && depth > deepest && !contact_at_border(s, *p, t))
        deepest = depth, at = *p;
    }
    if (deepest < 0) {
      if (auto p = coplanar_overlap(A, B, tol_)) {
        const bool same = (A[1] - A[0]).cross(A[2] - A[0]).dot((B[1] - B[0]).cross(B[2] - B[0])) > 0;
        Crossing c{std::min(s, t), std::max(s, t), *p, 0.0, same};
        c.coplanar = same ? Crossing::kSameWay : Crossing::kOpposite;
        coplanar_.push_back(c);
      }
      return;
    }
    Crossing c{std::min(s, t), std::max(s, t), at, deepest, deepest >= kDeep};
    if (c.deep) {
      found_ = c;
    } else {
      ++shallow_count_;
      if (!shallow_ || c.depth > shallow_->depth) shallow_ = c;
    }
  }

  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& F_;
  const Eigen::MatrixXi TT_;  // edge neighbours (triangle_adjacency)
  std::vector<int> ring_start_, ring_;  // vertex v's triangles: ring_[ring_start_[v] .. ring_start_[v + 1])
  std::vector<Box> box_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  double tol_ = 0;  // a touch: within 1e-6 of the diagonal
  std::optional<Crossing> found_, shallow_;
  int shallow_count_ = 0;
  std::vector<Crossing> coplanar_;  // pairs lying on each other, in the order found
};

// Whether point p is inside the closed shell made of `tris` (1) or outside it (0): crossings of a
// ray in a direction no axis-aligned part lines up with, counted by parity; -1 when the ray meets
// the shell within `tol` of p (p lies on it: the parity says nothing).
int inside(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris, const Vec& p, double tol) {
  const Vec d = Vec(0.8731, 0.3917, 0.2903).normalized();
  int crossings = 0;
  for (int f : tris) {
    const Vec a = vertex(V, F(f, 0)), b = vertex(V, F(f, 1)), c = vertex(V, F(f, 2));
    const Vec e1 = b - a, e2 = c - a, h = d.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-300) continue;
    const Vec s = p - a;
    const double u = s.dot(h) / det;
    if (u < 0 || u > 1) continue;
    const Vec q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(q) / det;
    if (std::abs(t) <= tol) return -1;
    if (t > 0) ++crossings;
  }
  return crossings % 2;
}

// Whether shell `tris_i` lies inside shell `tris_j`: the vote of the ray test (inside) from its
// first vertex and its extreme vertices along each axis, those lying on `tris_j` (within `tol`)
// abstaining. A shell inside another has every vertex inside; one touching another from outside,
// or lying on it, has its vertices on it or outside.
bool shell_inside(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris_i,
                  const std::vector<int>& tris_j, double tol) {
  int pick[7] = {F(tris_i[0], 0), -1, -1, -1, -1, -1, -1};
  for (int f : tris_i)
    for (int c = 0; c < 3; ++c) {
      const int v = F(f, c);
      for (int k = 0; k < 3; ++k) {
        if (pick[1 + 2 * k] < 0 || V(v, k) < V(pick[1 + 2 * k], k)) pick[1 + 2 * k] = v;
        if (pick[2 + 2 * k] < 0 || V(v, k) > V(pick[2 + 2 * k], k)) pick[2 + 2 * k] = v;
      }
    }
  int votes = 0;
  for (int v : pick) {
    const int in = inside(V, F, tris_j, vertex(V, v), tol);
    votes += in == 1 ? 1 : in == 0 ? -1 : 0;
  }
  return votes > 0;
}

// The pairs of solids (1-based) that `opposite` (pairs of triangles lying on each other facing
// opposite ways) puts together; throws when both triangles of a pair bound one solid.
std::vector<std::array<int, 2>> touching_solids(const std::vector<Crossing>& opposite, const std::vector<int>& solid,
                                                const std::string& what) {
  std::vector<std::array<int, 2>> pairs;
  for (const Crossing& c : opposite) {
    const int a = solid[c.a], b = solid[c.b];
    if (a == b)
      throw GeometryError(what + fmt(" touches itself: triangles %.0f and %.0f lie on each other facing opposite ways",
                                     c.a + 1.0, c.b + 1.0) +
                          fmt(" at (%.6g, %.6g, %.6g), a wall of no thickness; a solid's surface must not", c.point.x(),
                              c.point.y(), c.point.z()));
    pairs.push_back({std::min(a, b) + 1, std::max(a, b) + 1});
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace

void check_closed_manifold(const SurfaceMesh& s) {
  const int nf = static_cast<int>(s.F.rows());
  if (nf == 0) throw GeometryError("the surface has no triangles");
  // Every half-edge as (undirected edge, f * 3 + k), sorted: an edge's triangles are consecutive,
  // in triangle order. One array and one sort, no per-edge allocation.
  std::vector<std::pair<EdgeKey, int>> half(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a < 0 || a >= s.V.rows()) throw GeometryError("triangle " + std::to_string(f + 1) + " refers to a missing vertex");
      if (a == b) throw GeometryError("triangle " + std::to_string(f + 1) + " is degenerate (repeats vertex " + std::to_string(a + 1) + ")");
      half[3 * static_cast<size_t>(f) + k] = {undirected_edge(a, b), 3 * f + k};
    }
  }
  std::sort(half.begin(), half.end());
  for (size_t i = 0; i < half.size();) {
    size_t j = i + 1;
    while (j < half.size() && half[j].first == half[i].first) ++j;
    const size_t c = j - i;
    if (c != 2)
      throw GeometryError(std::string(c == 1 ? "open surface: boundary" : "non-manifold") + " edge (" +
                          std::to_string(edge_from(half[i].first) + 1) + ", " + std::to_string(edge_to(half[i].first) + 1) +
                          ") is shared by " + std::to_string(c) + " triangle" + (c == 1 ? "" : "s") +
                          " (a closed surface needs 2)");
    i = j;
  }
  // With two triangles per edge, both running it the same way means they disagree on orientation.
  for (size_t i = 0; i < half.size(); i += 2) {
    const int f0 = half[i].second / 3, k0 = half[i].second % 3, f = half[i + 1].second / 3, k = half[i + 1].second % 3;
    const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
    if (s.F(f0, k0) == a)
      throw GeometryError("triangles next to edge (" + std::to_string(a + 1) + ", " + std::to_string(b + 1) +
                          ") are inconsistently oriented (triangle " + std::to_string(f + 1) + ")");
  }
}

std::optional<Crossing> find_self_intersection(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int* shallow_pairs,
                                               std::vector<Crossing>* coplanar) {
  CrossingSearch search(V, F);
  std::optional<Crossing> c = search.find();
  if (shallow_pairs) *shallow_pairs = search.shallow_pairs();
  if (coplanar) *coplanar = search.coplanar();
  if (c && c->deep) return c;
  for (const Crossing& k : search.coplanar())
    if (k.coplanar == Crossing::kSameWay) return k;
  return c;
}

SurfaceCheck check_solid_surface(SurfaceMesh& s, const std::string& what, const SurfaceCheckOptions& opt) {
  try {
    check_closed_manifold(s);
  } catch (const GeometryError& e) {
    throw GeometryError(what + ": " + e.what());
  }
  check_interrupt("check the surface");
  SurfaceCheck r;
  std::vector<Crossing> coplanar;
  if (opt.self_intersection) {
    CrossingSearch search(s.V, s.F);
    const auto c = search.find();
    coplanar = search.coplanar();
    if (c && c->deep)
      throw GeometryError(what + fmt(" crosses itself: triangles %.0f and %.0f cross", c->a + 1.0, c->b + 1.0) +
                          fmt(" at (%.6g, %.6g, %.6g); a solid's surface must not (overlapping bodies written as one "
                              "surface must be united first)",
                              c->point.x(), c->point.y(), c->point.z()));
    if (c)
      r.warnings.push_back(what + fmt(" folds over itself slightly: %.0f pairs of triangles cross by less than a tenth "
                                      "of their edges (the deepest: triangles %.0f and %.0f",
                                      static_cast<double>(search.shallow_pairs()), c->a + 1.0, c->b + 1.0) +
                           fmt(" at (%.6g, %.6g, %.6g)); meshed as it is", c->point.x(), c->point.y(), c->point.z()));
  }
  std::vector<int> shell;
  r.shells = triangle_components(triangle_adjacency(s.F), [](int, int) { return true; }, shell);
  std::vector<std::vector<int>> tris(r.shells);
  std::vector<double> volume(r.shells, 0.0);
  for (int f = 0; f < s.F.rows(); ++f) {
    tris[shell[f]].push_back(f);
    volume[shell[f]] += vertex(s.V, s.F(f, 0)).dot(vertex(s.V, s.F(f, 1)).cross(vertex(s.V, s.F(f, 2)))) / 6.0;
  }
  // Nesting: shells inside an even number of others bound a solid, the others are the cavities of
  // the shell one level further out that holds them.
  std::vector<int> depth(r.shells, 0), solid_of_shell(r.shells, -1);
  const double tol = 1e-6 * (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm();
  std::vector<std::vector<char>> holds(r.shells, std::vector<char>(r.shells, 0));  // holds[j][i]: i inside j
  for (int i = 0; r.shells > 1 && i < r.shells; ++i)
    for (int j = 0; j < r.shells; ++j)
      if (j != i && shell_inside(s.V, s.F, tris[i], tris[j], tol)) {
        holds[j][i] = 1;
        ++depth[i];
      }
  std::vector<char> wrong(r.shells);  // facing the wrong way: turned around below
  for (int i = 0; i < r.shells; ++i) wrong[i] = depth[i] % 2 == 1 ? volume[i] > 0 : volume[i] < 0;
  // Triangles lying on each other, judged with every shell facing as it will: the same way is a
  // volume covered twice; opposite ways, solids that touch (or a wall of no thickness).
  std::vector<Crossing> opposite;
  for (const Crossing& c : coplanar) {
    if ((c.coplanar == Crossing::kSameWay) == (wrong[shell[c.a]] == wrong[shell[c.b]]))
      throw GeometryError(what + fmt(" lies on itself: triangles %.0f and %.0f lie on each other facing the same way",
                                     c.a + 1.0, c.b + 1.0) +
                          fmt(" at (%.6g, %.6g, %.6g); a solid's surface must not (overlapping bodies, or one written "
                              "twice, must be united first)",
                              c.point.x(), c.point.y(), c.point.z()));
    opposite.push_back(c);
  }
  if (r.shells > 1 && !opt.several_solids) {
    const int outer = static_cast<int>(std::count(depth.begin(), depth.end(), 0));
    if (outer > 1)
      throw GeometryError(what + fmt(" has %.0f separate closed shells (solids), none inside another: mesh each solid on "
                                     "its own", static_cast<double>(outer)));
    if (*std::max_element(depth.begin(), depth.end()) > 1)
      throw GeometryError(what + " has a shell inside a cavity (a solid inside another's hole): mesh each solid on its own");
  }
  for (int i = 0; i < r.shells; ++i)
    if (depth[i] % 2 == 0) solid_of_shell[i] = r.solids++;
  for (int i = 0; i < r.shells; ++i)
    if (depth[i] % 2 == 1)
      for (int j = 0; j < r.shells; ++j)
        if (holds[j][i] && depth[j] == depth[i] - 1) solid_of_shell[i] = solid_of_shell[j];
  r.solid.resize(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) r.solid[f] = solid_of_shell[shell[f]];
  r.touching = touching_solids(opposite, r.solid, what);
  for (const auto& [a, b] : r.touching)
    r.warnings.push_back(what + fmt(": solids %.0f and %.0f touch", a + 0.0, b + 0.0) +
                         ": their meshes are made one by one and do not conform where they meet");
  for (int i = 0; i < r.shells; ++i) {
    const bool cavity = depth[i] % 2 == 1;
    if (cavity) ++r.cavities;
    if (!wrong[i]) continue;
    for (int f : tris[i]) std::swap(s.F(f, 1), s.F(f, 2));
    ++r.flipped_shells;
    r.warnings.push_back(what + ": " +
                         (!cavity ? (r.shells > 1 ? (r.solids > 1 ? fmt("the outer shell of solid %.0f", solid_of_shell[i] + 1.0)
                                                                  : std::string("the outer shell"))
                                                  : std::string("the surface"))
                                  : std::string("a cavity's shell")) +
                         fmt(" of %.0f triangles faced ", static_cast<double>(tris[i].size())) +
                         (!cavity ? "inward (inside out)" : "into the solid") + "; turned around");
  }
  return r;
}

std::vector<SurfaceMesh> split_solids(const SurfaceMesh& s, const SurfaceCheck& check) {
  if (check.solids <= 1 || static_cast<Eigen::Index>(check.solid.size()) != s.F.rows()) return {s};
  std::vector<SurfaceMesh> out(check.solids);
  std::vector<int> count(check.solids, 0), node(s.V.rows(), -1), nodes(check.solids, 0);
  for (int k : check.solid) ++count[k];
  for (int k = 0; k < check.solids; ++k) {
    out[k].F.resize(count[k], 3);
    out[k].patch.resize(count[k]);
    count[k] = 0;
  }
  for (int f = 0; f < s.F.rows(); ++f) {  // a vertex belongs to the one solid its triangles do
    const int k = check.solid[f];
    for (int c = 0; c < 3; ++c) {
      int& v = node[s.F(f, c)];
      if (v < 0) v = nodes[k]++;
      out[k].F(count[k], c) = v;
    }
    out[k].patch(count[k]++) = s.patch.rows() == s.F.rows() ? s.patch(f) : 0;
  }
  for (int k = 0; k < check.solids; ++k) out[k].V.resize(nodes[k], 3);
  for (int f = 0; f < s.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) out[check.solid[f]].V.row(node[s.F(f, c)]) = s.V.row(s.F(f, c));
  return out;
}

}  // namespace hexdom::mesh
