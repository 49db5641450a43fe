// The frame a part's faces fit: the rotation that turns the triangle normals closest to the six
// axis directions, so that a part lying at an angle in its model (placed turned in an assembly) is
// segmented and given a polycube as if it were square to the axes.
#pragma once

#include <Eigen/Core>

#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

struct CubeFrameOptions {
  /// The identity is kept unless the best rotation's fit beats it by more than this (fit is the
  /// area-weighted mean of sum_k (R n)_k^4, 1 for a box, 1/3 at worst): a part already square to the
  /// axes, or one whose faces the axes fit nearly as well as any frame, is left as it is.
  double min_gain = 0.02;
  /// Planar faces (normals shared by three triangles or more) weigh this many times their area in
  /// the fit: they set the frame, and curved faces only turn it where the planar ones leave it free
  /// (on a revolved part square to the axes, the conical faces alone would pull the fit to a frame
  /// tilted tens of degrees, its flat ends then at an angle).
  double planar_weight = 100;
  /// Starting rotations of the local ascent, spread over the rotation group (plus the identity).
  int starts = 72;
  int iterations = 60;  ///< ascent steps from each start
};

struct CubeFrame {
  /// Rotation taking the part's coordinates to the frame: x_frame = rotation * x. The identity
  /// when the part is kept as it is.
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double fit_identity = 0;  ///< fit of the part's own axes (planar faces weighted: planar_weight)
  double fit = 0;           ///< fit of `rotation` (== fit_identity when it is the identity)
  double angle_degrees = 0; ///< angle of `rotation`
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< its axis (unit; Z for the identity)
  bool turned() const { return angle_degrees > 0; }
};

/// Area-weighted mean over the triangles of sum_k (R n)_k^4: 1 when every normal lies along an
/// axis of the rotated frame. R must be a rotation.
double cube_fit(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation);

/// The rotation whose frame the triangle normals fit best (maximises cube_fit by gradient ascent
/// on the rotation group from `starts` starting rotations), or the identity when it gains less
/// than `min_gain`; planar faces weigh planar_weight times their area in these fits. Of the 24 equivalent rotations of a cube the one with the smallest angle is
/// returned. Deterministic. An empty surface gives the identity. The last 16 results are kept: a
/// surface whose triangle normals and areas (merged as the fit sees them) and options are those of
/// a kept call gets that call's frame after one pass over its triangles (the pipeline asks for the
/// frame of one surface in the tessellation, the polycube path and the overlay path).
CubeFrame cube_frame(const mesh::SurfaceMesh& surface, const CubeFrameOptions& options = {});

/// The surface with its vertices turned into the frame (x -> rotation * x); patch ids kept.
mesh::SurfaceMesh rotated(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation);

/// Diagonal of the bounding box of the surface turned into the frame (the model's box for the
/// identity): what the default element sizes (diagonal / 30) are taken from. 0 for no vertex.
double frame_diagonal(const mesh::SurfaceMesh& surface, const Eigen::Matrix3d& rotation);

/// A CubeFrame of a given rotation: its angle and axis (the fits left at 0).
CubeFrame frame_of(const Eigen::Matrix3d& rotation);

}  // namespace hexdom::segmentation
