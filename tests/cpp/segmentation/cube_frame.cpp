// cube_frame: the frame a part's faces fit, found back after the part is turned.
#include "hexdom/segmentation/cube_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "hexdom/segmentation/segment_cvt.h"
#include "seg_test_util.h"

namespace hexdom::segmentation {
namespace {

// An L of three voxels (no symmetry but the identity maps it onto itself by a turn), 3 x 2 x 1.
mesh::SurfaceMesh l_shape() { return test::voxel_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}, 2); }

Eigen::Matrix3d turn(const Eigen::Vector3d& axis, double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

// Angle in degrees between two frames up to the 24 turns of a cube (the labels are the same for
// frames a cube's symmetry apart only after renaming, so this is the angle that matters here).
double frame_angle(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  const Eigen::Matrix3d D = A * B.transpose();
  double best = 180;
  for (int p = 0; p < 6; ++p)
    for (int s = 0; s < 8; ++s) {
      static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
      Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
      for (int r = 0; r < 3; ++r) S(r, perm[p][r]) = (s >> r) & 1 ? -1.0 : 1.0;
      if (S.determinant() < 0) continue;
      const double c = std::clamp(((S * D).trace() - 1.0) / 2.0, -1.0, 1.0);
      best = std::min(best, std::acos(c) * 180.0 / M_PI);
    }
  return best;
}

TEST(CubeFrame, APartSquareToTheAxesIsLeftAsItIs) {
  const CubeFrame f = cube_frame(l_shape());
  EXPECT_FALSE(f.turned());
  EXPECT_TRUE(f.rotation.isIdentity(0));
  EXPECT_NEAR(f.fit_identity, 1.0, 1e-12);  // every normal along an axis
}

TEST(CubeFrame, ATurnedPartIsTurnedBackIntoItsFrame) {
  const mesh::SurfaceMesh part = l_shape();
  for (const auto& [axis, degrees] : std::vector<std::pair<Eigen::Vector3d, double>>{
           {Eigen::Vector3d::UnitZ(), 45.0}, {Eigen::Vector3d(1, 2, 3), 30.0}, {Eigen::Vector3d(-2, 1, 0.5), 71.0}}) {
    const Eigen::Matrix3d R = turn(axis, degrees);
    const CubeFrame f = cube_frame(rotated(part, R));
    ASSERT_TRUE(f.turned()) << degrees;
    EXPECT_NEAR(f.fit, 1.0, 1e-9) << degrees;
    EXPECT_LT(f.fit_identity, 0.9) << degrees;
    // The frame undoes the turn, up to a cube's symmetry.
    EXPECT_LT(frame_angle(f.rotation * R, Eigen::Matrix3d::Identity()), 1e-4) << degrees;
    EXPECT_NEAR((f.rotation.transpose() * f.rotation - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_GT(f.rotation.determinant(), 0);
    // Of the equivalent frames, the one nearest the model's axes: never more than a cube's
    // largest smallest turn (about 62.8 degrees).
    EXPECT_LE(f.angle_degrees, 62.81) << degrees;
  }
}

// The kept results: the same surface again gives the same frame; a surface turned another way,
// or the same one with other options, is not given the kept frame.
TEST(CubeFrame, TheSameSurfaceAgainGetsTheSameFrameAndAnotherItsOwn) {
  const mesh::SurfaceMesh a = rotated(l_shape(), turn(Eigen::Vector3d(1, 2, 3), 30.0));
  const CubeFrame f1 = cube_frame(a), f2 = cube_frame(a);
  ASSERT_TRUE(f1.turned());
  EXPECT_TRUE(f2.rotation == f1.rotation);
  EXPECT_EQ(f2.fit, f1.fit);
  EXPECT_EQ(f2.angle_degrees, f1.angle_degrees);
  const mesh::SurfaceMesh b = rotated(l_shape(), turn(Eigen::Vector3d(1, 2, 3), 20.0));
  const CubeFrame g = cube_frame(b);
  EXPECT_LT(frame_angle(g.rotation * turn(Eigen::Vector3d(1, 2, 3), 20.0), Eigen::Matrix3d::Identity()), 1e-4);
  EXPECT_GT(frame_angle(g.rotation, f1.rotation), 5.0);
  CubeFrameOptions strict;
  strict.min_gain = 0.9;  // no turn gains that much over these axes
  EXPECT_FALSE(cube_frame(a, strict).turned());
}

TEST(CubeFrame, ASmallTiltIsNotWorthATurn) {
  // A part 2 degrees off: the axes fit it to within min_gain, so the model's axes are kept.
  const CubeFrame f = cube_frame(rotated(l_shape(), turn(Eigen::Vector3d::UnitZ(), 2.0)));
  EXPECT_FALSE(f.turned());
  const CubeFrame strict = cube_frame(rotated(l_shape(), turn(Eigen::Vector3d::UnitZ(), 2.0)), CubeFrameOptions{0.0});
  EXPECT_TRUE(strict.turned());
  EXPECT_NEAR(strict.angle_degrees, 2.0, 1e-4);
}

TEST(CubeFrame, SegmentingInTheFrameGivesTheLabelsOfThePartSquareToTheAxes) {
  const mesh::SurfaceMesh part = l_shape();
  const Eigen::Matrix3d R = turn(Eigen::Vector3d(1, 2, 3), 30.0);
  const mesh::SurfaceMesh turned = rotated(part, R);
  CvtOptions in_frame;
  in_frame.frame = cube_frame(turned).rotation;
  const Eigen::VectorXi labels = segment_cvt(turned, in_frame).label;
  // The frame may differ from R^T by a cube's symmetry, which renames the labels consistently:
  // every triangle of one face of the part carries one label, and faces with opposite normals in
  // the part carry opposite labels.
  const Eigen::VectorXi square = segment_cvt(part).label;
  int mapping[7] = {0, 0, 0, 0, 0, 0, 0};
  for (int f = 0; f < part.F.rows(); ++f) {
    int& m = mapping[square(f)];
    if (m == 0) m = labels(f);
    EXPECT_EQ(m, labels(f)) << "triangle " << f;
  }
  for (int l = 1; l <= 6; l += 2) EXPECT_EQ((mapping[l] - 1) / 2, (mapping[l + 1] - 1) / 2);
}

// A hollow frustum square to the axes (outer radius 27 at the base to 17 at the top, height 17,
// wall 5, as the corpus's cone_005): its conical faces alone fit a frame tilted about 55 degrees
// better than the model's axes, which would put its flat ends at an angle; the planar faces keep
// the model's axes.
mesh::SurfaceMesh hollow_frustum() {
  const int n = 96;
  const double H = 17, R[2][2] = {{27, 17}, {22, 12}};  // [outer, inner][base, top]
  mesh::SurfaceMesh s;
  s.V.resize(4 * n, 3);
  for (int w = 0; w < 2; ++w)
    for (int z = 0; z < 2; ++z)
      for (int k = 0; k < n; ++k) {
        const double a = 2 * M_PI * k / n;
        s.V.row((2 * w + z) * n + k) << R[w][z] * std::cos(a), R[w][z] * std::sin(a), z * H;
      }
  std::vector<Eigen::Vector3i> F;
  auto ring = [&](int w, int z, int k) { return (2 * w + z) * n + (k % n); };
  for (int k = 0; k < n; ++k) {
    // outer side (normals out), inner side (normals in), base ring (-z), top ring (+z)
    F.emplace_back(ring(0, 0, k), ring(0, 0, k + 1), ring(0, 1, k + 1));
    F.emplace_back(ring(0, 0, k), ring(0, 1, k + 1), ring(0, 1, k));
    F.emplace_back(ring(1, 0, k), ring(1, 1, k + 1), ring(1, 0, k + 1));
    F.emplace_back(ring(1, 0, k), ring(1, 1, k), ring(1, 1, k + 1));
    F.emplace_back(ring(0, 0, k), ring(1, 0, k + 1), ring(0, 0, k + 1));
    F.emplace_back(ring(0, 0, k), ring(1, 0, k), ring(1, 0, k + 1));
    F.emplace_back(ring(0, 1, k), ring(0, 1, k + 1), ring(1, 1, k + 1));
    F.emplace_back(ring(0, 1, k), ring(1, 1, k + 1), ring(1, 1, k));
  }
  s.F.resize(static_cast<int>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(static_cast<int>(i)) = F[i].transpose();
  s.patch = Eigen::VectorXi::Zero(s.F.rows());
  return s;
}

TEST(CubeFrame, ARevolvedPartSquareToTheAxesKeepsThemForItsFlatEnds) {
  const mesh::SurfaceMesh part = hollow_frustum();
  EXPECT_GT(mesh::enclosed_volume(part.V, part.F), 0);
  CubeFrameOptions by_area;
  by_area.planar_weight = 1;  // planar faces by their area alone: the conical faces turn it
  EXPECT_TRUE(cube_frame(part, by_area).turned());
  const CubeFrame f = cube_frame(part);
  EXPECT_FALSE(f.turned());
  // The same part turned is still turned back into its frame (its planar faces fit it better).
  const Eigen::Matrix3d T = turn(Eigen::Vector3d(1, 2, 0.5), 35.0);
  const CubeFrame g = cube_frame(rotated(part, T));
  ASSERT_TRUE(g.turned());
  const Eigen::Vector3d axis = g.rotation * T * Eigen::Vector3d::UnitZ();  // the part's axis in the frame
  EXPECT_GT(axis.cwiseAbs().maxCoeff(), 1 - 1e-6) << axis.transpose();
}

TEST(CubeFrame, AnEmptySurfaceHasTheModelsAxes) {
  const CubeFrame f = cube_frame(mesh::SurfaceMesh{});
  EXPECT_FALSE(f.turned());
  EXPECT_EQ(f.fit, 0.0);
}

}  // namespace
}  // namespace hexdom::segmentation
