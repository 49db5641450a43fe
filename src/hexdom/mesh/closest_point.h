// Closest points on a triangle surface (an AABB tree), for keeping nodes on the input surface.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "hexdom/mesh/cell_faces.h"

namespace hexdom::mesh {

/// Closest point to `p` on triangle (a, b, c).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Closest point to `p` on segment (a, b).
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& b);

class TriangleProjector {
 public:
  TriangleProjector() = default;
  /// V: #V by 3, F: #F by 3.
  TriangleProjector(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
  bool empty() const { return slot_.empty(); }
  /// Closest point on the surface; `triangle` receives its triangle when given. `hint`, any
  /// triangle (-1: none; e.g. the one an earlier query near p returned), bounds the search from the
  /// start; the answer is the same point and triangle, bit for bit, with or without it (the bound
  /// is just above the hint's distance, so the triangle found first among equally near ones is the
  /// same), only found sooner.
  Eigen::Vector3d project(const Eigen::Vector3d& p, int* triangle = nullptr, int hint = -1) const;
  /// The distance along the ray from `origin` in `direction` (any length) to the first triangle it
  /// meets beyond `from` and up to `up_to`, triangle `skip` left out (the ray's own, or -1);
  /// +infinity when it meets none. `triangle` receives the triangle met (-1 for none).
  double ray_distance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double from, double up_to,
                      int skip = -1, int* triangle = nullptr) const;
  /// Unit normal of triangle t (right hand over its corners).
  Eigen::Vector3d normal(int t) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1, right = -1;  // children, or -1
    int begin = 0, end = 0;     // leaf range in order_
  };
  int build(int begin, int end);
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<Node> nodes_;
  /// The corners of triangle order_[i] at corners_[3 i .. 3 i + 2] (by triangle while build()
  /// runs): a leaf's triangles side by side in memory, which is most of a query's time. The
  /// projector keeps no other copy of the surface.
  std::vector<Eigen::Vector3d> corners_;
  std::vector<int> slot_;  ///< per triangle: its place i in order_
};

/// A projector onto the segments (a, b) of points of V (rows), each held as the degenerate triangle
/// (a, b, b): the closest point on a set of curves.
TriangleProjector segment_projector(const Eigen::MatrixXd& V, const std::vector<std::array<int, 2>>& segments);

/// For each face of `faces` (corners in rows of V), the triangle of `projector`'s surface nearest to
/// its centre (the mean of its corners), -1 for an empty surface. With a tessellation whose patch
/// ids are CAD faces, patch(triangle) is the CAD face a boundary face of a mesh made from it lies on.
std::vector<int> nearest_triangles(const TriangleProjector& projector, const Eigen::MatrixXd& V,
                                   const std::vector<BoundaryFace>& faces);

}  // namespace hexdom::mesh
