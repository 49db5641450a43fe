// The boundary of the polycube a segmented surface asks for, as the original Polycube step wrote
// it: its corners, its edges (the boundary curves between corners) and one face per patch over the
// patch's 3 or 4 corners. The interior structure is built from it by hand (paper, Sec. 3.2).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

struct PolycubeEdge {
  int corners[2] = {-1, -1};  ///< indices into PolycubeBoundary::corner_vertices
  int patches[2] = {0, 0};    ///< 1-based patches on either side (left of the path first)
  std::vector<int> path;      ///< surface vertices from the first corner to the second
};

struct PolycubeFace {
  int patch = 0;              ///< 1-based patch number (the shell id)
  int id = 0;                 ///< part id of the patch's triangles
  /// 3 or 4 corner indices, counter-clockwise seen from outside, starting (as the original did) at
  /// the first corner met when scanning the patch's triangles in order
  std::vector<int> corners;
};

struct PolycubeBoundary {
  std::vector<int> corner_vertices;  ///< 0-based surface vertex of each corner, ascending
  Eigen::MatrixXd corners;           ///< #corners by 3 positions
  std::vector<PolycubeEdge> edges;   ///< each boundary curve once
  std::vector<PolycubeFace> faces;   ///< one per patch, in patch order (order of first triangle)
};

/// Corners (vertices where 3 or more patches meet, ascending vertex order), edges and faces of a
/// segmented closed manifold surface. Throws GeometryError when the surface is unfit (see
/// check_surface) or a patch is not a disk with 3 or 4 corners, naming up to 5 such patches (run
/// check_patches for the full list).
PolycubeBoundary polycube_boundary(const mesh::SurfaceMesh& surface);

/// The faces as shells over the corners, as the original's initial polycube files: nodes = corners
/// in order, one quad or triangle per patch, region (part id) = patch number.
mesh::Mesh polycube_shells(const PolycubeBoundary& boundary);

/// Writes "vertexIndex x y z" per corner (0-based surface vertex; the original's corner files).
void write_corner_file(const std::string& path, const PolycubeBoundary& boundary);
/// Writes the corners and the edges' paths as legacy VTK POLYDATA (VERTICES and LINES, cell data
/// "patch_a", "patch_b") for display.
void write_edges_vtk(const std::string& path, const mesh::SurfaceMesh& surface, const PolycubeBoundary& boundary);

}  // namespace hexdom::segmentation
