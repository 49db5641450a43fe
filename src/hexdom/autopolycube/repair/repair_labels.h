// What keeps a labelling from being the chart layout of a polycube, and a repair that relabels the
// smallest chart involved until nothing is left (or a limit is reached).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/common/deadline.h"
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
  /// A curve between two charts that runs along a convex sharp edge in part and along a concave one
  /// in part (each at least a tenth of its length and a minimum length, e.g. the element size;
  /// sharp: normals more than 35 degrees apart), as
  /// where two tangent surfaces part at a cusp and one chart wraps around the tip of the other. A
  /// polycube edge is either convex or concave, so the map must fold there. Reported by
  /// mixed_convexity_problems, not chart_problems: a labelling with such a curve still gives a
  /// polycube (folds that the map untangles, poor blocks there).
  MixedConvexity,
};
/// "opposite_neighbours", "closed_curve", "pinch", "few_corners", "missing_axis", "zero_length_edge",
/// "bad_turning", "mixed_convexity".
std::string kind_name(ProblemKind kind);

struct ChartProblem {
  ProblemKind kind;
  std::vector<int> charts;  ///< 0-based charts involved (for bad_turning: the chart itself first)
  int vertex = -1;          ///< 0-based surface vertex at the place
  std::string message;      ///< names the charts (1-based) and the vertex (1-based)
};

/// Every problem of the labelled surface (patch = label 1..6 per triangle), in a fixed order.
std::vector<ChartProblem> chart_problems(const mesh::SurfaceMesh& labels, const ChartGraph& graph,
                                         const PlaneGroups& groups);

/// The curves of the labelled surface that are convex in part and concave in part (MixedConvexity),
/// each part at least `min_length` long (0: the bounding-box diagonal / 30). Shorter parts lie
/// within a cell or two and do not fold the map beyond what its untangling mends.
std::vector<ChartProblem> mixed_convexity_problems(const mesh::SurfaceMesh& labels, const ChartGraph& graph,
                                                   double min_length = 0);

struct RepairOptions {
  int max_relabels = 200;  ///< charts (or bands) relabelled at most
  /// Width (model units) of the bands relabelled between opposite charts or along creases; 0: the
  /// bounding-box diagonal / 30 (autopolycube passes the element size).
  double band_width = 0;
  /// Degrees: two triangles of one chart whose normals differ by more than this meet at a crease.
  double crease_angle = 35.0;
  /// Checked at the head of every round and before every band tried: once passed, repair_labels
  /// throws TimeoutError ("autopolycube (label repair): stopped after the time budget of ...").
  Deadline deadline;
  LogCallback log;
};

struct RepairResult {
  Eigen::VectorXi label;  ///< #F repaired labels
  int relabelled = 0;     ///< charts and bands relabelled
  int banded = 0;         ///< of them, bands along a curve between opposite charts or a crease
  std::vector<ChartProblem> remaining;  ///< problems left (empty on success)
};

/// Repairs triangles, not only whole charts. In each round, unless the smallest chart named by a
/// problem is below band_width^2 in area (a sliver, relabelled whole): two opposite charts that share a curve,
/// both of at least band_width^2 area, get a band (relabel_band, band_width / 2, 1, 2 or 4
/// band_width wide, on either side: a bend of the polycube) when one leaves fewer problems; else a
/// chart with a bad_turning problem that is folded over a crease (crease_angle, at least band_width long,
/// e.g. a hole's wall labelled like the face it leaves) gets a band on one side of the crease when
/// one leaves fewer problems; else the problem whose smallest chart has the least area gives that
/// chart the label, among its neighbours' labels, that best fits its triangles' normals
/// (relabel_chart). When no problem is left, a curve of mixed convexity (mixed_convexity_problems,
/// each part at least band_width long)
/// gets a band of one of its charts along its concave or its convex part, given the other chart's
/// label and limited to the triangles within band_width or 2 band_width of that part and nearer to it than
/// to the chart's other curves (at a cusp: the tip of the chart that the other wraps around), when one
/// leaves no problem and fewer such curves, the least normal fit lost first; such curves that no band
/// repairs are left (not returned). Stops when no problem is left, after max_relabels, or when a
/// labelling comes back (a cycle). Never throws for problems: they are returned; throws TimeoutError
/// when options.deadline passes.
RepairResult repair_labels(const mesh::SurfaceMesh& labels, const RepairOptions& options = {});

/// The labels with the triangles of `chart` within `width` (centroid to the nearest vertex of
/// `curve`, grown edge by edge from the curve inside the chart) given the label, of the two axes other
/// than the chart's, that fits each triangle's normal best.
Eigen::VectorXi relabel_band(const mesh::SurfaceMesh& labels, const ChartGraph& graph, int chart,
                             const std::vector<int>& curve, double width);

/// Relabels one chart (0-based) as repair_labels would; returns the new labels. With `problems` > 0
/// (the current number of problems), every candidate label is tried and one that leaves fewer
/// problems is taken; otherwise, or when none does, the chart joins the neighbour whose label fits
/// its normals best.
Eigen::VectorXi relabel_chart(const mesh::SurfaceMesh& labels, const ChartGraph& graph, int chart, int problems = 0);

}  // namespace hexdom::autopolycube
