// Checks that a triangle surface bounds a solid, before any meshing stage: closed and 2-manifold,
// consistently oriented, every shell facing out of the solid (an inside-out export is turned
// around, with a warning), no triangle crossing another. The errors name what the user must fix
// (an edge, two triangles and a point) in 1-based numbers, as the file lists them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

/// Throws GeometryError unless every edge of `surface` is shared by exactly two triangles that
/// use it in opposite directions, and no triangle repeats a vertex or refers to a missing one; the
/// message names the first offending edge or triangle (1-based).
void check_closed_manifold(const SurfaceMesh& surface);

/// Two triangles (0-based) that cross each other, and a point where they do. `depth`: how far the
/// crossing edge reaches past the other's plane on its shorter side, over its length; `deep` when
/// that is a tenth or more (bodies overlapping), not for a local fold. Two triangles lying on each
/// other (coplanar, overlapping over an area) are `coplanar`: facing the same way, bodies overlap
/// or one is written twice (deep); facing opposite ways, two solids touch (depth 0, not deep).
struct Crossing {
  enum Coplanar { kNone, kSameWay, kOpposite };
  int a = -1, b = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double depth = 0;
  bool deep = false;
  Coplanar coplanar = kNone;
};

/// The first pair of triangles of (V, F) sharing no vertex where an edge of one crosses the plane of
/// the other (its ends on either side, farther than 1e-6 of the bounding-box diagonal) at a point
/// of that triangle, edges included, or where the two lie on each other facing the same way (every
/// corner within that distance of the other's plane, an overlap of at least 1e-3 of the smaller's
/// area); found over a bounding-box tree: n log n for a surface without crossings. None when the
/// surface does not cross itself. Touching at an edge or a point and neighbouring triangles are not
/// counted. Returns the first deep crossing found, else the first pair lying on each other facing
/// the same way (as the triangles are written), else the deepest shallow crossing; `shallow_pairs`
/// receives how many shallow crossings there are (all of them when none is deep), `coplanar` every
/// pair lying on each other (Crossing::coplanar: facing the same way or opposite ways). (V, F) must
/// pass check_closed_manifold.
std::optional<Crossing> find_self_intersection(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                               int* shallow_pairs = nullptr, std::vector<Crossing>* coplanar = nullptr);

struct SurfaceCheck {
  int shells = 0;          ///< closed shells (triangles connected through edges)
  int cavities = 0;        ///< of them, inside an odd number of others: a solid's cavities
  int flipped_shells = 0;  ///< shells turned around (inside-out exports)
  /// Solids: each shell inside an even number of others (none, or a solid inside another's cavity)
  /// bounds one, with the cavities directly inside it; numbered in the order of their shells' first
  /// triangles.
  int solids = 0;
  std::vector<int> solid;  ///< #F: the solid (0-based) each triangle bounds
  /// Pairs of solids (1-based, first < second) whose surfaces lie on each other facing opposite
  /// ways over some area: solids that touch (their meshes, made one by one, do not conform there).
  std::vector<std::array<int, 2>> touching;
  std::vector<std::string> warnings;  ///< one line per shell turned around, one for slight folds
};

struct SurfaceCheckOptions {
  bool self_intersection = true;  ///< look for triangles crossing each other
  /// Accept several solids (separate shells, or a solid inside another's cavity); otherwise
  /// they are refused.
  bool several_solids = false;
};

/// Checks `surface` (check_closed_manifold, then per shell, then find_self_intersection) and turns
/// around every shell that faces the wrong way: an outer shell (inside no other) must enclose a
/// positive volume, a cavity (a shell inside an odd number of others) a negative one. Throws
/// GeometryError naming the cause: an open or non-manifold edge, an edge whose two triangles
/// disagree on orientation, two triangles crossing deeply (Crossing::deep: overlapping bodies) or
/// lying on each other facing the same way, with a point; one solid's triangles lying on each other
/// facing opposite ways (a wall of no thickness), each judged with every shell facing as it will
/// once turned around; and unless options.several_solids shells that are
/// separate solids ("2 separate closed shells (solids)...") or nested more than one deep. A surface
/// that only folds over itself slightly is taken with a warning, and so are solids that touch
/// (SurfaceCheck::touching). `what` prefixes the messages (a file name, "the tessellation").
SurfaceCheck check_solid_surface(SurfaceMesh& surface, const std::string& what = "the surface",
                                 const SurfaceCheckOptions& options = {});

/// The surface of each solid check_solid_surface found in `surface` (its outer shell and its
/// cavities, vertices renumbered from 0 in the order the triangles use them, patch ids kept);
/// `surface` itself when there is one solid.
std::vector<SurfaceMesh> split_solids(const SurfaceMesh& surface, const SurfaceCheck& check);

}  // namespace hexdom::mesh
