#include "hexdom/segmentation/check_patches.h"

#include "hexdom/io/mesh_io.h"
#include "hexdom/segmentation/edit_patches.h"
#include "seg_test_util.h"

using namespace hexdom;
using segmentation::ViolationKind;

namespace {

int count(const segmentation::PatchCheck& c, ViolationKind kind) {
  int n = 0;
  for (const auto& v : c.violations) n += v.kind == kind;
  return n;
}

std::string all_messages(const segmentation::PatchCheck& c) {
  std::string s;
  for (const auto& v : c.violations) s += v.message + "\n";
  return s;
}

/// A thin wedge (apex angle 15 degrees) extruded along Z: its two long sides (nearest +Y and -Y,
/// 165 degrees apart) meet at the apex edge.
mesh::SurfaceMesh thin_wedge() {
  const double h = 10 * std::tan(7.5 * M_PI / 180);
  return test::extruded_polygon({test::segment_points({0, -h}, {10, 0}, 8), test::segment_points({10, 0}, {0, h}, 8),
                                 test::segment_points({0, h}, {0, -h}, 3)},
                                4.0, 4);
}

}  // namespace

TEST(CheckPatches, BoxIsValid) {
  auto c = segmentation::check_patches(test::box_surface(2, 1, 1));
  EXPECT_TRUE(c.is_valid()) << all_messages(c);
  EXPECT_EQ(c.patches.size(), 6u);
  EXPECT_EQ(c.corners.size(), 8u);
  EXPECT_EQ(c.curves, 12);
  for (const auto& p : c.patches) {
    EXPECT_EQ(p.curves, 4);
    EXPECT_EQ(p.loops, 1);
    EXPECT_EQ(p.euler, 1);
    EXPECT_FALSE(p.triangular);
    EXPECT_EQ(p.orientation, p.id);  // the box's ids are its axis labels
    EXPECT_EQ(p.neighbours.size(), 4u);
  }
  EXPECT_NE(segmentation::to_text(c).find("valid: 6 patches"), std::string::npos);
  EXPECT_NE(segmentation::to_json(c).find("\"valid\": true"), std::string::npos);
}

TEST(CheckPatches, OppositePatchesTouching) {
  auto s = thin_wedge();
  auto c = segmentation::check_patches(s);
  ASSERT_EQ(count(c, ViolationKind::OppositeOrientations), 1) << all_messages(c);
  const auto* v = &c.violations[0];
  for (const auto& x : c.violations)
    if (x.kind == ViolationKind::OppositeOrientations) v = &x;
  // Patches 1 (-Y side) and 2 (+Y side) in order of first triangle; the place is on the apex edge.
  EXPECT_EQ(v->patches, (std::vector<int>{1, 2}));
  EXPECT_NEAR(v->location(0), 10.0, 1e-12);
  EXPECT_NEAR(v->location(1), 0.0, 1e-12);
  EXPECT_NE(v->message.find("opposite orientations"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("(part 1, -Y)"), std::string::npos) << v->message;
  // A wider angle than the normals' 165 degrees accepts it.
  segmentation::CheckOptions opt;
  opt.opposite_angle = 170;
  EXPECT_EQ(count(segmentation::check_patches(s, opt), ViolationKind::OppositeOrientations), 0);
}

TEST(CheckPatches, FiveSidedPatchesAfterAReassignment) {
  // Give the corner square of the +Z face of a box to a new patch: +Z, +X and -Y get 5 curves.
  auto s = test::box_surface(2, 2, 1, 2);
  std::vector<int> corner_square;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (s.patch(f) != 5) continue;
    Eigen::RowVector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3;
    if (c(0) > 1.5 && c(1) < 0.5) corner_square.push_back(f);
  }
  ASSERT_EQ(corner_square.size(), 2u);
  s.patch = segmentation::reassign_triangles(s, corner_square, 0);
  auto c = segmentation::check_patches(s);
  EXPECT_FALSE(c.is_valid());
  std::set<int> five_sided;
  for (const auto& v : c.violations) {
    EXPECT_EQ(v.kind, ViolationKind::CurveCount) << v.message;
    if (v.kind == ViolationKind::CurveCount) {
      ASSERT_EQ(v.patches.size(), 1u);
      const auto& p = c.patches[v.patches[0] - 1];
      EXPECT_EQ(p.curves, 5);
      five_sided.insert(p.id);
      EXPECT_NE(v.message.find("5 boundary curves"), std::string::npos) << v.message;
    }
  }
  EXPECT_EQ(five_sided, (std::set<int>{1, 4, 5}));  // +X, -Y, +Z
  // The new patch itself has 3 corners: a valid triangular patch.
  EXPECT_EQ(c.patches.back().id, 7);
  EXPECT_EQ(c.patches.back().curves, 3);
  EXPECT_TRUE(c.patches.back().triangular);
  // Declared quadrilateral, it is a violation too.
  segmentation::CheckOptions opt;
  opt.triangular_ids = {99};
  EXPECT_EQ(count(segmentation::check_patches(s, opt), ViolationKind::CurveCount), 4);
}

TEST(CheckPatches, TwoPatchCornerWhereFacesAreMerged) {
  // +Y joins +X: the box corners on the old X/Y edge are sharp but only 2 patches meet there.
  auto s = test::box_surface(1, 1, 1, 2);
  for (int f = 0; f < s.F.rows(); ++f)
    if (s.patch(f) == 3) s.patch(f) = 1;
  auto c = segmentation::check_patches(s);
  std::set<int> at;
  for (const auto& v : c.violations)
    if (v.kind == ViolationKind::TwoPatchCorner) {
      at.insert(v.vertex);
      EXPECT_EQ(v.patches.size(), 2u);
      EXPECT_NE(v.message.find("angle defect 90"), std::string::npos) << v.message;
    }
  EXPECT_EQ(at, (std::set<int>{test::vertex_at(s, 1, 1, 0), test::vertex_at(s, 1, 1, 1)})) << all_messages(c);
}

TEST(CheckPatches, IslandIsAClosedCurveAndAHole) {
  auto s = test::box_surface(1, 1, 1, 4);
  std::vector<int> centre;
  for (int f = 0; f < s.F.rows(); ++f) {
    Eigen::RowVector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3;
    if (s.patch(f) == 5 && std::abs(c(0) - 0.5) < 0.25 && std::abs(c(1) - 0.5) < 0.25) centre.push_back(f);
  }
  s.patch = segmentation::reassign_triangles(s, centre, 0);
  auto c = segmentation::check_patches(s);
  EXPECT_EQ(count(c, ViolationKind::TwoPatchCorner), 1) << all_messages(c);
  EXPECT_EQ(count(c, ViolationKind::NotDisk), 1) << all_messages(c);
  EXPECT_EQ(count(c, ViolationKind::CurveCount), 1) << all_messages(c);
  for (const auto& v : c.violations) {
    if (v.kind == ViolationKind::NotDisk) {
      EXPECT_EQ(c.patches[v.patches[0] - 1].id, 5);
      EXPECT_EQ(c.patches[v.patches[0] - 1].loops, 2);
    }
    if (v.kind == ViolationKind::TwoPatchCorner) {
      EXPECT_NE(v.message.find("closed curve"), std::string::npos);
    }
  }
}

TEST(CheckPatches, WholeSurfaceAsOnePatch) {
  auto s = test::box_surface(1, 1, 1);
  s.patch.setOnes();
  auto c = segmentation::check_patches(s);
  ASSERT_FALSE(c.is_valid());
  EXPECT_EQ(count(c, ViolationKind::NotDisk), 1);
  EXPECT_EQ(count(c, ViolationKind::TwoPatchCorner), 8);  // the box corners
}

TEST(CheckPatches, TurningCurveOnRequest) {
  // Merged faces again, with a rounded view: the curve between the merged patch and +Z turns by
  // 90 degrees; reported when corner_angle is set.
  auto s = test::box_surface(1, 1, 1, 4);
  for (int f = 0; f < s.F.rows(); ++f)
    if (s.patch(f) == 3) s.patch(f) = 1;
  segmentation::CheckOptions opt;
  opt.corner_defect = 1000;  // only the turning test
  EXPECT_EQ(count(segmentation::check_patches(s, opt), ViolationKind::TwoPatchCorner), 0);
  opt.corner_angle = 60;
  opt.turn_window = 1.0;
  auto c = segmentation::check_patches(s, opt);
  EXPECT_EQ(count(c, ViolationKind::TwoPatchCorner), 2) << all_messages(c);
}

TEST(CheckPatches, OpenSurfaceIsAGeometryError) {
  auto s = test::box_surface(1, 1, 1);
  s.F.conservativeResize(s.F.rows() - 2, 3);
  s.patch.conservativeResize(s.F.rows());
  EXPECT_THROW(segmentation::check_patches(s), GeometryError);
}

TEST(CheckPatches, JsonListsViolations) {
  auto c = segmentation::check_patches(thin_wedge());
  const std::string j = segmentation::to_json(c);
  EXPECT_NE(j.find("\"valid\": false"), std::string::npos);
  EXPECT_NE(j.find("\"kind\": \"opposite_orientations\""), std::string::npos);
  EXPECT_NE(j.find("\"patches\": [1, 2]"), std::string::npos);
}

// ---- the paper's accepted patch files ----

class CheckPaperPatches : public ::testing::TestWithParam<std::string> {};

TEST_P(CheckPaperPatches, AcceptedFilesHaveNoViolation) {
  const std::string path = test::data_path("hexdom/" + GetParam());
  HEXDOM_REQUIRE_DATA(path);
  auto c = segmentation::check_patches(io::read_surface(path));
  EXPECT_TRUE(c.is_valid()) << all_messages(c);
  int quads = 0, tris = 0;
  for (const auto& p : c.patches) (p.triangular ? tris : quads)++;
  EXPECT_EQ(quads + tris, static_cast<int>(c.patches.size()));
}

INSTANTIATE_TEST_SUITE_P(
    PaperModels, CheckPaperPatches,
    ::testing::Values("rockerarm/rockerarm_indexPatch_hexdom.k", "mount1/mount1_patch_hexdom.k",
                      "hepta/hepta_patch_hexdom.k", "fertility/fertility_indexPatch_hexdom.k",
                      "ant/ant_indexPatch_hexdom.k", "mountwithhole/mountwithhole_patch_hexdom.k",
                      "mountwithhole/mountwithhole_indexpatch_corrected.k", "rod_demo/rod_indexPatch_read.k",
                      "joint/joint_initial_read.k"));
