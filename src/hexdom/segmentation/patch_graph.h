// The patches of a segmented surface as a graph: the boundary graph (polycube::BoundaryGraph:
// patches = regions of one id, corners, curves between corners, every loop of every patch) with what
// the segmentation measures on each patch: its Euler characteristic, normal, area, nearest axis and
// centroid.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/polycube/boundary_graph.h"
#include "hexdom/polycube/patch_layout.h"

namespace hexdom::segmentation {

using PatchCurve = polycube::BoundaryCurve;

struct PatchGraph : polycube::BoundaryGraph {
  polycube::PatchLayout layout;  ///< the graph's PatchLayout view (corners where 3+ patches meet, first loops)
  std::vector<int> euler;        ///< per patch: Euler characteristic V - E + F (1 for a disk)
  Eigen::MatrixXd normal;        ///< #patches by 3 area-weighted unit normal
  Eigen::VectorXd area;          ///< #patches
  Eigen::VectorXi axis;          ///< #patches label 1..6 of the axis nearest to `normal`
  Eigen::MatrixXd centroid;      ///< #patches by 3 area-weighted centroid
  int num_patches() const { return num_regions(); }
  /// Patch r's curves along its first boundary loop (loops[r][0].curves: i or ~i), empty for a
  /// patch without boundary.
  const std::vector<int>& patch_curves(int r) const;
};

/// Builds the graph of a closed manifold surface (see check_surface), patches = edge-connected
/// regions of one patch id, numbered in the order of their first triangle.
PatchGraph patch_graph(const mesh::SurfaceMesh& surface);

}  // namespace hexdom::segmentation
