// The six polycube orientations and the labels that name them: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z
// (the original program's generators 0..5 plus one, as its segmented files write them).
#pragma once

#include <Eigen/Core>
#include <string>

#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

/// Unit axis of a label 1..6; throws std::invalid_argument for other labels.
Eigen::Vector3d label_axis(int label);
/// "+X", "-X", "+Y", "-Y", "+Z", "-Z" for labels 1..6, "?" otherwise.
std::string label_name(int label);
/// Label 1..6 of the axis nearest to direction `n` (largest n . axis; ties go to the lower label).
int nearest_label(const Eigen::Vector3d& n);
/// True when labels a and b (1..6) are the two directions of one axis.
inline bool are_opposite(int a, int b) { return a != b && (a - 1) / 2 == (b - 1) / 2; }

/// Per-triangle geometry of a surface.
struct TriangleGeometry {
  Eigen::MatrixXd normal;  ///< #F by 3 unit normals (right-hand rule)
  Eigen::VectorXd area;    ///< #F areas
  Eigen::MatrixXd centroid;  ///< #F by 3
};
TriangleGeometry triangle_geometry(const mesh::SurfaceMesh& surface);

/// Checks what segmentation, the patch check and the polycube boundary need: a closed, 2-manifold,
/// consistently oriented surface (polycube::check_closed_manifold) without zero-area triangles
/// (area below 1e-12 x the squared bounding-box diagonal). Throws GeometryError naming the first
/// offending edge or triangle (1-based, in file order).
void check_surface(const mesh::SurfaceMesh& surface);

}  // namespace hexdom::segmentation
