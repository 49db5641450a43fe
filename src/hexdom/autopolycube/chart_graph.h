// Charts of a labelled surface (connected regions of one axis label 1..6), the corners where three
// or more of them meet and the curves between consecutive corners: the boundary graph that the
// automatic polycube turns into faces, vertices and edges.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

/// A boundary curve between two charts, from one corner to the next.
struct ChartCurve {
  int left = -1;   ///< chart (0-based) whose triangles run along `vertices` counter-clockwise
  int right = -1;  ///< the chart on the other side
  std::vector<int> vertices;  ///< surface vertices, corner to corner; closed curves repeat the first
  bool closed = false;        ///< no corner on it: the two charts meet along a loop
};

struct ChartGraph {
  Eigen::VectorXi chart;           ///< #F chart of each triangle
  std::vector<int> label;          ///< per chart: its label 1..6 (+X, -X, +Y, -Y, +Z, -Z)
  std::vector<double> area;        ///< per chart
  std::vector<int> triangles;      ///< per chart: triangle count
  std::vector<int> first_triangle; ///< per chart: its first triangle (charts are numbered in this order)
  std::vector<int> corners;        ///< vertices around which the charts change three or more times
  Eigen::VectorXi corner_of;       ///< #V index into `corners`, -1 for other vertices
  std::vector<int> pinches;        ///< vertices around which one chart appears in two separate fans
  std::vector<ChartCurve> curves;  ///< each curve once, left < right
  std::vector<std::vector<int>> chart_curves;  ///< per chart: its curves (indices into `curves`)
  /// Per chart, per boundary loop (found by chaining its curves): the corners along it; a closed
  /// curve is a loop without corners.
  std::vector<std::vector<std::vector<int>>> loop_corners;
  /// Per chart, per boundary loop (same order as loop_corners): its curves in loop order, curve i as
  /// i when the chart is its `left`, as ~i (bitwise not) when the loop runs it backwards; empty for a
  /// closed curve.
  std::vector<std::vector<std::vector<int>>> loop_curves;
  int num_charts() const { return static_cast<int>(label.size()); }
};

/// Builds the graph of a closed, 2-manifold, consistently oriented surface whose patch ids are axis
/// labels 1..6 (charts = edge-connected regions of one label, numbered in order of first triangle).
/// Throws GeometryError for an open or non-manifold surface or a label outside 1..6.
ChartGraph chart_graph(const mesh::SurfaceMesh& labels);

/// "chart 4 (+Y, 120 triangles)"
std::string chart_name(const ChartGraph& graph, int chart);

}  // namespace hexdom::autopolycube
