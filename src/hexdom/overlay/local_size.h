// Sizes asked for the cells on chosen patches of the surface (CAD faces), as FreeCAD's mesh
// regions and Gmsh's size fields on faces ask: the overlay path's octree (octree.h) refines its
// grid by thirds down to them near those faces, its templates grading the cells back to the grid's.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::overlay {

/// A cell size asked for on the triangles of one patch (a CAD face: FreeCAD's Face{patch}), or,
/// when `polyline` has rows, along that polyline (a CAD edge's points, in the surface's
/// coordinates; `patch` is then not used).
struct LocalSize {
  int patch = 0;
  double size = 0;
  Eigen::MatrixXd polyline;  ///< #points by 3, or empty
};

/// The growth rate the band of each level is drawn for by default: 3^(1/4), about 1.32 (cells grow
/// by a factor 3 from one level to the next over about four cells).
inline const double kGrowthRate = std::pow(3.0, 0.25);

/// InputError unless 1 < growth <= 3 (LocalSizeField's growth rate).
void check_growth_rate(double growth);

/// Throws InputError naming the first local size whose size is not positive and finite, whose
/// patch has no triangle in `surface` (`what` names the surface in the message) or whose polyline
/// has fewer than 2 points.
void check_local_sizes(const std::vector<LocalSize>& sizes, const mesh::SurfaceMesh& surface,
                       const std::string& what = "the surface");

/// How the grid's spacing is set so that the octree reaches the local sizes.
struct LocalLevels {
  double factor = 1;  ///< the grid's spacing times this
  int levels = 0;     ///< octree levels the smallest size needs (0: none; the spacing alone meets it)
};

/// For a grid of longest spacing `spacing` and the smallest local size s (not below min_size when
/// that is given): the octree level L and the spacing h (spacing * factor) whose cells of level L
/// (h / 3^L) are within a factor 1.2 of s: h is `spacing` when that already gives such a level,
/// otherwise the spacing nearest it (by ratio) that does, and is at most 1.2 times it (the grid is
/// made finer rather than coarser: within a factor 2.1 of `spacing`, at most 1.2 coarser).
/// L = 0 with a factor below 1: the whole grid is made that much finer. L is at most max_levels.
/// Other sizes get the level whose cells are nearest them (LocalSizeField). {1, 0} when no size
/// is below spacing / 1.2 (sizes above the grid's cells do not coarsen it).
LocalLevels local_levels(double spacing, const std::vector<LocalSize>& sizes, double min_size, int max_levels = 4);

/// Which octree cells the local sizes split: those near a triangle of a patch (or a polyline)
/// asking for a size below the cell's longest side / sqrt(3) (so that the cells there end within
/// a factor sqrt(3) of the size; within 1.2 of the smallest with local_levels' spacing). Near: the
/// distance from the cell's centre is at most its half diagonal plus a band of (ln 3 / ln growth -
/// 1) of its children's sides, so that across a level's band, from the face outwards, the cell size grows by
/// about `growth` per cell on average before the next level (3 times larger) begins: 3 children at
/// the default kGrowthRate, one at growth sqrt(3), none from growth 3 (only the cells touching
/// the face). InputError for a growth not in (1, 3].
/// `surface` is the one the grid is laid over (a stretched copy for a stretched grid: positions
/// are measured there, sizes in real lengths, the caller giving the cell's real longest side).
class LocalSizeField {
 public:
  LocalSizeField() = default;
  /// `transform` maps the polylines' points into the surface's space (row-wise: p * transform);
  /// the surface itself is already there.
  LocalSizeField(const mesh::SurfaceMesh& surface, const std::vector<LocalSize>& sizes, double growth = kGrowthRate,
                 const Eigen::Matrix3d& transform = Eigen::Matrix3d::Identity());
  /// No size applies: none was given, or none of their patches is on the surface.
  bool empty() const { return by_size_.empty(); }
  /// The smallest size that applies (0 when empty).
  double smallest() const { return by_size_.empty() ? 0.0 : by_size_.front().size; }
  /// Split the cell [lo, lo + size] (grid space), whose longest real side is `real_side`?
  bool split(const Eigen::Vector3d& lo, const Eigen::Vector3d& size, double real_side) const;

 private:
  struct Sized {
    double size = 0;
    mesh::TriangleProjector triangles;                              // the patches' asking for it
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;  // the polylines'
  };
  std::vector<Sized> by_size_;  // one per distinct size, smallest first
  double band_ = 3;  // children's sides beyond the half diagonal
};

}  // namespace hexdom::overlay
