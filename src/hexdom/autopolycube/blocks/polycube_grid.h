// The polycube as grid cells: each chart's plane polygon rasterised into unit squares, the cells
// those squares enclose, and the check that the cells' boundary is exactly those squares.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/autopolycube/map/polycube_map.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

/// A unit square of the polycube's boundary, in plane x_axis = plane, spanning
/// [i, i+1] along axis (axis+1)%3 and [j, j+1] along (axis+2)%3.
struct GridSquare {
  int axis = 0, sign = 1;  ///< outward normal sign * e_axis
  int plane = 0, i = 0, j = 0;
  int chart = -1;
};

struct PolycubeGrid {
  std::vector<std::array<int, 3>> cells;  ///< lower corners of the cells inside, sorted
  std::vector<GridSquare> squares;        ///< boundary squares, sorted by (axis, plane, i, j)
  std::map<std::array<int, 4>, int> square_of;  ///< (axis, plane, i, j) -> index into squares
  /// Charts whose polygons overlap themselves or others, or whose squares do not bound the cells.
  std::vector<int> bad_charts;
  std::string problem;  ///< what went wrong (empty when bad_charts is empty)
};

/// Rasterises the charts of `map` (grid units) and fills the cells they enclose, by the parity of
/// the X squares along each grid row. Problems are returned in bad_charts / problem, not thrown.
PolycubeGrid polycube_grid(const mesh::SurfaceMesh& labels, const ChartGraph& graph, const PlaneGroups& groups,
                           const PolycubeMap& map);

}  // namespace hexdom::autopolycube
