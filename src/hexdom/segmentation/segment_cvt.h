// Polycube segmentation: centroidal Voronoi tessellation (CVT) of the triangle normals with the six
// generators +-X, +-Y, +-Z, first with the classical energy, then with an edge-weighted
// (harmonic boundary-enhanced) energy that straightens non-monotone, zig-zag boundaries.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

/// Whether CAD face ids (the input surface's patch ids) constrain the labels.
enum class FaceMode { Auto, On, Off };

struct CvtOptions {
  /// lambda of the edge-weighted pass: distance^2 = |n - g|^2 / 4 + 2 lambda (N - N_same) / N over
  /// the triangle's neighbourhood of N triangles, N_same of them carrying the candidate label.
  /// 0 skips the pass (classical CVT only).
  double edge_weight = 0.1;
  int classical_sweeps = 50;  ///< at most this many sweeps of the classical pass
  int edge_sweeps = 200;      ///< at most this many sweeps of the edge-weighted pass
  /// Degrees: the classical pass moves each generator toward its region's mean normal, but no
  /// further than this from its axis (labels name axes, and the polycube's faces are axis-aligned).
  double max_drift = 10.0;
  int min_moves = 3;          ///< the classical pass stops after a sweep with fewer moves
  int ring = 2;               ///< neighbourhood of the edge term: triangles within `ring` edge steps
  /// Auto: on when the surface carries more than one patch id (CAD faces, e.g. from `hexdom
  /// tessellate`). On: a planar face keeps one label; a curved face whose triangles' nearest axes
  /// give one label to `face_majority` of its area takes that label entirely; both are fixed during
  /// the passes, and the edge term counts only neighbours of the same face, so that boundaries follow
  /// CAD edges where the normals allow it.
  FaceMode respect_faces = FaceMode::Auto;
  double planar_angle = 1.0;    ///< degrees: a face whose normals all lie this close to its mean is planar
  double face_majority = 0.9;   ///< area share above which a curved face takes one label
  /// Fixed labels: (0-based triangle, label 1..6), e.g. from read_manual_labels; never moved.
  std::vector<std::pair<int, int>> manual;
  /// The frame the labels refer to: +X is the frame's first axis, x_frame = frame * x (a rotation;
  /// see cube_frame). The identity: the model's own axes. Generators are given in the frame.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  LogCallback log;
};

struct Segmentation {
  Eigen::VectorXi label;      ///< #F label 1..6 (+X, -X, +Y, -Y, +Z, -Z) per triangle
  Eigen::VectorXi classical;  ///< #F label after the classical pass (before the edge-weighted one)
  Eigen::Matrix<double, 6, 3> generators;  ///< generator normals after the classical pass, row k for label k+1
  int classical_sweeps = 0, edge_sweeps = 0;
  int classical_moves = 0, edge_moves = 0;
  bool respected_faces = false;
  int faces = 0, planar_faces = 0, uniform_faces = 0;  ///< CAD faces, planar ones, curved ones given one label
};

/// Labels each triangle 1..6. Every triangle starts at its nearest axis (manual labels and planar
/// CAD faces are fixed); in each sweep a triangle on a region boundary may move to a neighbouring
/// region whose generator is nearer. The classical pass updates each generator to its region's
/// area-weighted mean normal and stops after a sweep with fewer than `min_moves` moves; the
/// edge-weighted pass keeps the generators and stops when nothing moves.
/// Throws GeometryError for an open, non-manifold or inconsistently oriented surface or a zero-area
/// triangle, InputError for a manual label naming a missing triangle or a label outside 1..6.
Segmentation segment_cvt(const mesh::SurfaceMesh& surface, const CvtOptions& options = {});

}  // namespace hexdom::segmentation
