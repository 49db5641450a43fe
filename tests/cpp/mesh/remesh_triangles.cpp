#include "hexdom/mesh/remesh_triangles.h"

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>

#include "hexdom/mesh/closest_point.h"
#include "test_common.h"

using namespace hexdom;
using namespace hexdom::mesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

RemeshTrianglesOptions with_size(double size) {
  RemeshTrianglesOptions o;
  o.size = size;
  return o;
}

/// Box [0,a]x[0,b]x[0,c] as 12 triangles, face ids 1..6 (-x, +x, -y, +y, -z, +z), outward.
SurfaceMesh box(double a, double b, double c) {
  SurfaceMesh s;
  s.V.resize(8, 3);
  for (int i = 0; i < 8; ++i) s.V.row(i) << (i & 1 ? a : 0), (i & 2 ? b : 0), (i & 4 ? c : 0);
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  s.F.resize(12, 3);
  s.patch.resize(12);
  for (int q = 0; q < 6; ++q) {
    s.F.row(2 * q) << quads[q][0], quads[q][1], quads[q][2];
    s.F.row(2 * q + 1) << quads[q][0], quads[q][2], quads[q][3];
    s.patch(2 * q) = s.patch(2 * q + 1) = q + 1;
  }
  return s;
}

/// Faceted cylinder radius r, height h, n sides: side id 1, bottom 2, top 3 (caps as fans).
SurfaceMesh cylinder(double r, double h, int n) {
  SurfaceMesh s;
  s.V.resize(2 * n + 2, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    s.V.row(i) << r * std::cos(t), r * std::sin(t), 0;
    s.V.row(n + i) << r * std::cos(t), r * std::sin(t), h;
  }
  s.V.row(2 * n) << 0, 0, 0;
  s.V.row(2 * n + 1) << 0, 0, h;
  s.F.resize(4 * n, 3);
  s.patch.resize(4 * n);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s.F.row(4 * i) << i, j, n + j;
    s.F.row(4 * i + 1) << i, n + j, n + i;
    s.F.row(4 * i + 2) << 2 * n, j, i;
    s.F.row(4 * i + 3) << 2 * n + 1, n + i, n + j;
    s.patch(4 * i) = s.patch(4 * i + 1) = 1;
    s.patch(4 * i + 2) = 2;
    s.patch(4 * i + 3) = 3;
  }
  return s;
}

/// Every directed edge once and its reverse once: closed, 2-manifold, consistently oriented.
bool closed_and_oriented(const Eigen::MatrixXi& F) {
  std::map<std::pair<int, int>, int> directed;
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{F(t, k), F(t, (k + 1) % 3)}];
  for (const auto& [e, n] : directed)
    if (n != 1 || !directed.count({e.second, e.first})) return false;
  return true;
}

double volume(const SurfaceMesh& s) {
  double v = 0;
  for (int t = 0; t < s.F.rows(); ++t)
    v += Eigen::Vector3d(s.V.row(s.F(t, 0))).dot(Eigen::Vector3d(s.V.row(s.F(t, 1))).cross(Eigen::Vector3d(s.V.row(s.F(t, 2)))));
  return v / 6;
}

double min_angle_deg(const SurfaceMesh& s, int t) {
  double m = 180;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = s.V.row(s.F(t, k)), b = s.V.row(s.F(t, (k + 1) % 3)), c = s.V.row(s.F(t, (k + 2) % 3));
    const Eigen::Vector3d u = b - a, v = c - a;
    m = std::min(m, std::atan2(u.cross(v).norm(), u.dot(v)) * 180 / kPi);
  }
  return m;
}

}  // namespace

TEST(RemeshTriangles, BoxBecomesIsotropicAndKeepsItsFacesAndCorners) {
  const SurfaceMesh in = box(2, 1, 1);
  const double h = 0.2;
  const SurfaceMesh out = remesh_triangles(in, with_size(h));
  ASSERT_TRUE(closed_and_oriented(out.F));
  EXPECT_NEAR(volume(out), 2.0, 1e-9);
  // Each triangle lies in the plane of its face id, facing the same way.
  const Eigen::Vector3d normal[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  const double offset[6] = {0, 2, 0, 1, 0, 1};
  std::set<int> ids;
  double longest = 0, smallest = 180, mean_angle = 0;
  for (int t = 0; t < out.F.rows(); ++t) {
    const int f = out.patch(t) - 1;
    ASSERT_GE(f, 0);
    ASSERT_LT(f, 6);
    ids.insert(f);
    const Eigen::Vector3d a = out.V.row(out.F(t, 0)), b = out.V.row(out.F(t, 1)), c = out.V.row(out.F(t, 2));
    for (const Eigen::Vector3d& p : {a, b, c}) EXPECT_NEAR(p.dot(normal[f]), f % 2 ? offset[f] : 0, 1e-12) << t;
    EXPECT_GT((b - a).cross(c - a).normalized().dot(normal[f]), 1 - 1e-9) << t;
    longest = std::max({longest, (b - a).norm(), (c - b).norm(), (a - c).norm()});
    smallest = std::min(smallest, min_angle_deg(out, t));
    mean_angle += min_angle_deg(out, t) / out.F.rows();
  }
  EXPECT_EQ(ids.size(), 6u);
  // The 8 box corners are vertices of the result.
  for (int i = 0; i < 8; ++i) {
    double d = 1e9;
    for (int v = 0; v < out.V.rows(); ++v) d = std::min(d, (out.V.row(v) - in.V.row(i)).norm());
    EXPECT_LT(d, 1e-12) << "corner " << i;
  }
  // Near-equilateral triangles of about h: area 10 / (sqrt(3)/4 h^2) = 577 equilateral triangles.
  EXPECT_GT(out.F.rows(), 300);
  EXPECT_LT(out.F.rows(), 1200);
  EXPECT_LE(longest, 1.5 * h);
  EXPECT_GE(smallest, 25.0);
  EXPECT_GE(mean_angle, 45.0);
}

TEST(RemeshTriangles, VerticesStayOnTheInputTrianglesOfTheirFace) {
  const SurfaceMesh in = cylinder(5, 12, 24);
  const SurfaceMesh out = remesh_triangles(in, with_size(1.0));
  ASSERT_TRUE(closed_and_oriented(out.F));
  // Every vertex of a triangle with face id k lies on the input triangles of id k.
  std::map<int, TriangleProjector> on;
  for (int k = 1; k <= 3; ++k) {
    std::vector<int> rows;
    for (int t = 0; t < in.F.rows(); ++t)
      if (in.patch(t) == k) rows.push_back(t);
    Eigen::MatrixXi Fk(rows.size(), 3);
    for (size_t i = 0; i < rows.size(); ++i) Fk.row(i) = in.F.row(rows[i]);
    on.emplace(k, TriangleProjector(in.V, Fk));
  }
  std::set<int> ids;
  for (int t = 0; t < out.F.rows(); ++t) {
    ids.insert(out.patch(t));
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = out.V.row(out.F(t, k));
      EXPECT_LT((on.at(out.patch(t)).project(p) - p).norm(), 1e-9) << "triangle " << t;
    }
  }
  EXPECT_EQ(ids, (std::set<int>{1, 2, 3}));
  // Vertices on a convex faceted surface: the new triangles are chords inside it.
  EXPECT_LE(volume(out), volume(in) * (1 + 1e-12));
  EXPECT_GE(volume(out), 0.99 * volume(in));
  // Much better shaped than the input's fans and long side strips.
  double smallest = 180;
  for (int t = 0; t < out.F.rows(); ++t) smallest = std::min(smallest, min_angle_deg(out, t));
  EXPECT_GE(smallest, 25.0);
  EXPECT_GT(out.F.rows(), 4 * in.F.rows());
}

// A vertex no triangle uses (a .k file may list such a node; the paper's mount1 has one, on which
// `hexdom remesh` used to crash) is left out: the result is the box's, closed, with its volume and
// its six faces, as many triangles as without the vertex.
TEST(RemeshTriangles, AVertexNoTriangleUsesIsLeftOut) {
  const SurfaceMesh in = box(2, 1, 1);
  SurfaceMesh spare = in;
  spare.V.conservativeResize(in.V.rows() + 1, 3);
  spare.V.row(in.V.rows()) << 0.5, 0.5, 0.5;
  const SurfaceMesh a = remesh_triangles(in, with_size(0.2)), b = remesh_triangles(spare, with_size(0.2));
  ASSERT_TRUE(closed_and_oriented(b.F));
  EXPECT_NEAR(volume(b), 2.0, 1e-9);
  EXPECT_EQ(b.F.rows(), a.F.rows());
  EXPECT_EQ(std::set<int>(b.patch.data(), b.patch.data() + b.patch.size()).size(), 6u);
  for (int v = 0; v < b.V.rows(); ++v) EXPECT_GT((b.V.row(v) - spare.V.row(in.V.rows())).norm(), 0.4) << v;
}

TEST(RemeshTriangles, OpenOrNonManifoldSurfacesAreRefused) {
  SurfaceMesh open = box(1, 1, 1);
  open.F.conservativeResize(11, 3);
  open.patch.conservativeResize(11);
  try {
    remesh_triangles(open, with_size(0.2));
    FAIL() << "no error for an open surface";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("open: edge ("), std::string::npos) << e.what();
  }
  SurfaceMesh flipped = box(1, 1, 1);
  flipped.F.row(0) << flipped.F(0, 0), flipped.F(0, 2), flipped.F(0, 1);
  EXPECT_THROW(remesh_triangles(flipped, with_size(0.2)), InputError);
  SurfaceMesh wrong_ids = box(1, 1, 1);
  wrong_ids.patch.conservativeResize(5);
  EXPECT_THROW(remesh_triangles(wrong_ids, with_size(0.2)), InputError);
}

TEST(RemeshTriangles, FeatureAngleKeepsTheEdgesOfASurfaceWithoutFaceIds) {
  SurfaceMesh one = box(2, 1, 1);
  one.patch.setConstant(7);
  RemeshTrianglesOptions o = with_size(0.2);
  o.feature_angle = 45;
  const SurfaceMesh sharp = remesh_triangles(one, o);
  ASSERT_TRUE(closed_and_oriented(sharp.F));
  EXPECT_NEAR(volume(sharp), 2.0, 1e-9);  // no chord cuts an edge of the box
  for (int t = 0; t < sharp.F.rows(); ++t) EXPECT_EQ(sharp.patch(t), 7);
  const SurfaceMesh round = remesh_triangles(one, with_size(0.2));  // nothing holds the edges
  EXPECT_LT(volume(round), 2.0 - 1e-3);
}
