// The polycube map of a labelled surface: every chart flattened onto an axis-aligned plane, the
// planes snapped to a grid of spacing `cell`, every chart boundary curve straightened between its
// corners and every chart interior mapped harmonically into its plane polygon.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct PolycubeMapOptions {
  double cell = 0;  ///< grid spacing h (model units); must be positive
  /// Extra orders: plane group `second` must lie at least one cell above plane group `first` (same axis).
  std::vector<std::pair<int, int>> separate;
  /// Two parallel curves of one chart whose spans only touch (end at one grid line) are kept a cell
  /// apart too, not only those whose spans overlap (e.g. a hole's side and the outer boundary's).
  bool separate_touching = true;
  /// Two charts of opposite labels that bound one chart from opposite sides and face each other across
  /// a void (a hole's or a slot's two walls: opposite mean normals within 20 degrees, each pointing to
  /// the other's centroid) get planes as many cells apart as their input distance (centroid to centroid
  /// along their mean normal, rounded, at least 1), not only one: the least-squares offsets of curved
  /// charts shrink a round hole to a narrower tunnel than its width, a tilted one most.
  bool keep_widths = true;
  /// A curved chart boundary curve (off its chord by 5% of it somewhere: a straight edge loses no
  /// volume between its nodes) whose span between the least-squares plane offsets of its end
  /// corners is below this share of its input chord gets at least length_share times its input length in
  /// cells (the arc, at most 1.25 times the chord, rounded), when that is 2 or more cells beyond the
  /// span: the side charts of a cone get planes that compromise between the base and the tip, and
  /// the base rim too few nodes. 0: least-squares offsets only.
  double keep_lengths = 0.6;
  /// The share of its input length a curve of keep_lengths keeps in cells (docs/tuning-notes.md).
  double length_share = 0.6;
  /// Untangle folded charts by the barrier energy of untangle_plane_map (otherwise only local moves).
  bool untangle = true;
  /// Checked before each chart is mapped and in the untangling's rounds: once passed, polycube_map
  /// throws TimeoutError ("autopolycube (chart maps): ...").
  Deadline deadline;
  LogCallback log;
};

struct PolycubeMap {
  /// #V by 3: the least-squares deformation (model units) that keeps the surface's gradients
  /// (cotangent Dirichlet energy of u - u0, per axis) while every plane group is flat at a free offset.
  Eigen::MatrixXd continuous;
  /// #V by 3: the polycube in grid units: chart planes at integers, curves straight between corners
  /// at integer grid points, chart interiors harmonic; coordinates within 1e-6 of a grid line lie on it.
  Eigen::MatrixXd D;
  Eigen::VectorXd offset;  ///< per plane group: its offset in `continuous` (model units)
  Eigen::VectorXi plane;   ///< per plane group: its integer plane (grid units)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< model position of grid point (0, 0, 0)
  double cell = 0;         ///< h: model position = origin + h * D
  std::vector<int> flipped;  ///< per chart: triangles whose orientation in its plane is wrong or zero
  int pushed = 0;            ///< plane groups moved more than one cell to keep every curve's length >= h
  /// Times keep_widths asked more than one cell between two walls facing across a void; 0: the map
  /// is the one keep_widths = false gives.
  int widened = 0;
  int lengthened = 0;  ///< curves given the cells of their input length (keep_lengths)
};

/// Computes the map. Expects a labelling without chart problems (see chart_problems) and no
/// chord edges (split_chords). Throws GeometryError when the curves' directions order the planes of
/// one axis in a cycle, naming the charts, and MeshingError when a solve fails.
PolycubeMap polycube_map(const mesh::SurfaceMesh& labels, const ChartGraph& graph, const PlaneGroups& groups,
                         const PolycubeMapOptions& options);

/// The polycube in model units (origin + h D) with the labels as patch ids, for inspection.
mesh::SurfaceMesh polycube_surface(const mesh::SurfaceMesh& labels, const PolycubeMap& map);

}  // namespace hexdom::autopolycube
