#include "hexdom/quality/second_order.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "hexdom/mesh/cell_faces.h"

namespace hexdom::quality {

using mesh::CellType;
using Eigen::Vector3d;

namespace {

// Reference coordinates of the corners, VTK order.
const double kHexCorner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const double kWedgeCorner[6][3] = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
const double kTetCorner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

const double (*corners(CellType t))[3] {
  switch (t) {
    case CellType::Hex: return kHexCorner;
    case CellType::Wedge: return kWedgeCorner;
    default: return kTetCorner;
  }
}

/// Derivatives dN_i/d(x, y, z) of the 20 shape functions of the serendipity hex at x.
void hex_derivatives(const double* x, double (*d)[3]) {
  const auto [edges, ne] = mesh::cell_edges(CellType::Hex);
  for (int i = 0; i < 20; ++i) {
    double n[3];
    if (i < 8) {
      for (int k = 0; k < 3; ++k) n[k] = kHexCorner[i][k];
      const double f[3] = {1 + n[0] * x[0], 1 + n[1] * x[1], 1 + n[2] * x[2]};
      const double s = n[0] * x[0] + n[1] * x[1] + n[2] * x[2];
      for (int k = 0; k < 3; ++k) d[i][k] = n[k] * f[(k + 1) % 3] * f[(k + 2) % 3] * (s + n[k] * x[k] - 1) / 8;
      continue;
    }
    const auto& e = edges[i - 8];
    for (int k = 0; k < 3; ++k) n[k] = 0.5 * (kHexCorner[e[0]][k] + kHexCorner[e[1]][k]);
    const int z = n[0] == 0 ? 0 : n[1] == 0 ? 1 : 2;  // the axis the edge runs along
    const int u = (z + 1) % 3, v = (z + 2) % 3;
    const double fu = 1 + n[u] * x[u], fv = 1 + n[v] * x[v], q = 1 - x[z] * x[z];
    d[i][z] = -x[z] * fu * fv / 2;
    d[i][u] = q * n[u] * fv / 4;
    d[i][v] = q * fu * n[v] / 4;
  }
}

/// Derivatives of the 15 shape functions of the quadratic wedge at (r, s, z).
void wedge_derivatives(const double* x, double (*d)[3]) {
  const double L[3] = {1 - x[0] - x[1], x[0], x[1]};
  const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
  const double z = x[2];
  for (int i = 0; i < 6; ++i) {  // corners
    const int j = i % 3;
    const double zi = i < 3 ? -1 : 1;
    const double dn = 0.5 * (4 * L[j] - 1) * (1 + zi * z) - 0.5 * (1 - z * z);
    d[i][0] = dn * dL[j][0];
    d[i][1] = dn * dL[j][1];
    d[i][2] = 0.5 * L[j] * (2 * L[j] - 1) * zi + L[j] * z;
  }
  const int tri[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (int h = 0; h < 2; ++h)
    for (int e = 0; e < 3; ++e) {  // mid nodes of the triangles' edges
      const int i = 6 + 3 * h + e, a = tri[e][0], b = tri[e][1];
      const double zi = h == 0 ? -1 : 1, f = 1 + zi * z;
      d[i][0] = 2 * (dL[a][0] * L[b] + L[a] * dL[b][0]) * f;
      d[i][1] = 2 * (dL[a][1] * L[b] + L[a] * dL[b][1]) * f;
      d[i][2] = 2 * L[a] * L[b] * zi;
    }
  for (int j = 0; j < 3; ++j) {  // mid nodes of the vertical edges
    d[12 + j][0] = dL[j][0] * (1 - z * z);
    d[12 + j][1] = dL[j][1] * (1 - z * z);
    d[12 + j][2] = -2 * L[j] * z;
  }
}

/// Derivatives of the 10 shape functions of the quadratic tet at (r, s, t).
void tet_derivatives(const double* x, double (*d)[3]) {
  const double L[4] = {1 - x[0] - x[1] - x[2], x[0], x[1], x[2]};
  const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) d[i][k] = (4 * L[i] - 1) * dL[i][k];
  const auto [edges, ne] = mesh::cell_edges(CellType::Tet);
  for (int e = 0; e < ne; ++e) {
    const int a = edges[e][0], b = edges[e][1];
    for (int k = 0; k < 3; ++k) d[4 + e][k] = 4 * (dL[a][k] * L[b] + L[a] * dL[b][k]);
  }
}

/// The map's derivatives (columns a, b, c) at reference point x.
Eigen::Matrix3d jacobian(CellType t, const double (*p)[3], const double* x) {
  double d[20][3];
  int n = 0;
  switch (t) {
    case CellType::Hex: hex_derivatives(x, d), n = 20; break;
    case CellType::Wedge: wedge_derivatives(x, d), n = 15; break;
    default: tet_derivatives(x, d), n = 10; break;
  }
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) J(r, k) += p[i][r] * d[i][k];
  return J;
}

/// The scaled sample of a Jacobian (see the header).
double scaled(CellType t, const Eigen::Matrix3d& J) {
  const Vector3d a = J.col(0), b = J.col(1), c = J.col(2);
  const double det = a.dot(b.cross(c));
  double product = 0, factor = 1, sign = 1;
  switch (t) {
    case CellType::Hex: product = a.norm() * b.norm() * c.norm(); break;
    case CellType::Wedge:
      // VTK's wedge turns its first triangle's normal away from the second: det < 0 when valid.
      sign = -1, factor = 2 / std::sqrt(3.0);
      product = c.norm() * std::max({a.norm() * b.norm(), a.norm() * (b - a).norm(), (a - b).norm() * b.norm()});
      break;
    default:
      factor = std::sqrt(2.0);
      product = std::max({a.norm() * b.norm() * c.norm(), a.norm() * (b - a).norm() * (c - a).norm(),
                          b.norm() * (a - b).norm() * (c - b).norm(), c.norm() * (a - c).norm() * (b - c).norm()});
  }
  if (!(product > 0)) return -1;
  return sign * factor * det / product;
}

struct Rule {
  std::vector<std::array<double, 3>> points;
  std::vector<double> weights;
};

Rule make_rule(CellType t) {
  Rule r;
  const double g = std::sqrt(0.6), gx[3] = {-g, 0, g}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  if (t == CellType::Hex) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) r.points.push_back({gx[i], gx[j], gx[k]}), r.weights.push_back(gw[i] * gw[j] * gw[k]);
  } else if (t == CellType::Wedge) {
    const double tri[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) r.points.push_back({tri[i][0], tri[i][1], gx[k]}), r.weights.push_back(gw[k] / 6);
  } else {
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    for (const auto& x : {std::array<double, 3>{b, b, b}, {a, b, b}, {b, a, b}, {b, b, a}})
      r.points.push_back(x), r.weights.push_back(1.0 / 24);
  }
  return r;
}

const Rule& rule(CellType t) {
  static const Rule hex = make_rule(CellType::Hex), wedge = make_rule(CellType::Wedge), tet = make_rule(CellType::Tet);
  return t == CellType::Hex ? hex : t == CellType::Wedge ? wedge : tet;
}

}  // namespace

int second_order_jacobian_samples(CellType t, const double (*p)[3], double* s) {
  if (!mesh::is_volume(t)) return 0;
  const int nc = mesh::node_count(t);
  const auto [edges, ne] = mesh::cell_edges(t);
  const double (*ref)[3] = corners(t);
  int n = 0;
  for (int i = 0; i < nc + ne; ++i) {
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = i < nc ? ref[i][k] : 0.5 * (ref[edges[i - nc][0]][k] + ref[edges[i - nc][1]][k]);
    s[n++] = scaled(t, jacobian(t, p, x));
  }
  for (const auto& x : rule(t).points) s[n++] = scaled(t, jacobian(t, p, x.data()));
  return n;
}

double second_order_scaled_jacobian(CellType t, const double (*p)[3]) {
  double s[kMaxSecondOrderSamples];
  const int n = second_order_jacobian_samples(t, p, s);
  return n ? *std::min_element(s, s + n) : std::nan("");
}

double second_order_volume(CellType t, const double (*p)[3]) {
  if (!mesh::is_volume(t)) return 0;
  const Rule& r = rule(t);
  const double sign = t == CellType::Wedge ? -1 : 1;
  double v = 0;
  for (size_t i = 0; i < r.points.size(); ++i) v += r.weights[i] * sign * jacobian(t, p, r.points[i].data()).determinant();
  return v;
}

}  // namespace hexdom::quality
