// Cutting the surface along the grid lines of its polycube, so that every boundary square of the
// polycube becomes one patch: the patch surface `hexdom generate` takes with the grid structure.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/blocks/polycube_grid.h"
#include "hexdom/autopolycube/map/polycube_map.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct GridCut {
  /// The input surface's geometry re-triangulated along the grid lines; patch = 1 + index of the
  /// grid square (PolycubeGrid::squares) each triangle lies in. Input vertices keep their indices.
  mesh::SurfaceMesh patches;
  Eigen::MatrixXd D;  ///< #V by 3 positions of `patches`' vertices on the polycube (grid units)
  std::map<std::array<int, 3>, int> grid_vertex;  ///< grid point on the polycube -> vertex of `patches`
};

/// Clips every triangle (in its chart's plane, grid units) by the grid lines of both in-plane axes;
/// a new vertex gets the input position at the same barycentric coordinates, so the surface keeps
/// its shape exactly. Expects no flipped triangle in `map`. Throws MeshingError when a piece falls
/// into a square the grid does not have or two vertices land on one grid point.
GridCut cut_along_grid(const mesh::SurfaceMesh& labels, const ChartGraph& graph, const PolycubeMap& map,
                       const PolycubeGrid& grid);

}  // namespace hexdom::autopolycube
