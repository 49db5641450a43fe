// Prism blocks where the polycube has a thin strip chart: the knife edge of a wedge-like feature,
// where the label repair put a band of a third label between two nearly opposite charts. In the
// polycube that band is a row of squares at least one cell wide; in reality either its edges across
// are much shorter than its edges along (a sliver), or the
// band lies in the plane of the side it was cut from, so the hex blocks under it have an angle of
// nearly 180 degrees where the band meets that side (scaled Jacobian about 0). Collapsing the
// strip's edges across turns those blocks into prisms (the paper's degenerate cubes) and the
// strip's squares join the neighbouring patches by patch id only: the geometry and the triangles of
// the patch surface do not change.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "hexdom/autopolycube/blocks/grid_polycube.h"
#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct CollapseSliversOptions {
  /// A strip is a sliver when the real length across it (the sum of its edges across along one
  /// cross line, the longest such line) is at most this share of its shortest edge along it; a
  /// sliver collapses unless that lowers the worst block (quality_slack).
  double max_ratio = 0.35;
  double quality_slack = 0.0;
  /// A strip whose hex blocks' worst scaled Jacobian is at most this collapses too, whatever its
  /// ratio, when the prisms' worst is higher by at least min_gain.
  double poor_quality = 0.2;
  double min_gain = 0.05;
  /// Keep a collapse only when the blocks it changes keep their volume within this share: a strip
  /// that is not in the plane of the patch it joins leaves a crease inside that patch, and the mesh
  /// cuts across it.
  double max_volume_change = 0.01;
  /// Checked before each strip (each costs a match of every block face to the patches): once
  /// passed, collapse_slivers throws TimeoutError ("autopolycube (slivers): ...").
  Deadline deadline;
  LogCallback log;
};

struct CollapseSlivers {
  int candidates = 0;  ///< strip charts (1 or 2 squares wide) seen
  int slivers = 0;     ///< of them, thin (max_ratio) or with poor hex blocks (poor_quality)
  int collapsed = 0;   ///< of them, collapsed (valid blocks, matching patches, not worse)
  int prisms = 0, tets = 0;
  int merged_squares = 0;  ///< squares whose triangles joined a neighbouring patch
};

/// Collapses the sliver strips of `polycube.grid` in `polycube.structure` (hex blocks over the grid
/// cells) and merges their squares' patches in `polycube.patches` (patch = 1 + square index,
/// renumbered 1..n after merging).
/// A strip is a chart whose squares form a 1 x n or 2 x n rectangle (wider strips cannot collapse
/// by patch ids: more patches than the 4 squares around a grid point would have to meet at one
/// corner); its cross lines (n + 1 of them) each become one vertex, the one that stays a corner of the patch surface (the middle of a
/// 2-wide strip, the far side of a 1-wide strip whose squares join the near side's patches). A
/// collapse is kept only if every block stays a hex, prism or tet, every boundary face of the
/// structure matches exactly one patch by its corners, and the blocks' quality does not drop
/// (thin strips) or rises (strips with poor hex blocks).
/// Unused vertices are dropped from `structure` (and `grid_of`); `grid`, `grid_vertex` and `D` stay.
CollapseSlivers collapse_slivers(GridPolycube& polycube, const CollapseSliversOptions& options = {});

/// The vertex ids of each face of a cell of `type` with `nodes` (VTK order), sorted: faces of
/// different cells are the same face when these match.
std::vector<std::vector<int>> sorted_faces(mesh::CellType type, const std::array<int, 8>& nodes);

}  // namespace hexdom::autopolycube
