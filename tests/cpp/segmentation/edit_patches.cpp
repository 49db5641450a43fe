#include "hexdom/segmentation/edit_patches.h"

#include "hexdom/segmentation/check_patches.h"
#include "hexdom/segmentation/polycube_boundary.h"
#include "seg_test_util.h"

using namespace hexdom;

namespace {
int distinct(const Eigen::VectorXi& v) { return static_cast<int>(std::set<int>(v.data(), v.data() + v.size()).size()); }
}  // namespace

TEST(NumberPatches, OneIdPerRegionInOrderOfFirstTriangle) {
  auto s = test::l_shape();
  Eigen::VectorXi ids = segmentation::number_patches(s);
  // 8 faces of an L prism: top, bottom and 6 sides (the two +X and two +Y sides are separate).
  EXPECT_EQ(distinct(ids), 8);
  EXPECT_EQ(ids(0), 1);
  int next = 1;
  for (int f = 0; f < ids.size(); ++f) {
    ASSERT_LE(ids(f), next);
    if (ids(f) == next) ++next;
  }
  EXPECT_EQ(segmentation::check_patches({s.V, s.F, ids}).patches.size(), 8u);
}

TEST(ReassignTriangles, ToANewOrAnExistingPatch) {
  auto s = test::box_surface(1, 1, 1);
  Eigen::VectorXi a = segmentation::reassign_triangles(s, {0, 1}, 0);
  EXPECT_EQ(a(0), 7);
  EXPECT_EQ(a(1), 7);
  EXPECT_EQ((a.array() != s.patch.array()).count(), 2);
  Eigen::VectorXi b = segmentation::reassign_triangles(s, {0}, 3);
  EXPECT_EQ(b(0), 3);
  EXPECT_THROW(segmentation::reassign_triangles(s, {static_cast<int>(s.F.rows())}, 1), InputError);
  EXPECT_THROW(segmentation::reassign_triangles(s, {-1}, 1), InputError);
}

TEST(MergePatches, TouchingPatchesBecomeOne) {
  auto s = test::box_surface(1, 1, 1);
  Eigen::VectorXi m = segmentation::merge_patches(s, 1, 3);  // +X and +Y share an edge
  EXPECT_EQ(distinct(m), 5);
  for (int f = 0; f < m.size(); ++f) EXPECT_EQ(m(f), s.patch(f) == 3 ? 1 : s.patch(f));
  EXPECT_THROW(segmentation::merge_patches(s, 1, 2), GeometryError);  // +X and -X do not touch
  EXPECT_THROW(segmentation::merge_patches(s, 1, 9), InputError);
  EXPECT_THROW(segmentation::merge_patches(s, 1, 1), InputError);
}

TEST(SplitPatch, CutAcrossAFaceAndMergeBack) {
  auto s = test::box_surface(2, 1, 1, 2);
  const int a = test::vertex_at(s, 1, 0, 1), b = test::vertex_at(s, 1, 1, 1);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  Eigen::VectorXi cut = segmentation::split_patch(s, 5, {a, b});
  EXPECT_EQ(distinct(cut), 7);
  // Each half of the +Z face is a unit square of 8 triangles.
  EXPECT_EQ((cut.array() == 5).count(), 8);
  EXPECT_EQ((cut.array() == 7).count(), 8);
  // The cut makes T-junctions on the -Y and +Y faces: the check finds them (5 curves each).
  auto c = segmentation::check_patches({s.V, s.F, cut});
  EXPECT_EQ(c.violations.size(), 2u);
  for (const auto& v : c.violations) EXPECT_EQ(v.kind, segmentation::ViolationKind::CurveCount);
  // Merging the halves back restores the map.
  EXPECT_EQ(segmentation::merge_patches({s.V, s.F, cut}, 5, 7), s.patch);
}

TEST(SplitPatch, PathMustSeparateSomething) {
  auto s = test::box_surface(2, 1, 1, 2);
  const int a = test::vertex_at(s, 1, 0, 1), mid = test::vertex_at(s, 1, 0.5, 1), far = test::vertex_at(s, 0, 0, 0);
  EXPECT_THROW(segmentation::split_patch(s, 5, {a, mid}), GeometryError);  // ends inside
  EXPECT_THROW(segmentation::split_patch(s, 5, {a, far}), GeometryError);  // not on the patch
  EXPECT_THROW(segmentation::split_patch(s, 5, {a}), InputError);
  EXPECT_THROW(segmentation::split_patch(s, 42, {a, mid}), InputError);
  EXPECT_THROW(segmentation::split_patch(s, 5, {a, 100000}), InputError);
}

TEST(SplitPatch, ClosedPathCutsOutAnIsland) {
  auto s = test::box_surface(1, 1, 1, 4);
  const int p0 = test::vertex_at(s, 0.25, 0.25, 1), p1 = test::vertex_at(s, 0.75, 0.25, 1),
            p2 = test::vertex_at(s, 0.75, 0.75, 1), p3 = test::vertex_at(s, 0.25, 0.75, 1);
  Eigen::VectorXi cut = segmentation::split_patch(s, 5, {p0, p1, p2, p3, p0});
  EXPECT_EQ((cut.array() == 7).count(), 8);  // the 2 x 2 squares inside
}

TEST(EditPatches, LShapeBecomesAValidPolycubeAfterFourCuts) {
  // Labels by axis give L-shaped top and bottom patches (6 curves each). Cutting them into three
  // quads each and the -X and -Y sides in two makes the three-block polycube.
  auto s = test::l_shape();
  s.patch = segmentation::number_patches(s);
  auto c = segmentation::check_patches(s);
  EXPECT_FALSE(c.is_valid());
  auto id_at = [&](double x, double y, double z) {  // patch id of a triangle whose centroid is near (x, y, z)
    int best = -1;
    double d = 1e300;
    for (int f = 0; f < s.F.rows(); ++f) {
      Eigen::RowVector3d ctr = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3;
      const double e = (ctr - Eigen::RowVector3d(x, y, z)).norm();
      if (e < d) { d = e; best = f; }
    }
    return s.patch(best);
  };
  auto v = [&](double x, double y, double z) { return test::vertex_at(s, x, y, z); };
  s.patch = segmentation::split_patch(s, id_at(0.5, 0.5, 1), {v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)});
  s.patch = segmentation::split_patch(s, id_at(0.5, 0.5, 0), {v(1, 0, 0), v(1, 1, 0), v(0, 1, 0)});
  s.patch = segmentation::split_patch(s, id_at(1, 0, 0.5), {v(1, 0, 0), v(1, 0, 1)});
  s.patch = segmentation::split_patch(s, id_at(0, 1, 0.5), {v(0, 1, 0), v(0, 1, 1)});
  c = segmentation::check_patches(s);
  std::string msgs;
  for (const auto& x : c.violations) msgs += x.message + "\n";
  EXPECT_TRUE(c.is_valid()) << msgs;
  EXPECT_EQ(c.patches.size(), 14u);
  auto b = segmentation::polycube_boundary(s);
  EXPECT_EQ(b.faces.size(), 14u);
  EXPECT_EQ(b.corner_vertices.size(), 16u);  // 12 of the L + 4 where the cuts meet the boundary
}
