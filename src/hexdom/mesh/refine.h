// Refinement of hexahedra by thirds with the vertex-marked 3-refinement templates (Schneiders
// 1996; Ito, Shih and Soni 2009). One table of templates serves the overlay path's octree and the
// refinement of any hex-dominant mesh around chosen nodes (refine_by_thirds).
#pragma once

#include <array>
#include <bitset>
#include <queue>
#include <utility>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

/// A point of a template in twelfths of the unit cube (0..12 per axis). A point whose three
/// coordinates are multiples of 4 lies on the cube's lattice of thirds and is shared with the
/// neighbours when it lies on a face; every other point is interior to the cube.
using P12 = std::array<int, 3>;
/// A hexahedron of a template, VTK corner order.
using Hex12 = std::array<P12, 8>;

/// Corner b (VTK order) of the unit cube.
extern const int kCubeCorner[8][3];

/// A symmetry of the cube: x[a] = flip[a] ? 12 - y[perm[a]] : y[perm[a]].
struct CubeSymmetry {
  std::array<int, 3> perm{0, 1, 2};
  std::array<bool, 3> flip{false, false, false};
  P12 apply(const P12& y) const;
};

/// The templates per mask of marked corners (bit b: corner b of kCubeCorner). Valid masks: none
/// (the cell as it is), all 8 (split in 27), one corner (corner template, 4 hexes), the two ends of
/// an edge (edge template, 11), the four corners of a face (face template, 22). Two cells sharing a
/// face with the same marks on its corners cut it alike: an edge is cut in thirds when both its ends
/// are marked, at the third next to its marked end when one is.
struct RefinementTemplates {
  int kind[256];                 ///< 0: none or all 8; 1 corner, 2 edge, 3 face; -1: not valid
  CubeSymmetry sym[256];         ///< takes the canonical template of `kind` onto the mask
  int largest_valid_subset[256]; ///< of the mask's corners, the valid mask with the most
  std::vector<Hex12> hexes[4];   ///< canonical templates; [0]: the 27 cubes of a split
  RefinementTemplates();
  /// The hexes of mask m (valid, not 0), after its symmetry; each with a positive volume.
  std::vector<Hex12> cells_for(int mask) const;
};

/// The table, built once.
const RefinementTemplates& refinement_templates();

/// Makes the marks of `cells` cells valid patterns (RefinementTemplates::kind >= 0), for the
/// octree's lattice and for refine_by_thirds alike. Completion first, the cells with the most marks
/// first (a cell in a concavity of the marked region before one beside its staircase, which, split
/// first, would grow the region outwards cell by cell): a cell whose marks are not valid gets all 8
/// when may_split(c); then the cut: each cell's marks cut to their largest valid subset, until every
/// cell's are valid (marks only go, so it ends). Callbacks: mask(c), the cell's mask of marked
/// corners; may_split(c); mark(c, b), marking corner b of cell c, true when it was not marked;
/// unmark(c, b); cells_at(c, b, out), appending to `out` the cells that have that corner.
template <class Mask, class MaySplit, class Mark, class Unmark, class CellsAt>
void settle_marks(int cells, Mask&& mask, MaySplit&& may_split, Mark&& mark, Unmark&& unmark, CellsAt&& cells_at) {
  const RefinementTemplates& tt = refinement_templates();
  auto count = [](int m) { return static_cast<int>(std::bitset<8>(m).count()); };
  std::vector<int> work;
  {
    std::priority_queue<std::pair<int, int>> heap;  // (marks, -cell): most marks, then lowest index
    auto push = [&](int c) {
      const int m = mask(c);
      if (tt.kind[m] < 0) heap.emplace(count(m), -c);
    };
    for (int c = 0; c < cells; ++c) push(c);
    while (!heap.empty()) {
      const auto [n, neg] = heap.top();
      heap.pop();
      const int c = -neg, m = mask(c);
      if (tt.kind[m] >= 0) continue;
      if (count(m) != n) {  // marked since: in its place again
        heap.emplace(count(m), neg);
        continue;
      }
      if (!may_split(c)) continue;  // left to the cut below
      for (int b = 0; b < 8; ++b)
        if (mark(c, b)) cells_at(c, b, work);
      for (int w : work) push(w);
      work.clear();
    }
  }
  for (int c = 0; c < cells; ++c) work.push_back(c);
  while (!work.empty()) {
    const int c = work.back();
    work.pop_back();
    const int m = mask(c);
    if (tt.kind[m] >= 0) continue;
    const int keep = tt.largest_valid_subset[m];
    for (int b = 0; b < 8; ++b)
      if ((m & ~keep) & (1 << b)) {
        unmark(c, b);
        cells_at(c, b, work);
      }
  }
}

/// What refine_by_thirds made.
struct Refinement {
  Mesh mesh;                ///< the refined mesh: the old nodes first, in their order
  std::vector<int> parent;  ///< per cell of `mesh`: the cell of the input it lies in
  std::vector<char> plain;  ///< per cell: 1 for an input cell kept or a cube of a split, 0 for a template's piece
  int split = 0;            ///< cells split in 27
  int templates = 0;        ///< cells replaced by a transition template
  int marked = 0;           ///< nodes marked once the marks were made valid
};

/// One level of refinement by thirds of the hexahedra of `m` around the nodes flagged in `marked`
/// (per node): each hexahedron whose 8 corners are marked is split in 27, one with a corner, an edge
/// or a face marked gets its transition template, so that the mesh stays conforming. Marks are made
/// valid first: a hexahedron with another pattern gets all 8 marked (those with the most marks
/// first, so that concavities of the marked region fill before its sides grow), unless one of its
/// nodes is fixed: a node of a cell that is not a hexahedron (prisms and tetrahedra are never cut)
/// or one flagged in `fixed` (per node, when given: e.g. the nodes of a template's pieces, so that
/// a second level never meets a piece of the first); then marks are cut to each cell's largest
/// valid subset until every cell's are valid.
///
/// New nodes are placed by the trilinear map of their hexahedron; a node on a face or an edge
/// shared with another cell is made once, at the same point from either side. Each new cell keeps
/// its parent's region and, when the parent is valid (positive corner Jacobians), its orientation.
/// Guarantees: conforming wherever the input is; the pieces of a parallelepiped fill it exactly
/// (of a trilinear hexahedron, up to the curvature of its map); nodes and cells outside the marked
/// region unchanged. Throws InputError for a second-order mesh.
Refinement refine_by_thirds(const Mesh& m, std::vector<char> marked, const std::vector<char>* fixed = nullptr);

}  // namespace hexdom::mesh
