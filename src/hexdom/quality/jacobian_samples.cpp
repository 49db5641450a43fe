#include "hexdom/quality/jacobian_samples.h"

#include <cmath>

namespace hexdom::quality {

using mesh::CellType;

namespace {

// At each corner the three edges in the order that gives a positive determinant for a valid cell
// (VTK node order), as Verdict takes them.
const int kHexEdgesAt[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
const int kWedgeEdgesAt[6][3] = {{2, 1, 3}, {0, 2, 4}, {1, 0, 5}, {4, 5, 0}, {5, 3, 1}, {3, 4, 2}};
const int kTetEdgesAt[4][3] = {{1, 2, 3}, {2, 0, 3}, {0, 1, 3}, {0, 2, 1}};

inline double det3(const double* a, const double* b, const double* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}
inline double norm2(const double* a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; }

// Per sample of a cell with corner points p: the determinant and the product of the squared
// lengths of its three edges; the sample is factor x det / sqrt(l2). Returns their number (hex 9,
// wedge 6, tet 4).
int sample_terms(CellType t, const double (*p)[3], double* det, double* l2, double& factor) {
  double e[3][3];
  if (t == CellType::Tet) {
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) e[q][d] = p[q + 1][d] - p[0][d];
    const double D = det3(e[0], e[1], e[2]);
    for (int k = 0; k < 4; ++k) {
      double l = 1;
      for (int q = 0; q < 3; ++q) {
        const int o = kTetEdgesAt[k][q];
        const double f[3] = {p[o][0] - p[k][0], p[o][1] - p[k][1], p[o][2] - p[k][2]};
        l *= norm2(f);
      }
      det[k] = D;
      l2[k] = l;
    }
    factor = std::sqrt(2.0);
    return 4;
  }
  const bool hex = t == CellType::Hex;
  const int (*E)[3] = hex ? kHexEdgesAt : kWedgeEdgesAt;
  const int nk = hex ? 8 : 6;
  factor = hex ? 1.0 : 2.0 / std::sqrt(3.0);
  for (int k = 0; k < nk; ++k) {
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) e[q][d] = p[E[k][q]][d] - p[k][d];
    det[k] = det3(e[0], e[1], e[2]);
    l2[k] = norm2(e[0]) * norm2(e[1]) * norm2(e[2]);
  }
  if (!hex) return 6;
  for (int d = 0; d < 3; ++d) {
    e[0][d] = p[1][d] - p[0][d] + p[2][d] - p[3][d] + p[5][d] - p[4][d] + p[6][d] - p[7][d];
    e[1][d] = p[3][d] - p[0][d] + p[2][d] - p[1][d] + p[7][d] - p[4][d] + p[6][d] - p[5][d];
    e[2][d] = p[4][d] - p[0][d] + p[5][d] - p[1][d] + p[6][d] - p[2][d] + p[7][d] - p[3][d];
  }
  det[8] = det3(e[0], e[1], e[2]);
  l2[8] = norm2(e[0]) * norm2(e[1]) * norm2(e[2]);
  return 9;
}

}  // namespace

const int (*corner_neighbours(CellType t))[3] {
  return t == CellType::Hex ? kHexEdgesAt : t == CellType::Wedge ? kWedgeEdgesAt : kTetEdgesAt;
}

int jacobian_samples(CellType t, const double (*p)[3], double* s) {
  double det[9], l2[9], factor;
  const int ns = sample_terms(t, p, det, l2, factor);
  for (int k = 0; k < ns; ++k) s[k] = l2[k] > 1e-300 ? factor * det[k] / std::sqrt(l2[k]) : -1.0;
  return ns;
}

bool some_jacobian_sample_at_most(CellType t, const double (*p)[3], double threshold) {
  double det[9], l2[9], factor;
  const int ns = sample_terms(t, p, det, l2, factor);
  const double r = threshold * threshold / (factor * factor);
  for (int k = 0; k < ns; ++k)
    if (!(l2[k] > 1e-300) || det[k] <= 0 || det[k] * det[k] <= r * l2[k]) return true;
  return false;
}

unsigned jacobian_samples_of_node(CellType t, int lv) {
  if (t == CellType::Tet) return 0xf;
  const bool hex = t == CellType::Hex;
  const int (*E)[3] = hex ? kHexEdgesAt : kWedgeEdgesAt;
  unsigned m = hex ? 1u << 8 : 0u;
  for (int k = 0; k < (hex ? 8 : 6); ++k)
    if (k == lv || E[k][0] == lv || E[k][1] == lv || E[k][2] == lv) m |= 1u << k;
  return m;
}

}  // namespace hexdom::quality
