// The polycube conditions on a segmented surface (paper, Sec. 3.1): 1) two patches with opposite
// orientations do not share a boundary; 2) every corner is shared by at least three patches;
// 3) a quadrilateral patch has four boundary curves, a triangular one (a face of a prism or tet
// block) three; and every patch is a disk with one boundary loop.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::segmentation {

struct CheckOptions {
  /// Degrees. A patch's orientation is the axis nearest to its area-weighted normal; two touching
  /// patches have opposite orientations when those axes are opposite and their normals are more
  /// than this angle apart. The paper's patches of prism and tet faces lie between two axes, and
  /// their neighbours may have opposite nearest axes at less than 135 degrees.
  double opposite_angle = 135.0;
  /// Degrees. A vertex whose angle defect (360 minus the sum of its triangle angles) exceeds this
  /// in magnitude is a corner of the shape (a cube corner has 90, a re-entrant corner -90) and must
  /// be shared by three patches. The paper's models reach 59 at smooth vertices.
  double corner_defect = 70.0;
  /// Degrees; 0 (default) skips this test. A boundary curve between two patches that turns by more
  /// than this at one of its vertices has a corner there that only two patches share. Meant for
  /// smooth models.
  double corner_angle = 0.0;
  /// The turn at a vertex is measured between chords to the points this many mean edge lengths
  /// before and after it along the curve (at the ends, as far as the curve goes).
  double turn_window = 3.0;
  /// Part ids of patches meant to be triangular (3 curves). Empty: a patch with 3 curves is
  /// triangular, one with any other number is taken as a quadrilateral.
  std::vector<int> triangular_ids;
};

enum class ViolationKind {
  OppositeOrientations,  ///< condition 1
  TwoPatchCorner,        ///< condition 2
  CurveCount,            ///< condition 3
  NotDisk,               ///< holes, several boundary loops, no boundary
};
/// "opposite_orientations", "two_patch_corner", "curve_count", "not_disk".
std::string kind_name(ViolationKind kind);

struct Violation {
  ViolationKind kind;
  std::vector<int> patches;  ///< 1-based patch numbers (order of first triangle; = shell ids of the polycube)
  int vertex = -1;           ///< 0-based surface vertex at the place (-1: none)
  Eigen::Vector3d location = Eigen::Vector3d::Zero();
  std::string message;       ///< names patches, part ids and the 1-based vertex
};

struct PatchReport {
  int patch = 0;        ///< 1-based patch number
  int id = 0;           ///< part id (label) of its triangles
  int orientation = 0;  ///< 1..6: +X, -X, +Y, -Y, +Z, -Z, nearest to the area-weighted normal
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double area = 0;
  int triangles = 0;
  bool triangular = false;    ///< meant to be triangular (3 curves) rather than quadrilateral (4)
  int curves = 0;             ///< boundary curves of its first loop (corners on it; 1 if it has none)
  int loops = 0;              ///< boundary loops
  int euler = 0;              ///< Euler characteristic (1 for a disk)
  std::vector<int> corners;   ///< 0-based corner vertices along its first loop, counter-clockwise
  std::vector<int> neighbours;  ///< 1-based patches across its curves, in loop order
};

struct PatchCheck {
  std::vector<PatchReport> patches;
  std::vector<int> corners;  ///< 0-based vertices where three or more patches meet
  int curves = 0;
  std::vector<Violation> violations;
  bool is_valid() const { return violations.empty(); }
};

/// Checks a segmented surface (patch id per triangle; a patch is a connected region of one id).
/// Finds every violation; throws only for a surface that is not closed, manifold and free of
/// zero-area triangles (GeometryError, see check_surface).
PatchCheck check_patches(const mesh::SurfaceMesh& surface, const CheckOptions& options = {});

/// "valid: N patches, C corners" or one line per violation, then a line per patch.
std::string to_text(const PatchCheck& check, bool list_patches = false);
/// {"valid", "patches": [...], "corners": [...], "violations": [{"kind", "patches", "vertex",
/// "location", "message"}]}; vertex indices 0-based, patch numbers 1-based.
std::string to_json(const PatchCheck& check);

}  // namespace hexdom::segmentation
