// The scaled Jacobian of a cell as its samples: one value per corner (and the hex's centre), whose
// minimum is the cell's scaled Jacobian. For the node moves of the optimisation, which need to know
// which part of a cell's quality a node affects and to test "at most t" often and cheaply.
//
// Samples, with the cell's corner points in VTK node order (p[0..node_count-1]):
//   corner k: factor x det[e1 e2 e3] / (|e1| |e2| |e3|), e_q = p[corner_neighbours(t)[k][q]] - p[k],
//     the neighbours ordered so that the determinant is positive for a valid cell;
//   hex sample 8 (the centre): det / lengths of the three principal axes (Verdict's).
//   factor: hex 1, wedge 2/sqrt(3), tet sqrt(2). Hex 9 samples, wedge 6, tet 4.
//   A sample with a zero-length edge is -1 (the cell is invalid).
// Agreement with quality::scaled_jacobian (Verdict's definition), up to rounding:
//   hex and wedge: the minimum of the samples is the scaled Jacobian of every cell without a
//     zero-length edge (valid or inverted); with one, the samples say -1 where scaled_jacobian says
//     DBL_MAX, both "inverted" for quality::is_inverted.
//   tet: the four samples share the determinant and divide by each corner's edge-length product, so
//     their minimum is the scaled Jacobian when it is positive (Verdict divides by the largest
//     product) and at most it when it is negative or zero.
#pragma once

#include "hexdom/mesh/mesh.h"

namespace hexdom::quality {

/// Most samples a cell has (the hex's 9).
constexpr int kMaxJacobianSamples = 9;

/// For each corner k of a hex (8), wedge (6) or tet (4): its three edge neighbours in the order of
/// corner k's sample. Rows beyond node_count(type) do not exist.
const int (*corner_neighbours(mesh::CellType type))[3];

/// Writes the samples of a hex, wedge or tet with corner points p into s (kMaxJacobianSamples
/// values at most) and returns their number (9, 6, 4).
int jacobian_samples(mesh::CellType type, const double (*p)[3], double* s);

/// True when some sample is at most `threshold` (>= 0), a sample with a zero-length edge included;
/// without roots or divisions, so it can be asked of every cell of a mesh. Exactly
/// "min of jacobian_samples <= threshold" up to rounding.
bool some_jacobian_sample_at_most(mesh::CellType type, const double (*p)[3], double threshold);

/// Bit mask (bit k: sample k) of the samples that depend on local node `local_node`: its own
/// corner, the corners it is an edge neighbour of, and the hex's centre; every sample of a tet.
/// Moving that node changes no other sample.
unsigned jacobian_samples_of_node(mesh::CellType type, int local_node);

}  // namespace hexdom::quality
