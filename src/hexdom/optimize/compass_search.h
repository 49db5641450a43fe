// Untangling a small mesh by compass search: each free node tries steps along +-x, +-y, +-z and
// keeps those that raise the worst cell around it. Made for block structures (a few hundred nodes,
// cells far from ideal), where a gradient of the worst cell is of little use.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::optimize {

struct CompassOptions {
  int rounds = 50;       ///< sweeps over the nodes, at most; a sweep that moves none ends the search
  double target = 0.3;   ///< nodes whose worst cell (quality::signed_sj) is at or above this stay
  /// A step may not make an edge of the node shorter than this share of the node's mean edge length
  /// at the start (nor shorten one that is already shorter): the scaled Jacobian alone lets a cell
  /// flatten to a slab. 0: no limit.
  double min_edge_share = 0.25;
};

/// Moves the nodes v of `mesh` with !fixed[v] whose worst cell is below options.target, one at a
/// time in node order: steps of a quarter of the node's mean edge length to its neighbours
/// `neighbours[v]` (the edge graph), halved down to a thousandth of it, along +-x, +-y, +-z; a step
/// is kept when it raises the worst signed scaled Jacobian of the node's cells by more than 1e-9
/// and respects min_edge_share. No cell's value drops below the worst of its nodes' cells before
/// the move. Returns the cells' signed scaled Jacobians afterwards (#cells).
Eigen::VectorXd compass_untangle(mesh::Mesh& mesh, const std::vector<char>& fixed,
                                 const std::vector<std::vector<int>>& neighbours, const CompassOptions& options);

}  // namespace hexdom::optimize
