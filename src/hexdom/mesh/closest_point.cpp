#include "hexdom/mesh/closest_point.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace hexdom::mesh {

using Vec = Eigen::Vector3d;

Vec closest_point_on_segment(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double l = ab.squaredNorm();
  if (l <= 0) return a;
  return a + std::clamp((p - a).dot(ab) / l, 0.0, 1.0) * ab;
}

// Ericson, Real-Time Collision Detection, 5.1.5.
Vec closest_point_on_triangle(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = va + vb + vc;
  if (!(denom > 0)) return closest_point_on_segment(p, a, b);  // degenerate triangle
  const double v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;
}

TriangleProjector::TriangleProjector(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const int n = static_cast<int>(F.rows());
  order_.resize(n);
  centroid_.resize(n);
  corners_.resize(3 * static_cast<size_t>(n));  // by triangle while the tree is built
  for (int i = 0; i < n; ++i) {
    order_[i] = i;
    for (int k = 0; k < 3; ++k) corners_[3 * i + k] = V.row(F(i, k)).transpose();
    centroid_[i] = (V.row(F(i, 0)) + V.row(F(i, 1)) + V.row(F(i, 2))).transpose() / 3.0;
  }
  nodes_.reserve(2 * n / 4 + 2);
  if (n > 0) build(0, n);
  std::vector<Vec> leaves(corners_.size());
  slot_.resize(n);
  for (int i = 0; i < n; ++i) {
    slot_[order_[i]] = i;
    for (int k = 0; k < 3; ++k) leaves[3 * i + k] = corners_[3 * order_[i] + k];
  }
  corners_.swap(leaves);
  std::vector<Vec>().swap(centroid_);  // the tree's splits only
}

int TriangleProjector::build(int begin, int end) {
  Node node;
  node.lo = Vec::Constant(std::numeric_limits<double>::max());
  node.hi = Vec::Constant(-std::numeric_limits<double>::max());
  for (int i = begin; i < end; ++i)
    for (int k = 0; k < 3; ++k) {
      node.lo = node.lo.cwiseMin(corners_[3 * order_[i] + k]);
      node.hi = node.hi.cwiseMax(corners_[3 * order_[i] + k]);
    }
  node.begin = begin;
  node.end = end;
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (end - begin > 4) {
    int axis;
    (node.hi - node.lo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return centroid_[a](axis) < centroid_[b](axis); });
    const int l = build(begin, mid);
    const int r = build(mid, end);
    nodes_[id].left = l;
    nodes_[id].right = r;
  }
  return id;
}

Vec TriangleProjector::project(const Vec& p, int* triangle, int hint) const {
  double best = std::numeric_limits<double>::max();
  if (hint >= 0 && hint < static_cast<int>(slot_.size())) {
    // Strictly above the hint's squared distance, which is at least the least one: every node on
    // the way to the first triangle at the least distance is still visited, and that triangle
    // still found first (below, only a strictly nearer triangle replaces the one found).
    const Vec* c = &corners_[3 * slot_[hint]];
    const double d = (closest_point_on_triangle(p, c[0], c[1], c[2]) - p).squaredNorm();
    if (std::isfinite(d)) best = std::max(d * (1 + 1e-9), std::numeric_limits<double>::min());
  }
  Vec result = p;
  int best_tri = -1;
  auto box_dist = [&](const Node& n) { return (p - p.cwiseMax(n.lo).cwiseMin(n.hi)).squaredNorm(); };
  // The tree is balanced (median splits), so the stack stays shallow; reusing one per thread
  // saves an allocation per query, which shows when improvement projects every surface move.
  thread_local std::vector<int> stack;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (box_dist(n) >= best) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const Vec* c = &corners_[3 * i];
        Vec q = closest_point_on_triangle(p, c[0], c[1], c[2]);
        const double d = (q - p).squaredNorm();
        if (d < best) { best = d; result = q; best_tri = order_[i]; }
      }
    } else {
      const double dl = box_dist(nodes_[n.left]), dr = box_dist(nodes_[n.right]);
      if (dl < dr) { stack.push_back(n.right); stack.push_back(n.left); }
      else { stack.push_back(n.left); stack.push_back(n.right); }
    }
  }
  if (triangle) *triangle = best_tri;
  return result;
}

namespace {

// The line a + t d against triangle (p, q, r): Moller and Trumbore (1997), barycentric bounds
// closed. Whether it meets the triangle at one point, and `t` there.
bool line_meets_triangle(const Vec& a, const Vec& d, const Vec& p, const Vec& q, const Vec& r, double* t) {
  const Vec e1 = q - p, e2 = r - p;
  const Vec h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (!(std::abs(det) > 1e-14 * scale)) return false;  // parallel (or degenerate): no single crossing
  const Vec s = a - p;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return false;
  const Vec qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 0 || u + v > 1) return false;
  *t = e2.dot(qv) / det;
  return true;
}

}  // namespace

Vec TriangleProjector::normal(int t) const {
  const Vec* c = &corners_[3 * slot_[t]];
  return (c[1] - c[0]).cross(c[2] - c[0]).normalized();
}

double TriangleProjector::ray_distance(const Vec& origin, const Vec& direction, double from, double up_to,
                                       int skip, int* triangle) const {
  const Vec d = direction.normalized();
  double best = up_to;
  bool hit = false;
  // The slab test of a box against the ray's part [from, best].
  auto reaches = [&](const Node& n) {
    double lo = from, hi = best;
    for (int a = 0; a < 3; ++a) {
      if (d(a) == 0) {
        if (origin(a) < n.lo(a) || origin(a) > n.hi(a)) return false;
        continue;
      }
      double t0 = (n.lo(a) - origin(a)) / d(a), t1 = (n.hi(a) - origin(a)) / d(a);
      if (t0 > t1) std::swap(t0, t1);
      lo = std::max(lo, t0);
      hi = std::min(hi, t1);
      if (lo > hi) return false;
    }
    return true;
  };
  if (triangle) *triangle = -1;
  if (nodes_.empty()) return std::numeric_limits<double>::infinity();
  thread_local std::vector<int> stack;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (!reaches(n)) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const int t = order_[i];
        const Vec* c = &corners_[3 * i];
        double u;
        if (t != skip && line_meets_triangle(origin, d, c[0], c[1], c[2], &u) &&
            u > from && u <= best) {
          best = u;
          hit = true;
          if (triangle) *triangle = t;
        }
      }
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  return hit ? best : std::numeric_limits<double>::infinity();
}

std::vector<int> nearest_triangles(const TriangleProjector& projector, const Eigen::MatrixXd& V,
                                   const std::vector<BoundaryFace>& faces) {
  std::vector<int> out(faces.size(), -1);
  if (projector.empty()) return out;
  for (size_t k = 0; k < faces.size(); ++k) {
    const BoundaryFace& f = faces[k];
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < f.n; ++i) c += V.row(f.v[i]).transpose();
    projector.project(c / f.n, &out[k]);
  }
  return out;
}

TriangleProjector segment_projector(const Eigen::MatrixXd& V, const std::vector<std::array<int, 2>>& segments) {
  Eigen::MatrixXi S(static_cast<int>(segments.size()), 3);
  for (size_t i = 0; i < segments.size(); ++i)
    S.row(static_cast<int>(i)) << segments[i][0], segments[i][1], segments[i][1];
  return TriangleProjector(V, S);
}

}  // namespace hexdom::mesh
