#include "hexdom/segmentation/segment_cvt.h"

#include <cmath>

#include "hexdom/io/mesh_io.h"
#include "hexdom/segmentation/axis_labels.h"
#include "hexdom/segmentation/segmentation_stats.h"
#include "hexdom/mesh/triangle_adjacency.h"
#include "seg_test_util.h"

using namespace hexdom;
using segmentation::CvtOptions;
using segmentation::FaceMode;

namespace {

/// A closed surface with smooth normals in every direction: a subdivided octahedron pushed onto
/// the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1.
mesh::SurfaceMesh ellipsoid(int n, double a, double b, double c) {
  // Octahedron faces subdivided n x n (barycentric grid), vertices shared through a map.
  std::map<std::array<long, 3>, int> index;
  std::vector<Eigen::Vector3d> V;
  std::vector<std::array<int, 3>> F;
  auto vertex = [&](Eigen::Vector3d p) {
    std::array<long, 3> key{std::lround(p(0) * 1e6), std::lround(p(1) * 1e6), std::lround(p(2) * 1e6)};
    auto [it, fresh] = index.try_emplace(key, static_cast<int>(V.size()));
    if (fresh) V.push_back(p);
    return it->second;
  };
  for (int sx : {1, -1})
    for (int sy : {1, -1})
      for (int sz : {1, -1}) {
        Eigen::Vector3d A(sx, 0, 0), B(0, sy, 0), C(0, 0, sz);
        if (sx * sy * sz < 0) std::swap(A, B);  // keep counter-clockwise from outside
        for (int i = 0; i < n; ++i)
          for (int j = 0; j + i < n; ++j) {
            auto P = [&](int u, int v) { return vertex((A * (n - u - v) + B * u + C * v) / double(n)); };
            F.push_back({P(i, j), P(i + 1, j), P(i, j + 1)});
            if (i + j + 1 < n) F.push_back({P(i + 1, j), P(i + 1, j + 1), P(i, j + 1)});
          }
      }
  mesh::SurfaceMesh s;
  s.V.resize(static_cast<int>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) {
    Eigen::Vector3d p = V[i].normalized();
    s.V.row(static_cast<int>(i)) << a * p(0), b * p(1), c * p(2);
  }
  s.F.resize(static_cast<int>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(static_cast<int>(i)) << F[i][0], F[i][1], F[i][2];
  s.patch = Eigen::VectorXi::Ones(s.F.rows());
  return s;
}

double axis_area_fraction(const mesh::SurfaceMesh& s, const Eigen::VectorXi& label, double degrees) {
  auto g = segmentation::triangle_geometry(s);
  double in = 0, total = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    total += g.area(f);
    if (g.normal.row(f).dot(segmentation::label_axis(label(f))) >= std::cos(degrees * M_PI / 180) - 1e-12) in += g.area(f);
  }
  return in / total;
}

}  // namespace

TEST(SegmentCvt, BoxFacesGetTheirAxisLabels) {
  auto s = test::voxel_surface({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, 3);
  const Eigen::VectorXi expected = s.patch;
  s.patch.setOnes();  // no CAD faces
  auto seg = segmentation::segment_cvt(s);
  EXPECT_EQ(seg.label, expected);
  EXPECT_EQ(seg.classical, expected);
  EXPECT_FALSE(seg.respected_faces);
  for (int l = 1; l <= 6; ++l)
    EXPECT_NEAR(seg.generators.row(l - 1).dot(segmentation::label_axis(l)), 1.0, 1e-12);
}

TEST(SegmentCvt, ScaledBoxIsUnchanged) {
  for (double scale : {1e-6, 1e6}) {
    auto s = test::voxel_surface({{0, 0, 0}, {0, 1, 0}}, 2, Eigen::Vector3d::Constant(scale));
    const Eigen::VectorXi expected = s.patch;
    s.patch.setOnes();
    EXPECT_EQ(segmentation::segment_cvt(s).label, expected) << scale;
  }
}

TEST(SegmentCvt, EllipsoidLabelsFollowNormalsAndBoundariesGetShorter) {
  auto s = ellipsoid(24, 1.0, 1.6, 0.7);
  auto seg = segmentation::segment_cvt(s);
  EXPECT_GE(axis_area_fraction(s, seg.label, 55.0), 0.95);
  auto classical = segmentation::segmentation_stats(s, seg.classical);
  auto final = segmentation::segmentation_stats(s, seg.label);
  EXPECT_LE(final.boundary_length, classical.boundary_length);
  EXPECT_LE(final.teeth, classical.teeth);
  EXPECT_EQ(final.patches, 6);
  // Every label is used, and by one region only.
  for (int l = 0; l < 6; ++l) EXPECT_GT(final.label_area[l], 0) << l;
}

TEST(SegmentCvt, ClassicalOnlyWithZeroLambda) {
  auto s = ellipsoid(12, 1.0, 1.3, 0.8);
  CvtOptions opt;
  opt.edge_weight = 0;
  auto seg = segmentation::segment_cvt(s, opt);
  EXPECT_EQ(seg.label, seg.classical);
  EXPECT_EQ(seg.edge_sweeps, 0);
}

TEST(SegmentCvt, GeneratorsStayWithinMaxDrift) {
  auto s = ellipsoid(16, 1.0, 2.5, 0.5);
  for (double drift : {0.0, 5.0, 10.0}) {
    CvtOptions opt;
    opt.max_drift = drift;
    auto seg = segmentation::segment_cvt(s, opt);
    for (int l = 1; l <= 6; ++l) {
      const double angle = std::acos(std::min(1.0, seg.generators.row(l - 1).dot(segmentation::label_axis(l)))) * 180 / M_PI;
      EXPECT_LE(angle, drift + 1e-6) << l;
    }
  }
}

TEST(SegmentCvt, ManualLabelsAreKept) {
  auto s = test::box_surface(2, 2, 2, 2);
  s.patch.setOnes();
  CvtOptions opt;
  opt.manual = {{0, 6}, {1, 6}, {5, 3}};
  auto seg = segmentation::segment_cvt(s, opt);
  EXPECT_EQ(seg.label(0), 6);
  EXPECT_EQ(seg.label(1), 6);
  EXPECT_EQ(seg.label(5), 3);
  opt.manual = {{static_cast<int>(s.F.rows()), 1}};
  EXPECT_THROW(segmentation::segment_cvt(s, opt), InputError);
  opt.manual = {{0, 7}};
  EXPECT_THROW(segmentation::segment_cvt(s, opt), InputError);
}

namespace {
/// A prism (height 6) over a convex polygon whose sides are CAD faces 1..6: -Y side, a short join
/// (normal -51 degrees), a curved face with normals from -40 to +50 degrees around +X (94% of its
/// area nearest +X), a planar chamfer with normal at 52 degrees (nearest +Y), +Y side, -X side;
/// caps 7 (top) and 8 (bottom).
mesh::SurfaceMesh chamfered_prism() {
  const double deg = M_PI / 180;
  const Eigen::Vector2d a0(11, 0.8), c = a0 - 4 * Eigen::Vector2d(std::cos(-40 * deg), std::sin(-40 * deg));
  std::vector<Eigen::Vector2d> arc;
  for (int i = 0; i <= 18; ++i) {
    const double th = (-40 + 90.0 * i / 18) * deg;
    arc.push_back(c + 4 * Eigen::Vector2d(std::cos(th), std::sin(th)));
  }
  const Eigen::Vector2d p = arc.back(), q = p + 3 * Eigen::Vector2d(std::cos(142 * deg), std::sin(142 * deg));
  std::vector<std::vector<Eigen::Vector2d>> sides = {
      test::segment_points({0, 0}, {10, 0}, 10), test::segment_points({10, 0}, a0, 2), arc,
      test::segment_points(p, q, 3), test::segment_points(q, {0, q(1)}, 8), test::segment_points({0, q(1)}, {0, 0}, 8)};
  return test::extruded_polygon(sides, 6.0, 6);
}
}  // namespace

TEST(SegmentCvt, CadFacesKeepOneLabelAndBoundariesFollowCadEdges) {
  auto s = chamfered_prism();
  ASSERT_NO_THROW(segmentation::check_surface(s));
  auto seg = segmentation::segment_cvt(s);  // Auto: more than one part id
  EXPECT_TRUE(seg.respected_faces);
  EXPECT_EQ(seg.faces, 8);
  EXPECT_EQ(seg.planar_faces, 7);  // all but the curved face
  EXPECT_EQ(seg.uniform_faces, 1);  // the curved face
  // Every CAD face carries one label, so label boundaries lie on CAD edges.
  std::map<int, std::set<int>> labels_of;
  for (int f = 0; f < s.F.rows(); ++f) labels_of[s.patch(f)].insert(seg.label(f));
  for (const auto& [face, labels] : labels_of) EXPECT_EQ(labels.size(), 1u) << "CAD face " << face;
  // The curved face (3) is mostly +X, the chamfer (4) nearest +Y.
  for (int f = 0; f < s.F.rows(); ++f) {
    if (s.patch(f) == 3) {
      EXPECT_EQ(seg.label(f), 1);
    }
    if (s.patch(f) == 4) {
      EXPECT_EQ(seg.label(f), 3);
    }
  }
  // Without faces, the curved face's triangles beyond 45 degrees go to +Y.
  CvtOptions off;
  off.respect_faces = FaceMode::Off;
  auto free = segmentation::segment_cvt(s, off);
  EXPECT_FALSE(free.respected_faces);
  std::set<int> curved;
  for (int f = 0; f < s.F.rows(); ++f)
    if (s.patch(f) == 3) curved.insert(free.label(f));
  EXPECT_EQ(curved, (std::set<int>{1, 3}));
}

TEST(SegmentCvt, OneSurfaceIdMeansNoFaces) {
  auto s = chamfered_prism();
  s.patch.setConstant(7);
  auto seg = segmentation::segment_cvt(s);
  EXPECT_FALSE(seg.respected_faces);
  EXPECT_EQ(seg.planar_faces, 0);
}

TEST(SegmentCvt, OpenSurfaceIsAGeometryError) {
  auto s = test::box_surface(1, 1, 1);
  s.F.conservativeResize(s.F.rows() - 1, 3);
  s.patch.conservativeResize(s.F.rows());
  try {
    segmentation::segment_cvt(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("open surface"), std::string::npos) << e.what();
  }
}

TEST(SegmentCvt, NonManifoldEdgeIsAGeometryError) {
  auto s = test::box_surface(1, 1, 1);
  s.F.conservativeResize(s.F.rows() + 1, 3);
  s.F.row(s.F.rows() - 1) << s.F(0, 0), s.F(0, 2), s.F(0, 1);  // a third triangle on three edges
  s.patch.conservativeResize(s.F.rows());
  s.patch(s.F.rows() - 1) = 1;
  try {
    segmentation::segment_cvt(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold"), std::string::npos) << e.what();
  }
}

TEST(SegmentCvt, ZeroAreaTriangleIsAGeometryError) {
  auto s = test::box_surface(2, 1, 1, 2);
  // Move the third vertex of triangle 0 onto the middle of its first edge.
  const int a = s.F(0, 0), b = s.F(0, 1), c = s.F(0, 2);
  s.V.row(c) = 0.5 * (s.V.row(a) + s.V.row(b));
  try {
    segmentation::segment_cvt(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
}

TEST(SegmentCvt, EmptySurfaceIsAGeometryError) {
  mesh::SurfaceMesh s;
  s.V = Eigen::MatrixXd::Zero(3, 3);
  s.F.resize(0, 3);
  s.patch.resize(0);
  EXPECT_THROW(segmentation::segment_cvt(s), GeometryError);
}

// ---- the paper's raw surfaces ----

class SegmentPaperModel : public ::testing::TestWithParam<std::string> {};

TEST_P(SegmentPaperModel, LabelsFollowAxesAndZigZagsShrink) {
  const std::string path = test::raw_surface(GetParam());
  HEXDOM_REQUIRE_DATA(path);
  auto s = io::read_surface(path);
  auto seg = segmentation::segment_cvt(s);
  auto classical = segmentation::segmentation_stats(s, seg.classical);
  auto final = segmentation::segmentation_stats(s, seg.label);
  EXPECT_GE(final.axis_fraction, 0.95);
  EXPECT_NEAR(final.axis_fraction, axis_area_fraction(s, seg.label, 55.0), 1e-12);
  for (int l = 0; l < 6; ++l) {
    EXPECT_GT(final.label_area[l], 0) << l;
    EXPECT_GE(final.label_axis_fraction[l], 0.95) << segmentation::label_name(l + 1);
  }
  EXPECT_LE(final.teeth, classical.teeth);
  EXPECT_LE(final.boundary_length, classical.boundary_length * 1.001);
  EXPECT_LE(final.patches, classical.patches);
}

INSTANTIATE_TEST_SUITE_P(PaperModels, SegmentPaperModel, ::testing::ValuesIn(test::paper_models()));
