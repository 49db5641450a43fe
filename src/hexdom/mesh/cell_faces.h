// Faces of volume cells, outward-oriented (right-hand normal pointing out of the cell), and the
// boundary of a volume mesh.
#pragma once

#include <array>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

struct LocalFace {
  int n;        ///< 3 or 4
  int v[4];     ///< local node indices, outward orientation
};

/// The faces of a cell type (6 for hex, 5 for wedge, 4 for tet), outward.
std::pair<const LocalFace*, int> cell_faces(CellType type);

/// The edges of a cell type (12 for hex, 9 for wedge, 6 for tet) as pairs of local nodes: hex
/// bottom ring, top ring, verticals; wedge and tet likewise.
std::pair<const std::array<int, 2>*, int> cell_edges(CellType type);

/// A face of the mesh boundary: a cell face no other cell shares.
struct BoundaryFace {
  int cell, local;          ///< the cell and its local face number
  int n;                    ///< 3 or 4
  std::array<int, 4> v;     ///< global nodes, outward orientation
};

/// Boundary faces of the volume cells of `mesh` (faces used by exactly one cell). Throws
/// GeometryError naming the nodes of a face shared by more than two cells (non-conforming mesh).
std::vector<BoundaryFace> boundary_faces(const Mesh& mesh);

/// The pairs of cells sharing a face (a < b in each pair), in increasing order of (a, b). Throws
/// GeometryError like boundary_faces for a face shared by more than two cells.
std::vector<std::array<int, 2>> face_neighbours(const Mesh& mesh);

/// The nodes of a boundary face: its corners, then for a second-order mesh the mid-edge node of each
/// edge from corner k to corner k + 1 (Gmsh's and VTK's quadratic quad / triangle order).
std::vector<int> face_nodes(const Mesh& mesh, const BoundaryFace& face);

/// Area vector of a boundary face: half the sum of the cross products of consecutive corners taken
/// about the corners' centroid; it points out of the mesh, and its length is the area of a planar
/// face.
Eigen::Vector3d face_area_vector(const Mesh& mesh, const BoundaryFace& face);

}  // namespace hexdom::mesh
