// Curving a second-order mesh: mid-edge nodes moved onto the geometry (the B-rep, the input
// surface) without letting any cell's Jacobian drop below what its straight shape has.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::optimize {

struct CurveOptions {
  /// A cell is accepted when its second-order scaled Jacobian (quality/second_order.h) is at least
  /// min(min_sj, the one of its straight shape, i.e. with its mid-edge nodes at the midpoints).
  double min_sj = 0.2;
  /// How often a rejected cell's mid-edge nodes have their offset from the midpoint halved before
  /// they are put back on the midpoint.
  int halvings = 3;
};

struct CurveReport {
  int targets = 0;    ///< mid-edge nodes with a target
  int placed = 0;     ///< of them, at their target
  int shortened = 0;  ///< between the midpoint and the target (offset halved)
  int straight = 0;   ///< back on the midpoint
  double max_gap = 0; ///< largest distance of a mid-edge node from its target
  double worst_sj = 0;  ///< least second-order scaled Jacobian over all cells (NaN with none)
  int inverted = 0;     ///< cells whose second-order scaled Jacobian is <= 0
};

/// What making a mesh second order did (second_order_on_surface, cad::second_order_on_brep).
struct SecondOrderReport {
  int boundary_mid_nodes = 0;  ///< mid-edge nodes of boundary edges
  int edge_targets = 0;        ///< of them, with their target on a CAD edge
  int face_targets = 0;        ///< on a CAD face, or on the surface
  /// Largest distance of a boundary mid-edge node's target from the midpoint of its edge: how far
  /// the second order moves them (relative figures divide by `diagonal`).
  double max_offset = 0;
  double diagonal = 0;  ///< bounding-box diagonal of the mesh
  CurveReport curve;    ///< what curve_mid_nodes kept of the targets
  double seconds = 0;
};

/// Moves every mid-edge node v of the second-order `mesh` with has_target[v] (#V entries) to
/// target.row(v) (#V by 3), then, for each cell not accepted (CurveOptions::min_sj), halves the
/// offsets from the midpoints of its targeted mid-edge nodes, at most `halvings` times, then puts
/// them on the midpoints, re-judging the cells around every node moved, until every cell is
/// accepted. By construction every cell ends at least at min(min_sj, its straight value): a cell
/// all of whose mid-edge nodes are on the midpoints has exactly its straight shape. The other
/// mid-edge nodes and the corners stay where they are. Throws InputError for a first-order mesh,
/// std::invalid_argument for sizes that do not match.
CurveReport curve_mid_nodes(mesh::Mesh& mesh, const Eigen::MatrixXd& target, const std::vector<char>& has_target,
                            const CurveOptions& options = {});

/// `linear` (first order, volume cells) made second order (mesh::add_mid_edge_nodes) with the
/// mid-edge node of every boundary edge on the nearest point of the closed triangle surface
/// `surface` it was meshed from, then curve_mid_nodes. `report` gets the figures when given.
mesh::Mesh second_order_on_surface(const mesh::Mesh& linear, const mesh::SurfaceMesh& surface,
                                   const CurveOptions& options = {}, SecondOrderReport* report = nullptr);

}  // namespace hexdom::optimize
