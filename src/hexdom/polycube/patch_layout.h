// Patches of a segmented surface as generate reads them: the regions of the boundary graph, the
// corners where three or more of them meet, and each patch's first boundary loop as a vertex loop
// with its corners marked. A view of polycube::BoundaryGraph.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/polycube/boundary_graph.h"

namespace hexdom::polycube {

struct Patch {
  int label = 0;               ///< the surface's patch id (segmentation label) of its triangles
  std::vector<int> triangles;  ///< triangle indices (BoundaryGraph::triangles order)
  /// First boundary loop (BoundaryGraph::loops[r][0]) as vertex indices, in the direction of the
  /// triangles' orientation (counter-clockwise seen from outside for an outward surface), starting at
  /// the loop's first corner. Empty for a closed patch.
  std::vector<int> loop;
  std::vector<int> corners;    ///< loop positions (indices into `loop`) that are corners, in order
  int num_loops = 0;           ///< boundary loops (1 for a disk; a pinch splits a loop in two)
};

struct PatchLayout {
  Eigen::VectorXi region;      ///< #F patch (region) index of each triangle
  std::vector<Patch> patches;  ///< one per region, in region order
  /// Surface vertices where 3 or more patches meet, ascending (the graph's corners but its pinches
  /// of two regions).
  std::vector<int> corners;
  Eigen::VectorXi corner_of;   ///< #V index into `corners`, -1 for other vertices
};

/// The layout view of a boundary graph.
PatchLayout patch_layout(const BoundaryGraph& graph);

/// patch_layout(boundary_graph(surface)): throws GeometryError when the surface is not closed and
/// manifold (see check_closed_manifold).
PatchLayout patch_layout(const mesh::SurfaceMesh& surface);

}  // namespace hexdom::polycube
