// Oblique triangular faces split from their corners (issue 9, "prism / tet blocks where a chart is
// triangular").
//
// A flat face whose normal is far from every axis, bounded by three creases whose neighbours carry
// one label of each axis (the slanted face of a tetrahedron, a corner cut off a box), has no label
// that makes a polycube: its normal is about as near +X as +Y and +Z, so the segmentation gives it
// one label (which then lies beside the opposite label along a whole edge) or a ragged split, and
// the label repair gives up. Its polycube is the corner of a cube: the face is cut into three quads
// along the segments from its centre to the midpoints of its sides (the medians' halves), the quad
// at each corner taking the axis of the opposite side's neighbour (the axis its two own neighbours
// lack), with the sign of the face's normal along it. Each quad has four corners: a corner of the
// face, two side midpoints and the centre, where the three quads meet as a polycube corner.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct ObliqueFaceOptions {
  /// Degrees: the face's mean normal lies at least this far from every axis ((1, 1, 1): 54.7).
  double min_axis_angle = 40.0;
  /// ... and has at least this component along every axis (a face leaning between two axes only,
  /// such as a 45 degree chamfer, is no octant's face).
  double min_component = 0.2;
  double max_bend = 5.0;     ///< degrees between the normals of neighbouring triangles of the face
  double max_spread = 10.0;  ///< degrees between any triangle's normal and the first one's
  double min_crease = 20.0;  ///< degrees between the normals across every boundary edge of the face
  double corner_angle = 30.0;  ///< degrees the boundary turns (in the face's plane) at a corner
  double min_side = 0;       ///< model units: each side at least this long (e.g. two element sizes)
  LogCallback log;
};

struct ObliqueFace {
  std::array<Eigen::Vector3d, 3> corners;  ///< the face's corners, in the boundary's order
  std::array<int, 3> labels{};             ///< the label (1..6) given to the quad at each corner
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< area-weighted mean unit normal
};

/// Finds the oblique triangular faces of `labels` (closed surface, patch = label 1..6) and cuts each
/// into three quads labelled from its corners (see above). Triangles are cut along the segments
/// (cut_triangles; new vertices appended, old ones keep their indices, the geometry unchanged), and
/// a crease edge the cut meets is split with the triangle beyond it, so the surface stays conforming.
/// Returns the faces split.
std::vector<ObliqueFace> split_oblique_faces(mesh::SurfaceMesh& labels, const ObliqueFaceOptions& options = {});

}  // namespace hexdom::autopolycube
