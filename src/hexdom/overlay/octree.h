// An all-hex mesh of a grid's box refined by thirds where asked: an octree whose cells split into
// 27, made conforming by the vertex-marked 3-refinement templates (Schneiders 1996; Ito, Shih and
// Soni 2009). For the overlay path's cells to be finer where the part is thin or small without a
// finer grid over its whole box.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/overlay/grid.h"

namespace hexdom::overlay {

/// An octree cell: level L (0: a cell of the grid) and its index (i, j, k) among the cells of the
/// grid refined L times by thirds (spacing grid.h / 3^L), lowest corner origin + (i, j, k) h / 3^L.
struct OctreeCell {
  int level = 0;
  int i = 0, j = 0, k = 0;
};

struct OctreeMesh {
  mesh::Mesh mesh;          ///< hexahedra, VTK order, every one of positive volume; region 1
  std::vector<int> level;   ///< per cell: the level of the octree cell it is in (or is)
  std::vector<char> plain;  ///< per cell: 1 for an octree cell itself, 0 for a piece of a template
  int levels = 0;           ///< finest lattice level reached (a template's nodes lie on its level + 1)
  int templates = 0;        ///< octree cells replaced by a transition template
};

/// The grid's cells, each split into 27 where `refine` asks (and its children likewise, down to
/// max_level), the unsplit cells next to split ones replaced by transition templates so that the
/// mesh is conforming (every face shared by two cells is a face of both; no hanging node).
///
/// Refinement is decided per level by marking nodes: a cell that `refine` asks to split marks its
/// 8 corners; a cell with all 8 corners marked is split; a cell with the corner, edge (2) or face
/// (4) of one side marked gets the corner (4 hexes), edge (11) or face (22) template, whose faces
/// match the neighbours' (an edge is cut in thirds when both its ends are marked, at a third from
/// its marked end when one is). Other marks are made valid: a cell whose 8 corners may all be
/// marked gets them all (it is split), the cells with the most marks first, so that concavities of
/// the marked region fill before its staircase sides (which, split first, would grow the region
/// outwards cell by cell across the grid). A cell that may not
/// take all 8 has its marks cut to the largest valid subset.
/// A node of level L > 0 may be marked only when the 8 cells of level L around it exist, so that
/// a template never meets cells two levels finer. Cells `refine` asks to split may thus stay
/// whole near the edge of a refined region (the refined region grows by at most one cell at its
/// edges where marks are completed, and shrinks by one where they are cut).
///
/// Guarantees: conforming; all hexes of positive volume (the templates' worst scaled Jacobian is
/// about 0.2 before any smoothing); they fill the grid's box exactly.
OctreeMesh octree_mesh(const Grid& grid, int max_level, const std::function<bool(const OctreeCell&)>& refine);

/// The box [lo, lo + size] of an octree cell of `grid`.
Eigen::Vector3d octree_cell_origin(const Grid& grid, const OctreeCell& c);
Eigen::Vector3d octree_cell_size(const Grid& grid, const OctreeCell& c);

}  // namespace hexdom::overlay
