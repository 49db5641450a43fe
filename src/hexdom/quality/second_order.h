// Quality of second-order cells (20-node hex, 15-node wedge, 10-node tet, VTK's quadratic node
// order): the Jacobian of the map from the reference cell, sampled where a FEM solver uses it.
//
// Samples: every node of the cell (its corners and mid-edge nodes) and the points of the usual
// Gauss rules (hex 3 x 3 x 3, as CalculiX's C3D20; wedge 3 triangle points x 3 along its height, as
// C3D15; tet 4, as C3D10): hex 47, wedge 24, tet 14. With the map's derivatives a, b, c along the
// reference axes at a sample (hex: x, y, z in [-1, 1]; wedge: the triangle's r, s and the height
// z in [-1, 1]; tet: r, s, t), the sample is
//   hex:   det[a b c] / (|a| |b| |c|);
//   wedge: 2/sqrt(3) det[a b c] / (|c| x the largest of the triangle's corner products |a||b|,
//          |a||b - a|, |a - b||b|);
//   tet:   sqrt(2) det[a b c] / (the largest of the four corners' products |a||b||c|,
//          |a||b - a||c - a|, |b||a - b||c - b|, |c||a - c||b - c|),
// signed so that a valid cell's are positive; -1 where a product is 0. For a cell whose mid-edge
// nodes are the midpoints of its edges the map is the first-order cell's, and the samples at the
// corners are quality::jacobian_samples' corner samples (hex and tet exactly; wedge at most them).
// The cell's second-order scaled Jacobian is the minimum; the cell is inverted when it is <= 0.
#pragma once

#include "hexdom/mesh/mesh.h"

namespace hexdom::quality {

/// Most samples a second-order cell has (the hex's 47).
constexpr int kMaxSecondOrderSamples = 47;

/// Writes the samples of a second-order hex, wedge or tet (`type` its first-order type) with node
/// points p (VTK's quadratic order: 20, 15 or 10 rows) into s and returns their number.
int second_order_jacobian_samples(mesh::CellType type, const double (*p)[3], double* s);

/// The minimum of the samples.
double second_order_scaled_jacobian(mesh::CellType type, const double (*p)[3]);

/// Volume of the curved cell, by its Gauss rule (exact for cells whose map is first order, i.e.
/// mid-edge nodes at the midpoints); negative when inverted.
double second_order_volume(mesh::CellType type, const double (*p)[3]);

}  // namespace hexdom::quality
