// Checks that a triangle surface bounds a solid, before any meshing stage: closed and 2-manifold,
// consistently oriented, every shell facing out of the solid (an inside-out export is turned
// around, with a warning), no triangle crossing another. The errors name what the user must fix
// (an edge, two triangles and a point) in 1-based numbers, as the file lists them.
#pragma once

#include <Eigen/Core>
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
/// that is a tenth or more (bodies overlapping), not for a local fold.
struct Crossing {
  int a = -1, b = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double depth = 0;
  bool deep = false;
};

/// The first pair of triangles of (V, F) sharing no vertex where an edge of one crosses the plane of
/// the other (its ends on either side, farther than 1e-6 of the bounding-box diagonal) at a point
/// of that triangle, edges included (found over a bounding-box tree: n log n for a surface without
/// crossings); none when the surface does not cross itself. Touching (an end within that distance
/// of the plane, coplanar overlaps) and neighbouring triangles are not counted. Returns the first
/// deep crossing found, else the deepest shallow one; `shallow_pairs` receives how many shallow
/// crossings there are (all of them when none is deep).
std::optional<Crossing> find_self_intersection(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                               int* shallow_pairs = nullptr);

struct SurfaceCheck {
  int shells = 0;          ///< closed shells (triangles connected through edges)
  int cavities = 0;        ///< of them, inside another: the solid's cavities
  int flipped_shells = 0;  ///< shells turned around (inside-out exports)
  std::vector<std::string> warnings;  ///< one line per shell turned around, one for slight folds
};

struct SurfaceCheckOptions {
  bool self_intersection = true;  ///< look for triangles crossing each other
};

/// Checks `surface` (check_closed_manifold, then per shell, then find_self_intersection) and turns
/// around every shell that faces the wrong way: an outer shell (inside no other) must enclose a
/// positive volume, a shell nested inside one other (a cavity) a negative one. Throws GeometryError
/// naming the cause: an open or non-manifold edge, an edge whose two triangles disagree on
/// orientation, shells that are separate solids ("2 separate closed shells (solids)..."), shells
/// nested more than one deep, two triangles crossing deeply (Crossing::deep: overlapping bodies)
/// with a point; a surface that only folds over itself slightly is taken with a warning. `what`
/// prefixes the messages (a file name, "the tessellation").
SurfaceCheck check_solid_surface(SurfaceMesh& surface, const std::string& what = "the surface",
                                 const SurfaceCheckOptions& options = {});

}  // namespace hexdom::mesh
