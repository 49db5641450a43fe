// Figures of a segmentation: how well labels follow the normals and how clean the boundaries are.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

struct SegmentationStats {
  int patches = 0;             ///< connected regions of one label
  int small_patches = 0;       ///< regions of fewer than 10 triangles (islands)
  double boundary_length = 0;  ///< total length of the edges between two labels
  /// Zig-zag measure: triangles with two or three edge neighbours of one other label (the boundary
  /// turns around a single triangle: a tooth or a notch; a triangle at a patch corner, whose two
  /// foreign neighbours carry different labels, does not count).
  int teeth = 0;
  double max_angle = 55;        ///< degrees, the threshold of axis_fraction
  /// Area share of the triangles whose normal is within max_angle of their label's axis, over all
  /// triangles and per label 1..6 (index 0..5; NaN for an unused label).
  double axis_fraction = 0;
  std::array<double, 6> label_axis_fraction{};
  std::array<double, 6> label_area{};  ///< area per label
};

/// Measures `label` (#F, values 1..6) on a closed manifold surface.
SegmentationStats segmentation_stats(const mesh::SurfaceMesh& surface, const Eigen::VectorXi& label,
                                     double max_angle = 55.0);

/// One line per figure, for people.
std::string to_text(const SegmentationStats& stats);

}  // namespace hexdom::segmentation
