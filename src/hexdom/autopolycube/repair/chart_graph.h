// Charts of a labelled surface: the regions of its boundary graph (polycube::BoundaryGraph) when the
// patch ids are axis labels 1..6, with their areas: the graph that the automatic polycube turns into
// faces, vertices and edges.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/polycube/boundary_graph.h"

namespace hexdom::autopolycube {

using ChartCurve = polycube::BoundaryCurve;

/// The boundary graph with charts for regions: `label` is each chart's axis label 1..6 (+X, -X, +Y,
/// -Y, +Z, -Z), `region` the chart of each triangle, `triangles` each chart's triangles.
struct ChartGraph : polycube::BoundaryGraph {
  std::vector<double> area;  ///< per chart, summed in the order of `triangles`
  int num_charts() const { return num_regions(); }
};

/// Builds the graph of a closed, 2-manifold, consistently oriented surface whose patch ids are axis
/// labels 1..6 (charts = edge-connected regions of one label, numbered in order of first triangle).
/// Throws GeometryError for an open or non-manifold surface or a label outside 1..6.
ChartGraph chart_graph(const mesh::SurfaceMesh& labels);
/// The same for a relabelling of a surface whose graph was built (`adjacency`: that graph's, the
/// surface checked then): its edges are not paired again. Empty: as chart_graph(labels).
ChartGraph chart_graph(const mesh::SurfaceMesh& labels, const Eigen::MatrixXi& adjacency);

/// "chart 4 (+Y, 120 triangles)"
std::string chart_name(const ChartGraph& graph, int chart);

}  // namespace hexdom::autopolycube
