#include "hexdom/quality/metrics.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "hexdom/common/parallel_for.h"
#include "hexdom/mesh/cell_faces.h"

namespace hexdom::quality {

using mesh::CellType;
using Vec = Eigen::Vector3d;

namespace {

constexpr double kDblMax = 1.0e+30;  // Verdict's VERDICT_DBL_MAX
constexpr double kDblMin = 1.0e-30;  // Verdict's VERDICT_DBL_MIN

Vec row(const CellPoints& P, int i) { return P.row(i).transpose(); }

// Plain arithmetic (no temporaries): this runs for every cell of every mesh, often many times.
inline double triple(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// A hex's corners in Verdict's order: corner c, its neighbours a, b, d, and the edges (kHexEdges)
// from c to them.
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {4, 5}, {5, 6}, {6, 7}, {4, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kHexCorners[8][7] = {{0, 1, 3, 4, 0, 3, 8}, {1, 2, 0, 5, 1, 0, 9}, {2, 3, 1, 6, 2, 1, 10},
                                   {3, 0, 2, 7, 3, 2, 11}, {4, 7, 5, 0, 7, 4, 8}, {5, 4, 6, 1, 4, 5, 9},
                                   {6, 5, 7, 2, 5, 6, 10}, {7, 6, 4, 3, 6, 7, 11}};

// The centre's value (principal axes); false for a zero-length axis (an invalid cell).
inline bool hex_centre(const double p[8][3], double* sj) {
  double x[3][3];
  for (int k = 0; k < 3; ++k) {
    x[0][k] = (p[1][k] - p[0][k]) + (p[2][k] - p[3][k]) + (p[5][k] - p[4][k]) + (p[6][k] - p[7][k]);
    x[1][k] = (p[3][k] - p[0][k]) + (p[2][k] - p[1][k]) + (p[7][k] - p[4][k]) + (p[6][k] - p[5][k]);
    x[2][k] = (p[4][k] - p[0][k]) + (p[5][k] - p[1][k]) + (p[6][k] - p[2][k]) + (p[7][k] - p[3][k]);
  }
  auto len2 = [](const double a[3]) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; };
  const double la = len2(x[0]), lb = len2(x[1]), lc = len2(x[2]);
  if (la <= kDblMin || lb <= kDblMin || lc <= kDblMin) return false;
  *sj = triple(x[0], x[1], x[2]) / std::sqrt(la * lb * lc);
  return true;
}

// Squared length of edge j; false when it is zero (an invalid cell).
inline bool hex_edge(const double p[8][3], int j, double* l) {
  const double d0 = p[kHexEdges[j][1]][0] - p[kHexEdges[j][0]][0], d1 = p[kHexEdges[j][1]][1] - p[kHexEdges[j][0]][1],
               d2 = p[kHexEdges[j][1]][2] - p[kHexEdges[j][0]][2];
  *l = d0 * d0 + d1 * d1 + d2 * d2;
  return !(*l <= kDblMin);
}

// Corner t of kHexCorners, given the squared edge lengths.
inline double hex_corner(const double p[8][3], const double l[12], const int* t) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = p[t[1]][k] - p[t[0]][k];
    v[k] = p[t[2]][k] - p[t[0]][k];
    w[k] = p[t[3]][k] - p[t[0]][k];
  }
  return triple(u, v, w) / std::sqrt(l[t[4]] * l[t[5]] * l[t[6]]);
}

inline double hex_clamped(double min_sj) { return min_sj > 0 ? std::min(min_sj, kDblMax) : std::max(min_sj, -kDblMax); }

double hex_sj(const CellPoints& P) {
  double p[8][3];
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = P(i, k);
  double min_sj = kDblMax, c;
  if (!hex_centre(p, &c)) return kDblMax;
  min_sj = std::min(min_sj, c);
  double l[12];  // the 12 squared edge lengths, computed once: each corner uses three of them
  for (int j = 0; j < 12; ++j)
    if (!hex_edge(p, j, &l[j])) return kDblMax;
  for (const auto& t : kHexCorners) min_sj = std::min(min_sj, hex_corner(p, l, t));
  return hex_clamped(min_sj);
}

double tet_sj(const CellPoints& P) {
  Vec s0 = row(P, 1) - row(P, 0), s1 = row(P, 2) - row(P, 1), s2 = row(P, 0) - row(P, 2);
  Vec s3 = row(P, 3) - row(P, 0), s4 = row(P, 3) - row(P, 1), s5 = row(P, 3) - row(P, 2);
  double jac = s3.dot(s2.cross(s0));
  double l0 = s0.squaredNorm(), l1 = s1.squaredNorm(), l2 = s2.squaredNorm();
  double l3 = s3.squaredNorm(), l4 = s4.squaredNorm(), l5 = s5.squaredNorm();
  double m = std::max({l0 * l2 * l3, l0 * l1 * l4, l1 * l2 * l5, l3 * l4 * l5});
  double len = std::sqrt(m);
  if (len < std::fabs(jac)) len = std::fabs(jac);
  if (len < kDblMin) return 0.0;
  return std::sqrt(2.0) * jac / len;
}

double wedge_sj(const CellPoints& Q) {
  // Verdict's node order is VTK's reordered (1 0 2 4 3 5).
  static const int perm[6] = {1, 0, 2, 4, 3, 5};
  Vec c[6];
  for (int i = 0; i < 6; ++i) c[i] = row(Q, perm[i]);
  // For each corner: (vec1, vec2, vec3) with jacobian vec2 . (vec1 x vec3), as Verdict takes them.
  static const int k[6][4] = {{0, 1, 3, 2}, {1, 2, 4, 0}, {2, 0, 5, 1},
                              {3, 0, 4, 5}, {4, 1, 5, 3}, {5, 3, 4, 2}};
  double min_sj = 0;
  for (int i = 0; i < 6; ++i) {
    Vec v1 = c[k[i][1]] - c[k[i][0]], v2 = c[k[i][2]] - c[k[i][0]], v3 = c[k[i][3]] - c[k[i][0]];
    double len = std::sqrt(v1.squaredNorm() * v2.squaredNorm() * v3.squaredNorm());
    // A zero-length edge makes this corner 0/0. Verdict lets that NaN through its min, so its
    // answer then depends on which corner it was (-DBL_MAX, 0, or the minimum of the other
    // corners, even a positive one); we call the cell invalid, as for hexes.
    if (!(len > 0)) return kDblMax;
    double j = v2.dot(v1.cross(v3)) / len;
    min_sj = i == 0 ? j : std::min(j, min_sj);
  }
  min_sj *= 2.0 / std::sqrt(3.0);
  return min_sj > 0 ? std::min(min_sj, kDblMax) : std::max(min_sj, -kDblMax);
}


}  // namespace

double scaled_jacobian(CellType type, const CellPoints& P) {
  switch (type) {
    case CellType::Hex: return hex_sj(P);
    case CellType::Tet: return tet_sj(P);
    case CellType::Wedge: return wedge_sj(P);
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

void hex_sj_axis_steps(const CellPoints& P, int node, double h, double out[3]) {
  double p[8][3];
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = P(i, k);
  auto touches = [&](const int* t) { return t[0] == node || t[1] == node || t[2] == node || t[3] == node; };
  // The edges and corners away from the node are the same in the three cells.
  double l[12];
  for (int j = 0; j < 12; ++j)
    if (kHexEdges[j][0] != node && kHexEdges[j][1] != node && !hex_edge(p, j, &l[j])) {
      out[0] = out[1] = out[2] = kDblMax;
      return;
    }
  double fixed = kDblMax;
  for (const auto& t : kHexCorners)
    if (!touches(t)) fixed = std::min(fixed, hex_corner(p, l, t));
  const double x0[3] = {p[node][0], p[node][1], p[node][2]};
  for (int k = 0; k < 3; ++k) {
    p[node][0] = x0[0], p[node][1] = x0[1], p[node][2] = x0[2];
    p[node][k] = x0[k] + h;
    double min_sj = kDblMax, c = 0;
    bool valid = hex_centre(p, &c);
    min_sj = std::min(min_sj, c);
    for (int j = 0; j < 12 && valid; ++j)
      if (kHexEdges[j][0] == node || kHexEdges[j][1] == node) valid = hex_edge(p, j, &l[j]);
    if (!valid) {
      out[k] = kDblMax;
      continue;
    }
    for (const auto& t : kHexCorners)
      if (touches(t)) min_sj = std::min(min_sj, hex_corner(p, l, t));
    out[k] = hex_clamped(std::min(min_sj, fixed));
  }
}

double edge_ratio(CellType type, const CellPoints& P) {
  const auto [edges, n] = mesh::cell_edges(type);
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  double lo = DBL_MAX, hi = 0;
  for (int e = 0; e < n; ++e) {
    double l = (P.row(edges[e][0]) - P.row(edges[e][1])).squaredNorm();
    lo = std::min(lo, l);
    hi = std::max(hi, l);
  }
  if (lo < kDblMin) return kDblMax;
  return std::sqrt(hi / lo);
}

double volume(CellType type, const CellPoints& P) {
  const double g = 0.5 - 0.5 / std::sqrt(3.0);  // 2-point Gauss abscissae on [0,1]: g, 1-g
  const double gp[2] = {g, 1 - g};
  double v = 0;
  if (type == CellType::Hex) {
    for (double u : gp)
      for (double w : gp)
        for (double t : gp) {
          // Derivatives of the trilinear map at (u, w, t).
          double su[2] = {1 - u, u}, sw[2] = {1 - w, w}, st[2] = {1 - t, t};
          Vec du = Vec::Zero(), dw = Vec::Zero(), dt = Vec::Zero();
          static const int pos[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
          for (int i = 0; i < 8; ++i) {
            double a = pos[i][0] ? 1 : -1, b = pos[i][1] ? 1 : -1, c = pos[i][2] ? 1 : -1;
            Vec p = row(P, i);
            du += a * sw[pos[i][1]] * st[pos[i][2]] * p;
            dw += b * su[pos[i][0]] * st[pos[i][2]] * p;
            dt += c * su[pos[i][0]] * sw[pos[i][1]] * p;
          }
          v += du.dot(dw.cross(dt)) / 8.0;
        }
    return v;
  }
  if (type == CellType::Wedge) {
    // Triangle (r, s) with the 3-point rule (degree 2) times 2-point Gauss in t.
    const double tr[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
    for (const auto& q : tr)
      for (double t : gp) {
        double r = q[0], s = q[1];
        Vec b[2] = {row(P, 0) * (1 - r - s) + row(P, 1) * r + row(P, 2) * s,
                    row(P, 3) * (1 - r - s) + row(P, 4) * r + row(P, 5) * s};
        Vec dr = (1 - t) * (row(P, 1) - row(P, 0)) + t * (row(P, 4) - row(P, 3));
        Vec ds = (1 - t) * (row(P, 2) - row(P, 0)) + t * (row(P, 5) - row(P, 3));
        Vec dt = b[1] - b[0];
        // VTK wedges have the first triangle's normal pointing away from the second: flip sign.
        v += -dr.cross(ds).dot(dt) * (1.0 / 6.0) * 0.5;
      }
    return v;
  }
  if (type == CellType::Tet)
    return (row(P, 1) - row(P, 0)).cross(row(P, 2) - row(P, 0)).dot(row(P, 3) - row(P, 0)) / 6.0;
  return std::numeric_limits<double>::quiet_NaN();
}

bool is_inverted(double sj) { return !(sj > 0) || sj >= kDblMax; }

double signed_sj(double sj) { return std::isfinite(sj) && sj < 2 ? sj : -1.0; }

double signed_sj(mesh::CellType type, const CellPoints& P) { return signed_sj(scaled_jacobian(type, P)); }

CellMetrics compute_metrics(const mesh::Mesh& m, int threads) {
  CellMetrics r;
  const int n = m.num_cells();
  r.scaled_jacobian.resize(n);
  r.edge_ratio.resize(n);
  r.volume.resize(n);
  parallel_for(n, threads, [&](int c) {
    const CellPoints P = cell_points(m, c);
    r.scaled_jacobian(c) = scaled_jacobian(m.type(c), P);
    r.edge_ratio(c) = edge_ratio(m.type(c), P);
    r.volume(c) = volume(m.type(c), P);
  });
  return r;
}

}  // namespace hexdom::quality
