// The feature structure of a closed triangle surface that the overlay path's boundary must capture:
// smooth regions, the sharp curves between them and the corners where curves meet, with
// projections onto each.
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::overlay {

struct FeatureOptions {
  /// An edge between triangles of different patches (CAD faces) is sharp when their normals differ
  /// by more than angle_across degrees, and with patch_edges also, whatever the angle, when the two
  /// patches meet along no sharp edge at all: the mesh then follows the CAD edges between tangent
  /// faces (a fillet and its plane) and coplanar ones (a split face) too, so that no boundary face
  /// straddles them where the buffer captures the curve (FreeCAD's face loads leave out a mesh face
  /// not wholly on the CAD face). Two patches whose edge is sharp in places and turns tangent on its
  /// way (crossing cylinders) keep its smooth stretch joined. Off: tangent and coplanar CAD faces
  /// are joined into one region. overlay_mesh meshes a grid without these curves too where cells
  /// stay inverted with a node held on one of them, and keeps the better mesh.
  bool patch_edges = true;
  double angle_across = 30;
  /// An edge inside one patch is sharp above this angle (triangle input without CAD faces).
  double angle_within = 50;
  /// When given (one per triangle, 0-based, consecutive), these regions instead of the ones the
  /// angles give; every edge between two of them is then a curve's. The overlay path uses it to
  /// keep a surface's features when it meshes the surface scaled per axis.
  std::vector<int> regions;
};

/// Regions, curves and corners of a surface. A region is a set of triangles joined across edges
/// that are not sharp; a curve is the set of sharp edges between one pair of regions; a corner is
/// a vertex on three or more regions, or where sharp edges end or branch.
class SurfaceFeatures {
 public:
  SurfaceFeatures(const mesh::SurfaceMesh& surface, const FeatureOptions& options = {});

  int regions() const { return regions_; }
  /// Region of each triangle (0-based).
  const std::vector<int>& region() const { return region_; }
  /// Corner vertices and the regions around each (sorted).
  const std::vector<int>& corners() const { return corners_; }
  const std::vector<std::vector<int>>& corner_regions() const { return corner_regions_; }
  /// Position of corner c (an index into corners()).
  Eigen::Vector3d corner_position(int c) const { return corner_position_[c]; }
  /// Whether regions a and b share a curve.
  bool has_curve(int a, int b) const;

  /// Closest point on the whole surface; `region` receives the region there and `normal` the unit
  /// outward normal of the triangle it lies on, when given.
  Eigen::Vector3d project(const Eigen::Vector3d& p, int* region = nullptr, Eigen::Vector3d* normal = nullptr) const;
  /// The tree over the whole surface's triangles (its closest points, rays, triangle normals).
  const mesh::TriangleProjector& triangles() const { return all_; }
  /// Closest point on region r. `hint`, when given, is read as a first bound and receives the
  /// triangle found (mesh::TriangleProjector::project: the same answer with or without it).
  Eigen::Vector3d project_region(int r, const Eigen::Vector3d& p, int* hint = nullptr) const;
  /// Closest point on the curve between regions a and b (has_curve(a, b) must hold); `hint` as
  /// for project_region.
  Eigen::Vector3d project_curve(int a, int b, const Eigen::Vector3d& p, int* hint = nullptr) const;

 private:
  int regions_ = 0;
  std::vector<int> region_, corners_;
  std::vector<Eigen::Vector3d> normal_;  // per triangle
  std::vector<std::vector<int>> corner_regions_;
  std::vector<Eigen::Vector3d> corner_position_;
  mesh::TriangleProjector all_;
  std::vector<std::unique_ptr<mesh::TriangleProjector>> by_region_;
  std::map<std::pair<int, int>, std::unique_ptr<mesh::TriangleProjector>> curves_;
};

}  // namespace hexdom::overlay
