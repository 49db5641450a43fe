// The boundary graph of a labelled surface: regions (edge-connected triangles of one patch id), the
// corners where the boundary between them branches, the pinches where a region meets itself, the
// curves from corner to corner, and every boundary loop of every region with its corners and curves
// in loop order. The one graph behind polycube::PatchLayout, segmentation::PatchGraph and
// autopolycube::ChartGraph.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::polycube {

/// A boundary curve between two regions, from one corner to the next.
struct BoundaryCurve {
  int left = -1;   ///< region (0-based) whose triangles run along `vertices` counter-clockwise
  int right = -1;  ///< the region on the other side; left < right
  std::vector<int> vertices;  ///< surface vertices, corner to corner; a closed curve repeats its first vertex last
  bool closed = false;        ///< no corner on it: the two regions meet along a loop
};

/// One boundary loop of a region, run with the region on its left (counter-clockwise seen from
/// outside on an outward surface).
struct BoundaryLoop {
  /// The corners along it (surface vertices), in loop order; the loop's curves start at them, curve
  /// i at corner i. Empty for a loop that is one closed curve.
  std::vector<int> corners;
  /// Its curves in loop order: curve i as i when the region is its `left`, as ~i (bitwise not) when
  /// the loop runs it backwards. A closed curve's loop holds that one curve.
  std::vector<int> curves;
};

struct BoundaryGraph {
  Eigen::VectorXi region;          ///< #F region of each triangle
  std::vector<int> label;          ///< per region: the patch id of its triangles
  /// Per region: its triangles in flood-fill order (depth first from the region's lowest triangle,
  /// neighbours across edges 0, 1, 2); regions are numbered in the order of their lowest triangle.
  std::vector<std::vector<int>> triangles;
  /// Vertices around which the region changes three or more times (ascending): the ends of curves.
  /// Every vertex where three or more regions meet is one; so is a pinch (see below).
  std::vector<int> corners;
  Eigen::VectorXi corner_of;       ///< #V index into `corners`, -1 for other vertices
  std::vector<int> corner_regions; ///< per corner: how many distinct regions meet there (2 at a pinch of two regions)
  std::vector<int> pinches;        ///< vertices around which one region appears in two separate fans (ascending)
  std::vector<BoundaryCurve> curves;  ///< each curve once (numbered as the walk from the ascending corners finds them, closed curves last)
  std::vector<std::vector<int>> region_curves;  ///< per region: its curves (indices into `curves`, ascending)
  /// Per region, every boundary loop (the first starts at the region's lowest corner that starts one
  /// of its curves; loops without corners last). Empty for a region that is the whole surface.
  std::vector<std::vector<BoundaryLoop>> loops;
  /// #F x 3: the surface's mesh::triangle_adjacency, to build the graphs of its relabellings with.
  Eigen::MatrixXi adjacency;
  int num_regions() const { return static_cast<int>(label.size()); }
};

/// Checks that the surface is closed and 2-manifold (every edge shared by exactly two triangles,
/// consistently oriented) and free of degenerate triangles; throws GeometryError naming the first
/// offending edge or triangle (1-based vertex and triangle numbers, as in the .k file order).
void check_closed_manifold(const mesh::SurfaceMesh& surface);

/// Builds the boundary graph of `surface` by its patch ids (any ints). Throws GeometryError when the
/// surface is not closed, 2-manifold and consistently oriented (check_closed_manifold) or has not
/// one patch id per triangle. Deterministic: the same surface gives the same numbering.
BoundaryGraph boundary_graph(const mesh::SurfaceMesh& surface);

/// The same graph for a surface that passed check_closed_manifold, given its
/// mesh::triangle_adjacency(surface.F): many labellings of one triangulation (a repair's or a
/// collapse's candidates) pair its edges once. Throws GeometryError when the patch ids or the
/// adjacency do not have one row per triangle.
BoundaryGraph boundary_graph(const mesh::SurfaceMesh& surface, const Eigen::MatrixXi& adjacency);

}  // namespace hexdom::polycube
