// Patches of a segmented surface: connected regions of one label, the corners where three or more
// of them meet, and each patch's boundary loop split at its corners into curves.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::polycube {

struct Patch {
  int label = 0;               ///< the surface's patch id (segmentation label) of its triangles
  std::vector<int> triangles;  ///< triangle indices
  /// Boundary loop as vertex indices, in the direction of the triangles' orientation (counter-
  /// clockwise seen from outside for an outward surface). Empty for a closed patch.
  std::vector<int> loop;
  std::vector<int> corners;    ///< loop positions (indices into `loop`) that are corners, in order
  int num_loops = 0;           ///< boundary loops found (1 for a disk)
};

struct PatchLayout {
  Eigen::VectorXi region;      ///< #F patch (region) index of each triangle
  std::vector<Patch> patches;
  std::vector<int> corners;    ///< surface vertices where 3 or more patches meet
  Eigen::VectorXi corner_of;   ///< #V index into `corners`, -1 for other vertices
};

/// Checks that the surface is closed and 2-manifold (every edge shared by exactly two triangles,
/// consistently oriented) and free of degenerate triangles; throws GeometryError naming the first
/// offending edge or triangle (1-based vertex and triangle numbers, as in the .k file order).
void check_closed_manifold(const mesh::SurfaceMesh& surface);

/// Splits the surface into patches (edge-connected regions of one patch id) and finds corners and
/// boundary loops. Expects a closed manifold surface (see check_closed_manifold).
PatchLayout patch_layout(const mesh::SurfaceMesh& surface);

}  // namespace hexdom::polycube
