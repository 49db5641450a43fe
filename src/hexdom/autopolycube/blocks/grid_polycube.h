// The grid polycube as the automatic polycube hands it from step to step: the grid cells and their
// boundary squares, the structure of blocks over the cells, and the patch surface cut along the grid.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <vector>

#include "hexdom/autopolycube/blocks/polycube_grid.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

/// As cut_along_grid and grid_structure leave it: `grid_of` has one grid point per structure vertex,
/// every grid point on the polycube's surface has a patch vertex in `grid_vertex`, D has one row per
/// patch vertex, and patch ids are 1 + the index of the grid square (grid.squares) a triangle lies
/// in. collapse_slivers and collapse_apexes keep `structure` and `grid_of` in step; when they collapse
/// something they renumber the patch ids, and collapse_apexes drops unused patch vertices, after which
/// `grid_vertex` and D (never updated) no longer describe `patches`: one collapse per polycube.
struct GridPolycube {
  PolycubeGrid grid;                             ///< cells and boundary squares (polycube_grid)
  mesh::Mesh structure;                          ///< blocks (VTK order), region = 1-based block number
  std::vector<std::array<int, 3>> grid_of;       ///< grid point of each structure vertex
  mesh::SurfaceMesh patches;                     ///< the input's geometry cut along the grid lines
  std::map<std::array<int, 3>, int> grid_vertex; ///< grid point on the polycube -> vertex of `patches`
  Eigen::MatrixXd D;                             ///< #patches.V by 3 positions on the polycube (grid units)
};

}  // namespace hexdom::autopolycube
