// Matching the faces of a polycube structure's blocks to the patches of its surface, by corners: a
// block face that is in one block only lies on the boundary and must be the face of exactly one
// patch (the patch whose corners are its vertices); every patch must be the face of exactly one
// block. The one matcher behind generate, the automatic polycube's collapses and Build Polycube.
#pragma once

#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::polycube {

/// One face of one block.
struct BlockFace {
  int block = -1;             ///< the block (0-based)
  int face = -1;              ///< its local face (mesh::cell_faces order); -1 when the caller does not need it
  std::vector<int> vertices;  ///< structure vertex ids in the block's order (any order matches)
};

enum class MatchProblemKind {
  PatchesShareCorners,  ///< two patches have the same corners: no block face can tell them apart
  FaceInManyBlocks,     ///< a face that is no patch is in three or more blocks
  FaceOnNoPatch,        ///< a face in one block only that is no patch: the structure is open there
  PatchOnNoFace,        ///< no block has a face on the patch's corners
  PatchOnManyFaces,     ///< two or more blocks have a face on the patch's corners: it is inside the structure
};

struct MatchProblem {
  MatchProblemKind kind = MatchProblemKind::FaceOnNoPatch;
  /// Patches concerned (0-based): PatchesShareCorners the earlier and the later one; Patch* the patch;
  /// for a face problem, none.
  std::vector<int> patches;
  /// Every use of the face concerned (indices into the faces given, ascending); empty for
  /// PatchOnNoFace and PatchesShareCorners.
  std::vector<int> faces;
  std::vector<int> vertices;  ///< the face's vertices or the patch's corners, sorted
  std::string message;        ///< names the patches (1-based), blocks (1-based) and vertices (1-based)
};

struct FaceMatch {
  /// Per patch: the face given (index) that is its boundary face, -1 when it has none (every patch
  /// with a problem). A patch sharing its corners with an earlier patch is never matched.
  std::vector<int> face_of_patch;
  std::vector<int> patch_of_face;  ///< per face given: the patch it is the boundary face of, or -1
  /// Every problem, in this order: shared corners (patch order), then per distinct face (ascending
  /// sorted vertices) FaceInManyBlocks / FaceOnNoPatch, then per patch PatchOnNoFace / PatchOnManyFaces.
  /// Each distinct face and each patch has at most one problem.
  std::vector<MatchProblem> problems;
  bool ok() const { return problems.empty(); }
};

/// Every face of every block of `structure` (hex, prism and tet blocks), block by block in
/// mesh::cell_faces order, vertices outward. Throws GeometryError naming a block that is no volume cell.
std::vector<BlockFace> block_faces(const mesh::Mesh& structure);

/// Matches `faces` (every face of every block) to patches given by their corners (structure vertex
/// ids, any order; patch p = patch_corners[p]). Faces match when their sorted vertices are equal.
/// Never throws; an empty patch list makes every face in one block a FaceOnNoPatch.
FaceMatch match_faces_to_patches(const std::vector<BlockFace>& faces, const std::vector<std::vector<int>>& patch_corners);

/// "patches_share_corners", "face_in_many_blocks", "face_on_no_patch", "patch_on_no_face",
/// "patch_on_many_faces".
std::string kind_name(MatchProblemKind kind);

}  // namespace hexdom::polycube
