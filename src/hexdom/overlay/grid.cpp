#include "hexdom/overlay/grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "hexdom/common/interrupt.h"
#include "hexdom/mesh/closest_point.h"

namespace hexdom::overlay {

std::array<int64_t, 8> Grid::corners(int i, int j, int k) const {
  return {node(i, j, k),         node(i + 1, j, k),         node(i + 1, j + 1, k),     node(i, j + 1, k),
          node(i, j, k + 1),     node(i + 1, j, k + 1),     node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
}

Grid grid_around(const Eigen::MatrixXd& V, const Eigen::Vector3d& h) {
  Grid g;
  const Eigen::Vector3d lo = V.colwise().minCoeff().transpose(), hi = V.colwise().maxCoeff().transpose();
  int n[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = hi(a) - lo(a);
    const int cells = std::max(1, static_cast<int>(std::lround(extent / h(a))));
    g.h(a) = extent > 0 ? extent / cells : h(a);
    n[a] = cells + 3;
    g.origin(a) = lo(a) - 1.5 * g.h(a);
  }
  g.nx = n[0];
  g.ny = n[1];
  g.nz = n[2];
  return g;
}

Grid cell_centres(const Grid& g) {
  Grid c = g;
  c.origin = g.origin + 0.5 * g.h;
  c.nx = g.nx - 1;
  c.ny = g.ny - 1;
  c.nz = g.nz - 1;
  return c;
}

Eigen::Vector3d grid_spacing(const Eigen::Vector3d& extent, double size, double across, double ratio,
                             double min_size) {
  Eigen::Vector3d h;
  for (int a = 0; a < 3; ++a) h(a) = std::max(std::min(size, extent(a) / across), std::min(min_size, size));
  const double shortest = h.minCoeff();
  for (int a = 0; a < 3; ++a) h(a) = std::min(h(a), ratio * shortest);
  return h;
}

double wall_thickness(const mesh::SurfaceMesh& s, double quantile) {
  const mesh::TriangleProjector proj(s.V, s.F);
  const double diagonal = (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm();
  std::vector<std::pair<double, double>> at;  // (thickness, area)
  double total = 0;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d a = s.V.row(s.F(t, 0)), b = s.V.row(s.F(t, 1)), c = s.V.row(s.F(t, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = n.norm() / 2;
    if (!(area > 0)) continue;
    const double d = proj.ray_distance((a + b + c) / 3, -n, 1e-9 * diagonal, std::numeric_limits<double>::infinity(), t);
    at.emplace_back(d, area);
    total += area;
  }
  if (at.empty()) return std::numeric_limits<double>::infinity();
  std::sort(at.begin(), at.end());
  double sum = 0;
  for (const auto& [d, area] : at) {
    sum += area;
    if (sum >= quantile * total) return d;
  }
  return at.back().first;
}

namespace {

// The crossing of the x-line through (py, pz) with triangle (A, B, C): 0 when the line misses it
// (or the triangle is parallel to it), else +1 where the line enters the solid (the normal points
// to -x), -1 where it leaves; `x` receives where.
int x_line_crossing(const Eigen::Vector3d& A, const Eigen::Vector3d& B, const Eigen::Vector3d& C, double py, double pz,
                    double* x) {
  const double d = (B.y() - A.y()) * (C.z() - A.z()) - (B.z() - A.z()) * (C.y() - A.y());
  if (d == 0) return 0;
  auto orient = [py, pz](double y0, double z0, double y1, double z1) { return (y1 - y0) * (pz - z0) - (z1 - z0) * (py - y0); };
  const double wa = orient(B.y(), B.z(), C.y(), C.z()), wb = orient(C.y(), C.z(), A.y(), A.z()),
               wc = orient(A.y(), A.z(), B.y(), B.z());
  if (!(d > 0 ? (wa > 0 && wb > 0 && wc > 0) : (wa < 0 && wb < 0 && wc < 0))) return 0;
  *x = (wa * A.x() + wb * B.x() + wc * C.x()) / d;
  return d < 0 ? 1 : -1;
}

// Signed crossings of the x-lines of the grid: per line (j, k), the x of each triangle it crosses
// and +1 where it enters the solid (normal pointing to -x), -1 where it leaves.
std::vector<std::vector<std::pair<double, int>>> line_crossings(const Grid& g, const mesh::SurfaceMesh& s, double ey,
                                                                 double ez) {
  std::vector<std::vector<std::pair<double, int>>> lines(size_t(g.ny + 1) * (g.nz + 1));
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d A = s.V.row(s.F(f, 0)), B = s.V.row(s.F(f, 1)), C = s.V.row(s.F(f, 2));
    const double d = (B.y() - A.y()) * (C.z() - A.z()) - (B.z() - A.z()) * (C.y() - A.y());
    if (d == 0) continue;  // parallel to the lines
    const double ylo = std::min({A.y(), B.y(), C.y()}), yhi = std::max({A.y(), B.y(), C.y()});
    const double zlo = std::min({A.z(), B.z(), C.z()}), zhi = std::max({A.z(), B.z(), C.z()});
    const int j0 = std::max(0, static_cast<int>(std::ceil((ylo - g.origin.y() - ey) / g.h.y())));
    const int j1 = std::min(g.ny, static_cast<int>(std::floor((yhi - g.origin.y() - ey) / g.h.y())));
    const int k0 = std::max(0, static_cast<int>(std::ceil((zlo - g.origin.z() - ez) / g.h.z())));
    const int k1 = std::min(g.nz, static_cast<int>(std::floor((zhi - g.origin.z() - ez) / g.h.z())));
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j) {
        double x = 0;
        const int sign = x_line_crossing(A, B, C, g.origin.y() + j * g.h.y() + ey, g.origin.z() + k * g.h.z() + ez, &x);
        if (sign != 0) lines[size_t(j) + size_t(g.ny + 1) * k].emplace_back(x, sign);
      }
  }
  return lines;
}

}  // namespace

NodeField classify_nodes(const Grid& g, const mesh::SurfaceMesh& s, double band) {
  NodeField out;
  const int64_t nn = g.num_nodes();
  out.inside.assign(nn, 0);
  out.distance.assign(nn, std::numeric_limits<double>::infinity());
  // Shifts no CAD coordinate is likely to hit: irrational multiples of 1e-7 h.
  const double ey = g.h.y() * 1e-7 * std::sqrt(2.0), ez = g.h.z() * 1e-7 * std::sqrt(3.0);
  auto lines = line_crossings(g, s, ey, ez);
  std::vector<std::pair<int, int>> bad;
  for (int k = 0; k <= g.nz; ++k)
    for (int j = 0; j <= g.ny; ++j) {
      auto& L = lines[size_t(j) + size_t(g.ny + 1) * k];
      int total = 0;
      for (const auto& c : L) total += c.second;
      if (total != 0) {
        bad.emplace_back(j, k);
        continue;
      }
      std::sort(L.begin(), L.end());
      size_t next = 0;
      int winding = 0;
      for (int i = 0; i <= g.nx; ++i) {
        const double x = g.origin.x() + i * g.h.x();
        while (next < L.size() && L[next].first < x) winding += L[next++].second;
        out.inside[g.node(i, j, k)] = winding > 0;
      }
    }
  if (!bad.empty()) {
    const mesh::TriangleProjector proj(s.V, s.F);
    for (const auto& [j, k] : bad)
      for (int i = 0; i <= g.nx; ++i) {
        const Eigen::Vector3d p = g.position(i, j, k);
        int t = -1;
        const Eigen::Vector3d q = proj.project(p, &t);
        const Eigen::Vector3d A = s.V.row(s.F(t, 0)), B = s.V.row(s.F(t, 1)), C = s.V.row(s.F(t, 2));
        out.inside[g.node(i, j, k)] = (B - A).cross(C - A).dot(p - q) < 0;
      }
  }
  // Distances within the band: each triangle's box, widened by the band, over the nodes it covers.
  for (int f = 0; f < s.F.rows(); ++f) {
    if ((f & 255) == 0) check_interrupt("overlay");
    const Eigen::Vector3d A = s.V.row(s.F(f, 0)), B = s.V.row(s.F(f, 1)), C = s.V.row(s.F(f, 2));
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({A(a), B(a), C(a)}) - band, mx = std::max({A(a), B(a), C(a)}) + band;
      const int n = a == 0 ? g.nx : a == 1 ? g.ny : g.nz;
      lo[a] = std::max(0, static_cast<int>(std::ceil((mn - g.origin(a)) / g.h(a))));
      hi[a] = std::min(n, static_cast<int>(std::floor((mx - g.origin(a)) / g.h(a))));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int64_t n = g.node(i, j, k);
          const Eigen::Vector3d p = g.position(i, j, k);
          const double dist = (mesh::closest_point_on_triangle(p, A, B, C) - p).norm();
          if (dist < out.distance[n]) out.distance[n] = dist;
        }
  }
  return out;
}

NodeField classify_points(const std::vector<Eigen::Vector3d>& points, const mesh::SurfaceMesh& s) {
  NodeField out;
  const size_t n = points.size();
  out.inside.assign(n, 0);
  out.distance.assign(n, std::numeric_limits<double>::infinity());
  if (n == 0 || s.F.rows() == 0) return out;
  // Triangles bucketed by their (y, z) boxes on a square grid of about 4 triangles per bucket row.
  const double ylo = s.V.col(1).minCoeff(), yhi = s.V.col(1).maxCoeff(), zlo = s.V.col(2).minCoeff(), zhi = s.V.col(2).maxCoeff();
  const int nb = std::max(1, std::min(1024, static_cast<int>(std::sqrt(double(s.F.rows())) / 2)));
  const double by = std::max(yhi - ylo, 1e-300) / nb, bz = std::max(zhi - zlo, 1e-300) / nb;
  auto bucket_y = [&](double y) { return std::clamp(static_cast<int>((y - ylo) / by), 0, nb - 1); };
  auto bucket_z = [&](double z) { return std::clamp(static_cast<int>((z - zlo) / bz), 0, nb - 1); };
  std::vector<std::vector<int>> bucket(size_t(nb) * nb);
  for (int f = 0; f < s.F.rows(); ++f) {
    double y0 = 1e300, y1 = -1e300, z0 = 1e300, z1 = -1e300;
    for (int c = 0; c < 3; ++c) {
      y0 = std::min(y0, s.V(s.F(f, c), 1));
      y1 = std::max(y1, s.V(s.F(f, c), 1));
      z0 = std::min(z0, s.V(s.F(f, c), 2));
      z1 = std::max(z1, s.V(s.F(f, c), 2));
    }
    for (int k = bucket_z(z0); k <= bucket_z(z1); ++k)
      for (int j = bucket_y(y0); j <= bucket_y(y1); ++j) bucket[size_t(j) + size_t(nb) * k].push_back(f);
  }
  const double e = 1e-7 * std::max({yhi - ylo, zhi - zlo, 1e-300}) / nb;
  const mesh::TriangleProjector proj(s.V, s.F);
  for (size_t i = 0; i < n; ++i) {
    if ((i & 1023) == 0) check_interrupt("overlay");
    const Eigen::Vector3d& p = points[i];
    int t = -1;
    const Eigen::Vector3d q = proj.project(p, &t);
    out.distance[i] = (q - p).norm();
    const double py = p.y() + e * std::sqrt(2.0), pz = p.z() + e * std::sqrt(3.0);
    int winding = 0, total = 0;
    if (py >= ylo && py <= yhi && pz >= zlo && pz <= zhi)
      for (int f : bucket[size_t(bucket_y(py)) + size_t(nb) * bucket_z(pz)]) {
        double x = 0;
        const int sign = x_line_crossing(s.V.row(s.F(f, 0)), s.V.row(s.F(f, 1)), s.V.row(s.F(f, 2)), py, pz, &x);
        total += sign;
        if (sign != 0 && x < p.x()) winding += sign;
      }
    if (total == 0) {
      out.inside[i] = winding > 0;
    } else {
      const Eigen::Vector3d A = s.V.row(s.F(t, 0)), B = s.V.row(s.F(t, 1)), C = s.V.row(s.F(t, 2));
      out.inside[i] = (B - A).cross(C - A).dot(p - q) < 0;
    }
  }
  return out;
}

}  // namespace hexdom::overlay
