#include "hexdom/polycube/match_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"

using namespace hexdom;

namespace {

// Two unit hexes side by side along x: vertices 0..11, block 0 on 0 1 2 3 / 4 5 6 7 ... sharing the
// face x = 1 (vertices 1 2 5 6 of block 0 = 0 3 4 7 of block 1).
const std::array<int, 8> kA = {0, 1, 2, 3, 4, 5, 6, 7};
const std::array<int, 8> kB = {1, 8, 9, 2, 5, 10, 11, 6};

void add_faces(std::vector<polycube::BlockFace>& out, int block, const std::array<int, 8>& nodes) {
  const auto [faces, n] = mesh::cell_faces(mesh::CellType::Hex);
  for (int f = 0; f < n; ++f) {
    polycube::BlockFace bf{block, f, {}};
    for (int i = 0; i < faces[f].n; ++i) bf.vertices.push_back(nodes[faces[f].v[i]]);
    out.push_back(bf);
  }
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

struct TwoHexes {
  std::vector<polycube::BlockFace> faces;
  std::vector<std::vector<int>> patches;  // the 10 boundary faces, in face order
  std::vector<int> shared;                // the face inside, sorted
  TwoHexes() {
    add_faces(faces, 0, kA);
    add_faces(faces, 1, kB);
    for (const auto& f : faces) {
      const auto vs = sorted(f.vertices);
      int uses = 0;
      for (const auto& g : faces) uses += sorted(g.vertices) == vs;
      if (uses == 1) patches.push_back(f.vertices);
      else shared = vs;
    }
  }
};

}  // namespace

TEST(MatchFaces, EveryBoundaryFaceIsOnePatch) {
  const TwoHexes t;
  ASSERT_EQ(t.patches.size(), 10u);
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  EXPECT_TRUE(m.ok());
  int matched = 0;
  for (size_t p = 0; p < t.patches.size(); ++p) {
    ASSERT_GE(m.face_of_patch[p], 0);
    EXPECT_EQ(sorted(t.faces[m.face_of_patch[p]].vertices), sorted(t.patches[p]));
    EXPECT_EQ(m.patch_of_face[m.face_of_patch[p]], static_cast<int>(p));
  }
  for (int p : m.patch_of_face) matched += p >= 0;
  EXPECT_EQ(matched, 10);  // the shared face's two uses match nothing
}

TEST(MatchFaces, FaceOnNoPatchNamesTheBlockFace) {
  TwoHexes t;
  const auto lost = sorted(t.patches[3]);
  t.patches.erase(t.patches.begin() + 3);
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  ASSERT_EQ(m.problems.size(), 1u);
  const auto& p = m.problems[0];
  EXPECT_EQ(p.kind, polycube::MatchProblemKind::FaceOnNoPatch);
  EXPECT_EQ(p.vertices, lost);
  ASSERT_EQ(p.faces.size(), 1u);
  EXPECT_EQ(sorted(t.faces[p.faces[0]].vertices), lost);
  EXPECT_NE(p.message.find("matches no patch"), std::string::npos) << p.message;
  EXPECT_NE(p.message.find("block " + std::to_string(t.faces[p.faces[0]].block + 1) + " face"), std::string::npos) << p.message;
}

TEST(MatchFaces, PatchOnNoFaceIsListedInPatchOrder) {
  TwoHexes t;
  t.patches.insert(t.patches.begin() + 2, {0, 1, 8, 9});  // no block has this face
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  ASSERT_EQ(m.problems.size(), 1u);
  EXPECT_EQ(m.problems[0].kind, polycube::MatchProblemKind::PatchOnNoFace);
  EXPECT_EQ(m.problems[0].patches, std::vector<int>{2});
  EXPECT_TRUE(m.problems[0].faces.empty());
  EXPECT_EQ(m.face_of_patch[2], -1);
  EXPECT_NE(m.problems[0].message.find("patch 3 "), std::string::npos) << m.problems[0].message;
}

TEST(MatchFaces, PatchInsideTheStructureIsOnManyFaces) {
  TwoHexes t;
  t.patches.push_back(t.shared);
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  ASSERT_EQ(m.problems.size(), 1u);
  const auto& p = m.problems[0];
  EXPECT_EQ(p.kind, polycube::MatchProblemKind::PatchOnManyFaces);
  EXPECT_EQ(p.patches, std::vector<int>{10});
  ASSERT_EQ(p.faces.size(), 2u);
  EXPECT_EQ(t.faces[p.faces[0]].block, 0);
  EXPECT_EQ(t.faces[p.faces[1]].block, 1);
  EXPECT_EQ(m.face_of_patch[10], -1);
}

TEST(MatchFaces, PatchesWithTheSameCornersAreOneProblem) {
  TwoHexes t;
  auto twin = t.patches[4];
  std::reverse(twin.begin(), twin.end());
  t.patches.push_back(twin);
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  ASSERT_EQ(m.problems.size(), 1u);
  EXPECT_EQ(m.problems[0].kind, polycube::MatchProblemKind::PatchesShareCorners);
  EXPECT_EQ(m.problems[0].patches, (std::vector<int>{4, 10}));
  EXPECT_GE(m.face_of_patch[4], 0);  // the earlier one keeps its face
  EXPECT_EQ(m.face_of_patch[10], -1);
}

TEST(MatchFaces, FaceInThreeBlocks) {
  TwoHexes t;
  add_faces(t.faces, 2, kB);  // block 1 twice: its faces are in two blocks, the shared one in three
  const auto m = polycube::match_faces_to_patches(t.faces, t.patches);
  int many = 0, twice = 0;
  for (const auto& p : m.problems) {
    if (p.kind == polycube::MatchProblemKind::FaceInManyBlocks) {
      ++many;
      EXPECT_EQ(p.vertices, t.shared);
      EXPECT_EQ(p.faces.size(), 3u);
      EXPECT_NE(p.message.find("in 3 blocks (1, 2, 3)"), std::string::npos) << p.message;
    }
    twice += p.kind == polycube::MatchProblemKind::PatchOnManyFaces;
  }
  EXPECT_EQ(many, 1);
  EXPECT_EQ(twice, 5);  // block 1's five faces on patches
  EXPECT_EQ(m.problems.size(), 6u);
}

TEST(MatchFaces, ProblemKindsHaveNames) {
  EXPECT_EQ(polycube::kind_name(polycube::MatchProblemKind::PatchesShareCorners), "patches_share_corners");
  EXPECT_EQ(polycube::kind_name(polycube::MatchProblemKind::FaceInManyBlocks), "face_in_many_blocks");
  EXPECT_EQ(polycube::kind_name(polycube::MatchProblemKind::FaceOnNoPatch), "face_on_no_patch");
  EXPECT_EQ(polycube::kind_name(polycube::MatchProblemKind::PatchOnNoFace), "patch_on_no_face");
  EXPECT_EQ(polycube::kind_name(polycube::MatchProblemKind::PatchOnManyFaces), "patch_on_many_faces");
}

TEST(MatchFaces, BlockFacesOfAStructureMatchItsPatches) {
  mesh::MeshBuilder mb;
  mb.add(mesh::CellType::Hex, kA.data(), 1);
  mb.add(mesh::CellType::Hex, kB.data(), 2);
  const mesh::Mesh T = mb.finish(Eigen::MatrixXd::Zero(12, 3));
  const auto faces = polycube::block_faces(T);
  ASSERT_EQ(faces.size(), 12u);
  EXPECT_EQ(faces[6].block, 1);
  EXPECT_EQ(faces[6].face, 0);
  const TwoHexes t;
  EXPECT_TRUE(polycube::match_faces_to_patches(faces, t.patches).ok());
  mesh::MeshBuilder quad;
  const int q[4] = {0, 1, 2, 3};
  quad.add(mesh::CellType::Quad, q, 1);
  EXPECT_THROW(polycube::block_faces(quad.finish(Eigen::MatrixXd::Zero(4, 3))), GeometryError);
}
