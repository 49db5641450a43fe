// What keeps a labelling from being the chart layout of a polycube, and a repair that relabels the
// smallest chart involved until nothing is left (or a limit is reached).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/autopolycube/chart_graph.h"
#include "hexdom/autopolycube/plane_groups.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

enum class ProblemKind {
  OppositeNeighbours,  ///< two charts of opposite labels (+X, -X) share a curve
  ClosedCurve,         ///< two charts meet along a loop that no third chart touches
  Pinch,               ///< a chart meets itself at a vertex
  FewCorners,          ///< a boundary loop of a chart has fewer than 4 corners
  MissingAxis,         ///< a corner where the charts span fewer than three axes
  ZeroLengthEdge,      ///< a curve whose two end corners lie in one plane group of its direction
  /// A boundary loop of a chart that cannot be a rectilinear polygon: walking its curves in their
  /// directions in the input (the sign of their axis coordinate from corner to corner), it doubles
  /// back or does not turn by +-360 degrees, or the chart's loops are not one outer and the rest holes.
  BadTurning,
};
/// "opposite_neighbours", "closed_curve", "pinch", "few_corners", "missing_axis", "zero_length_edge",
/// "bad_turning".
std::string kind_name(ProblemKind kind);

struct ChartProblem {
  ProblemKind kind;
  std::vector<int> charts;  ///< 0-based charts involved
  int vertex = -1;          ///< 0-based surface vertex at the place
  std::string message;      ///< names the charts (1-based) and the vertex (1-based)
};

/// Every problem of the labelled surface (patch = label 1..6 per triangle), in a fixed order.
std::vector<ChartProblem> chart_problems(const mesh::SurfaceMesh& labels, const ChartGraph& graph,
                                         const PlaneGroups& groups);

struct RepairOptions {
  int max_relabels = 200;  ///< charts relabelled at most
  LogCallback log;
};

struct RepairResult {
  Eigen::VectorXi label;  ///< #F repaired labels
  int relabelled = 0;     ///< charts relabelled
  std::vector<ChartProblem> remaining;  ///< problems left (empty on success)
};

/// Repeatedly takes the problem whose smallest chart has the least area and gives that chart the
/// label, among its neighbours' labels, that best fits its triangles' normals (area-weighted
/// n . axis), so that it joins a neighbour. Never throws for problems: they are returned.
RepairResult repair_labels(const mesh::SurfaceMesh& labels, const RepairOptions& options = {});

/// Relabels one chart (0-based) as repair_labels would; returns the new labels. With `problems` > 0
/// (the current number of problems), every candidate label is tried and one that leaves fewer
/// problems is taken; otherwise, or when none does, the chart joins the neighbour whose label fits
/// its normals best.
Eigen::VectorXi relabel_chart(const mesh::SurfaceMesh& labels, const ChartGraph& graph, int chart, int problems = 0);

}  // namespace hexdom::autopolycube
