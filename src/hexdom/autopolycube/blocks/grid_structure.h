// The polycube structure of the grid cells: one hex block per cell, boundary block vertices at
// their surface corners, interior ones placed harmonically and then untangled.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "hexdom/autopolycube/blocks/polycube_grid.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct GridStructureOptions {
  int untangle_rounds = 50;  ///< rounds of local moves of interior vertices
  /// Interior vertices of blocks whose scaled Jacobian is below this are moved (when it helps).
  double target_quality = 0.3;
  /// A move may not make an edge of the vertex shorter than this share of its mean edge length in
  /// the harmonic placement (the scaled Jacobian alone lets a block flatten to a slab); 0: no limit.
  double min_edge_share = 0.25;
  LogCallback log;
};

struct GridStructure {
  mesh::Mesh structure;                 ///< hex blocks (VTK order), region = 1-based block number
  std::vector<std::array<int, 3>> grid; ///< grid point of each structure vertex
  int boundary_vertices = 0, interior_vertices = 0;
  double min_quality_harmonic = 0;      ///< worst block scaled Jacobian before untangling
  double min_quality = 0;               ///< after untangling
  int inverted = 0;                     ///< blocks with scaled Jacobian <= 0 after untangling
};

/// Blocks over the grid cells; a structure vertex on the polycube's surface takes the position of
/// the surface vertex at its grid point (`grid_vertex`, positions `V`). Interior vertices solve the
/// discrete Laplace equation on the grid graph, then move one at a time to raise the worst scaled
/// Jacobian of their blocks. Throws MeshingError when a boundary grid point has no surface vertex.
GridStructure grid_structure(const PolycubeGrid& grid, const std::map<std::array<int, 3>, int>& grid_vertex,
                             const Eigen::MatrixXd& V, const GridStructureOptions& options = {});

}  // namespace hexdom::autopolycube
