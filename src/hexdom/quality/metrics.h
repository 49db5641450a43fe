// Element quality metrics, defined as VTK's Verdict library defines them so that our figures and
// Verdict's agree to rounding.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hexdom/mesh/mesh.h"

namespace hexdom::quality {

/// Corner coordinates of one cell (rows 0..node_count-1 used), VTK order.
using CellPoints = Eigen::Matrix<double, 8, 3>;

/// Scaled Jacobian in [-1, 1] (1: ideal shape).
/// Hex: minimum over the 8 corners and the centre of det[a b c] / (|a||b||c|), the centre using the
///   three principal axes; a zero-length edge gives DBL_MAX, as in Verdict (an invalid cell).
/// Tet: sqrt(2) det / (largest product of the three edge lengths meeting at a corner).
/// Wedge: 2/sqrt(3) x minimum over the 6 corners of the corner determinant over its edge-length
///   product; evaluated in Verdict's node order (VTK's reordered 1 0 2 4 3 5). A zero-length edge
///   gives DBL_MAX (invalid), where Verdict's answer depends on which corner the edge touches.
/// 2D cells: NaN.
double scaled_jacobian(mesh::CellType type, const CellPoints& P);

/// The scaled Jacobians of hex P with its node `node` (0-7) moved by h along x, y and z in turn
/// (out[k]: P(node, k) + h): bit for bit scaled_jacobian(Hex, ...) of each moved cell, the corners
/// away from the node computed once (a numerical gradient's three evaluations).
void hex_sj_axis_steps(const CellPoints& P, int node, double h, double out[3]);

/// Longest over shortest edge (the paper's "aspect ratio"); DBL_MAX for a zero-length edge.
/// Hexes use all 12 edges. Verdict's hex_edge_ratio (VTK 9.1 and later) takes the longest of
/// its first six edges only (its code overwrites the 12-edge maximum), so it can be lower.
double edge_ratio(mesh::CellType type, const CellPoints& P);

/// Volume of the trilinear (hex), bilinear-by-linear (wedge) or linear (tet) cell, by exact
/// quadrature of its Jacobian determinant; negative when inverted.
double volume(mesh::CellType type, const CellPoints& P);

/// True when the cell is inverted or degenerate: scaled Jacobian <= 0, DBL_MAX or NaN.
bool is_inverted(double scaled_jacobian);

/// The scaled Jacobian where it is defined (a finite value below 2), else -1: a value to order and
/// compare cells by, in which a degenerate cell (zero-length edge, NaN) ranks with inverted ones.
double signed_sj(double scaled_jacobian);
/// signed_sj of the cell's scaled Jacobian.
double signed_sj(mesh::CellType type, const CellPoints& P);

/// Points of cell `c` of `mesh` (rows past its node count zero). Inline: the optimisers call it for
/// every trial position.
inline CellPoints cell_points(const mesh::Mesh& mesh, int c) {
  CellPoints P;
  const int n = mesh::node_count(mesh.type(c));
  const double* x = mesh.V.data();  // column-major: x, then y, then z of every node
  const Eigen::Index rows = mesh.V.rows();
  for (int i = 0; i < n; ++i) {
    const Eigen::Index v = mesh.cells(c, i);
    P(i, 0) = x[v];
    P(i, 1) = x[v + rows];
    P(i, 2) = x[v + 2 * rows];
  }
  for (int i = n; i < 8; ++i) P.row(i).setZero();
  return P;
}

/// Per-cell metrics of a whole mesh (#C each; NaN for 2D cells).
struct CellMetrics {
  Eigen::VectorXd scaled_jacobian;
  Eigen::VectorXd edge_ratio;
  Eigen::VectorXd volume;
};
/// The cells are measured on `threads` threads (parallel_for): the same figures on any number.
CellMetrics compute_metrics(const mesh::Mesh& mesh, int threads = 1);

}  // namespace hexdom::quality
