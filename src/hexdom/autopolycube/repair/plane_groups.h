// Plane groups: charts of one axis that share a vertex must lie in one plane of the polycube (the
// vertex has a single coordinate along that axis), so they share one plane offset.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct PlaneGroups {
  std::vector<int> of_chart;               ///< per chart: its group
  std::vector<int> axis;                   ///< per group: 0, 1 or 2 (x, y, z)
  std::vector<std::vector<int>> charts;    ///< per group: its charts, ascending
  Eigen::MatrixXi of_vertex;               ///< #V by 3: group of the vertex along each axis, -1 if none
  int num_groups() const { return static_cast<int>(axis.size()); }
};

/// Unites the charts of each axis that share a vertex (a union-find over the triangles' vertices).
PlaneGroups plane_groups(const mesh::SurfaceMesh& labels, const ChartGraph& graph);

}  // namespace hexdom::autopolycube
