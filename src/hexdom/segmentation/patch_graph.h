// The patches of a segmented surface as a graph: patches (connected regions of one id, see
// polycube::patch_layout), the corners where three or more of them meet, and the boundary curves
// between consecutive corners that the polycube turns into its edges.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/polycube/patch_layout.h"

namespace hexdom::segmentation {

/// A boundary curve: the part of the boundary between two patches that runs from one corner to the
/// next (a closed curve, first vertex = last, when the two patches meet at no corner).
struct PatchCurve {
  int left = -1;   ///< patch (0-based) whose boundary loop runs along `vertices` (counter-clockwise)
  int right = -1;  ///< the patch on the other side
  std::vector<int> vertices;  ///< surface vertices, corner to corner
  bool closed() const { return vertices.size() > 1 && vertices.front() == vertices.back() && vertices.size() > 2; }
};

struct PatchGraph {
  polycube::PatchLayout layout;  ///< regions, corners, first boundary loop of each patch
  std::vector<PatchCurve> curves;  ///< each curve once
  /// Per patch: its curves along its first boundary loop, in loop order; curve i as i when the
  /// patch is its `left`, as ~i (bitwise not) when the curve runs the other way.
  std::vector<std::vector<int>> patch_curves;
  std::vector<int> euler;        ///< per patch: Euler characteristic V - E + F (1 for a disk)
  Eigen::MatrixXd normal;        ///< #patches by 3 area-weighted unit normal
  Eigen::VectorXd area;          ///< #patches
  Eigen::VectorXi axis;          ///< #patches label 1..6 of the axis nearest to `normal`
  Eigen::MatrixXd centroid;      ///< #patches by 3 area-weighted centroid
  int num_patches() const { return static_cast<int>(layout.patches.size()); }
};

/// Builds the graph of a closed manifold surface (see check_surface), patches = edge-connected
/// regions of one patch id, numbered in the order of their first triangle.
PatchGraph patch_graph(const mesh::SurfaceMesh& surface);

}  // namespace hexdom::segmentation
