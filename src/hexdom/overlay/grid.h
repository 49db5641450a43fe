// The overlay path's background grid: a box of cubes of one spacing, and which of its nodes lie
// inside a closed triangle surface and how far from it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::overlay {

/// A box of nx x ny x nz cells of spacing h (per axis) whose lowest corner is `origin`. Node (i, j, k),
/// 0 <= i <= nx, has index i + (nx + 1) * (j + (ny + 1) * k); cell (i, j, k) index
/// i + nx * (j + ny * k), its corners the nodes (i..i+1, j..j+1, k..k+1).
struct Grid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d h = Eigen::Vector3d::Ones();
  int nx = 0, ny = 0, nz = 0;

  int64_t num_nodes() const { return int64_t(nx + 1) * (ny + 1) * (nz + 1); }
  int64_t num_cells() const { return int64_t(nx) * ny * nz; }
  int64_t node(int i, int j, int k) const { return i + int64_t(nx + 1) * (j + int64_t(ny + 1) * k); }
  int64_t cell(int i, int j, int k) const { return i + int64_t(nx) * (j + int64_t(ny) * k); }
  Eigen::Vector3d position(int i, int j, int k) const { return origin + h.cwiseProduct(Eigen::Vector3d(i, j, k)); }
  /// The 8 corner nodes of cell (i, j, k) in VTK hexahedron order.
  std::array<int64_t, 8> corners(int i, int j, int k) const;
};

/// The grid of about spacing h (per axis) over the surface's bounding box: along each axis the
/// box's extent is cut into a whole number of cells (the spacing rounded to fit) and the grid's
/// planes lie half a cell off the box's faces, so that a face of the box (a part square to the
/// frame) is half a cell from the nearest plane inside; the grid reaches 1.5 cells beyond the box.
Grid grid_around(const Eigen::MatrixXd& V, const Eigen::Vector3d& h);

/// The grid whose nodes are the centres of g's cells: node (i, j, k) of the result is the centre of
/// cell (i, j, k) of g (g.nx - 1 by g.ny - 1 by g.nz - 1 cells, the same spacing).
Grid cell_centres(const Grid& g);

/// Spacing per axis for element size `size` over a bounding box of `extent`: `size` along every
/// axis, less along an axis the box is thin in, so that it spans at least `across` cells, but not
/// less than `min_size` (when > 0; a thinner part then spans fewer cells); no cell longer than
/// `ratio` times its shortest side (a plate gets flat cells, a rod long ones, neither needles).
Eigen::Vector3d grid_spacing(const Eigen::Vector3d& extent, double size, double across, double ratio,
                             double min_size = 0);

/// The wall thickness of the solid bounded by `surface` (closed, oriented outward): behind each
/// triangle, the distance from its centroid inward along its normal to the next triangle the ray
/// meets; of those, the one that `quantile` of the surface's area lies on walls no thicker than
/// (0.5: the median by area). +infinity when no ray meets another triangle.
double wall_thickness(const mesh::SurfaceMesh& surface, double quantile);

/// Per grid node: inside the closed surface or not, and, for nodes within `band` of the surface
/// (a bound on it, not the exact set), the distance to it; other nodes get +infinity.
struct NodeField {
  std::vector<char> inside;
  std::vector<double> distance;
};

/// Classifies the grid nodes against `surface` (closed, oriented outward) by counting, along each
/// grid line in x, the signed crossings of the triangles ahead of each node (the winding number).
/// The lines are shifted by a tiny irrational fraction of the spacing, so that they miss the triangles'
/// edges and vertices. A line whose crossings do not sum to zero (the surface is not closed
/// along it) takes its nodes' side from the nearest triangle's normal instead.
NodeField classify_nodes(const Grid& grid, const mesh::SurfaceMesh& surface, double band);

/// Per point: inside the closed surface or not, by the winding number of a ray in +x (shifted like
/// classify_nodes' lines; a ray whose crossings do not cancel takes the nearest triangle's side), and
/// its distance to the surface (every point's).
NodeField classify_points(const std::vector<Eigen::Vector3d>& points, const mesh::SurfaceMesh& surface);

}  // namespace hexdom::overlay
