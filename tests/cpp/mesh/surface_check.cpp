// mesh::check_solid_surface: the input checks before any meshing stage (closed, one orientation,
// facing out of the solid, not crossing itself, one solid with its cavities).
#include <gtest/gtest.h>

#include <string>

#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/mesh/surface_check.h"

using hexdom::GeometryError;
using hexdom::mesh::check_solid_surface;
using hexdom::mesh::find_self_intersection;
using hexdom::mesh::SurfaceMesh;

namespace {

// An axis-aligned box [lo, hi], 12 triangles facing out.
SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  SurfaceMesh s;
  s.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    s.V.row(i) << (i & 1 ? hi.x() : lo.x()), (i & 2 ? hi.y() : lo.y()), (i & 4 ? hi.z() : lo.z());
  s.F.resize(12, 3);
  s.F << 0, 2, 1, 1, 2, 3,  // z = lo
      4, 5, 6, 5, 7, 6,     // z = hi
      0, 1, 4, 1, 5, 4,     // y = lo
      2, 6, 3, 3, 6, 7,     // y = hi
      0, 4, 2, 2, 4, 6,     // x = lo
      1, 3, 5, 3, 7, 5;     // x = hi
  s.patch = Eigen::VectorXi::Ones(12);
  return s;
}

// Two surfaces written as one (a triangle soup of two bodies).
SurfaceMesh join(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh s;
  s.V.resize(a.V.rows() + b.V.rows(), 3);
  s.V << a.V, b.V;
  s.F.resize(a.F.rows() + b.F.rows(), 3);
  s.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  s.patch = Eigen::VectorXi::Ones(s.F.rows());
  return s;
}

void reverse(SurfaceMesh& s, int from = 0, int to = -1) {
  for (int f = from; f < (to < 0 ? s.F.rows() : to); ++f) std::swap(s.F(f, 1), s.F(f, 2));
}

std::string error_of(SurfaceMesh s) {
  try {
    check_solid_surface(s, "part.stl");
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SurfaceCheck, AnOutwardBoxPassesUnchanged) {
  SurfaceMesh s = box({0, 0, 0}, {10, 10, 10});
  const Eigen::MatrixXi F = s.F;
  const auto r = check_solid_surface(s);
  EXPECT_EQ(r.shells, 1);
  EXPECT_EQ(r.flipped_shells, 0);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(s.F, F);
}

TEST(SurfaceCheck, AnInsideOutBoxIsTurnedAroundWithAWarning) {
  SurfaceMesh s = box({0, 0, 0}, {10, 10, 10});
  reverse(s);
  ASSERT_LT(hexdom::mesh::enclosed_volume(s.V, s.F), 0);
  const auto r = check_solid_surface(s, "box.stl");
  EXPECT_EQ(r.flipped_shells, 1);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("box.stl"), std::string::npos);
  EXPECT_NE(r.warnings[0].find("inside out"), std::string::npos);
  EXPECT_NEAR(hexdom::mesh::enclosed_volume(s.V, s.F), 1000.0, 1e-9);
}

TEST(SurfaceCheck, InconsistentOrientationNamesAnEdge) {
  SurfaceMesh s = box({0, 0, 0}, {10, 10, 10});
  reverse(s, 0, 1);  // one triangle turned against its neighbours
  const std::string e = error_of(s);
  EXPECT_NE(e.find("part.stl"), std::string::npos) << e;
  EXPECT_NE(e.find("inconsistently oriented"), std::string::npos) << e;
  EXPECT_NE(e.find("edge ("), std::string::npos) << e;
}

TEST(SurfaceCheck, AnOpenSurfaceNamesItsBoundaryEdge) {
  SurfaceMesh s = box({0, 0, 0}, {10, 10, 10});
  s.F.conservativeResize(11, 3);
  s.patch.conservativeResize(11);
  const std::string e = error_of(s);
  EXPECT_NE(e.find("open surface: boundary edge"), std::string::npos) << e;
}

TEST(SurfaceCheck, OverlappingBoxesAreRefusedNamingTwoTrianglesAndAPoint) {
  const SurfaceMesh s = join(box({0, 0, 0}, {10, 10, 10}), box({5, 5, 5}, {15, 15, 15}));
  const auto c = find_self_intersection(s.V, s.F);
  ASSERT_TRUE(c.has_value());
  EXPECT_LT(c->a, 12);  // one triangle of each box
  EXPECT_GE(c->b, 12);
  // The point lies on both boxes' surfaces: on a face plane of each.
  const Eigen::Vector3d p = c->point;
  auto on_box = [&](double lo, double hi) {
    for (int k = 0; k < 3; ++k)
      if (std::abs(p(k) - lo) < 1e-9 || std::abs(p(k) - hi) < 1e-9) return true;
    return false;
  };
  EXPECT_TRUE(on_box(0, 10) && on_box(5, 15)) << p.transpose();
  const std::string e = error_of(s);
  EXPECT_NE(e.find("part.stl crosses itself: triangles"), std::string::npos) << e;
}

TEST(SurfaceCheck, TouchingIsNotCrossing) {
  // Neighbouring triangles of one closed surface, and two boxes far apart: no crossing.
  EXPECT_FALSE(find_self_intersection(box({0, 0, 0}, {1, 1, 1}).V, box({0, 0, 0}, {1, 1, 1}).F).has_value());
  const SurfaceMesh two = join(box({0, 0, 0}, {1, 1, 1}), box({3, 0, 0}, {4, 1, 1}));
  EXPECT_FALSE(find_self_intersection(two.V, two.F).has_value());
}

TEST(SurfaceCheck, ANestedBoxIsACavityFacingIntoIt) {
  // A cube with a cubic cavity: the inner shell must face into the cavity (negative volume).
  for (bool inner_wrong : {false, true}) {
    SurfaceMesh inner = box({3, 3, 3}, {7, 7, 7});
    if (!inner_wrong) reverse(inner);  // facing into the cavity, as a correct export writes it
    SurfaceMesh s = join(box({0, 0, 0}, {10, 10, 10}), inner);
    const auto r = check_solid_surface(s);
    EXPECT_EQ(r.shells, 2);
    EXPECT_EQ(r.cavities, 1);
    EXPECT_EQ(r.flipped_shells, inner_wrong ? 1 : 0);
    EXPECT_NEAR(hexdom::mesh::enclosed_volume(s.V, s.F), 1000.0 - 64.0, 1e-9);
  }
}

TEST(SurfaceCheck, SeparateSolidsAreRefused) {
  const SurfaceMesh s = join(box({0, 0, 0}, {1, 1, 1}), box({3, 0, 0}, {4, 1, 1}));
  const std::string e = error_of(s);
  EXPECT_NE(e.find("2 separate closed shells (solids)"), std::string::npos) << e;
}

TEST(SurfaceCheck, SeveralSolidsWhenAskedForEachWithItsCavities) {
  // Solid 1: a box with a cavity; solid 2 inside that cavity (inside-out: turned around); solid 3
  // beside them. Shells: outer, cavity, inner solid, separate box.
  SurfaceMesh cavity = box({2, 2, 2}, {10, 10, 10});
  reverse(cavity);
  SurfaceMesh inner = box({4, 4, 4}, {8, 8, 8});
  reverse(inner);
  SurfaceMesh s = join(join(join(box({0, 0, 0}, {12, 12, 12}), cavity), inner), box({20, 0, 0}, {21, 1, 1}));
  hexdom::mesh::SurfaceCheckOptions opt;
  opt.several_solids = true;
  const auto r = check_solid_surface(s, "parts.stl", opt);
  EXPECT_EQ(r.shells, 4);
  EXPECT_EQ(r.solids, 3);
  EXPECT_EQ(r.cavities, 1);
  EXPECT_EQ(r.flipped_shells, 1);
  ASSERT_EQ(r.solid.size(), 48u);
  for (int f = 0; f < 48; ++f) EXPECT_EQ(r.solid[f], f < 24 ? 0 : f < 36 ? 1 : 2) << f;
  const auto parts = hexdom::mesh::split_solids(s, r);
  ASSERT_EQ(parts.size(), 3u);
  const double volume[3] = {12.0 * 12 * 12 - 8.0 * 8 * 8, 64.0, 1.0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(parts[k].F.rows(), k == 0 ? 24 : 12);
    EXPECT_EQ(parts[k].V.rows(), k == 0 ? 16 : 8);
    EXPECT_EQ(parts[k].patch.rows(), parts[k].F.rows());
    EXPECT_NEAR(hexdom::mesh::enclosed_volume(parts[k].V, parts[k].F), volume[k], 1e-9) << k;
    EXPECT_NO_THROW(hexdom::mesh::check_closed_manifold(parts[k]));
  }
  // Without the option a solid inside a cavity is refused, as separate solids are.
  EXPECT_NE(error_of(join(join(box({0, 0, 0}, {12, 12, 12}), cavity), box({4, 4, 4}, {8, 8, 8})))
                .find("a shell inside a cavity"),
            std::string::npos);
}

TEST(SurfaceCheck, BoxesOverlappingAlongCoplanarFacesAreRefused) {
  // B's faces at y = 0, y = 10, z = 0 and z = 10 lie on A's over x in [5, 10]; the edges that
  // meet the other box's faces do so where the two surfaces lie on each other (contacts, not
  // crossings), so the coplanar test finds the overlap.
  const SurfaceMesh s = join(box({0, 0, 0}, {10, 10, 10}), box({5, 0, 0}, {15, 10, 10}));
  const auto c = find_self_intersection(s.V, s.F);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->coplanar, hexdom::mesh::Crossing::kSameWay);
  EXPECT_TRUE(c->deep);
  EXPECT_LT(c->a, 12);
  EXPECT_GE(c->b, 12);
  EXPECT_GE(c->point.x(), 5 - 1e-9);  // in the overlap, on a face plane of both
  EXPECT_LE(c->point.x(), 10 + 1e-9);
  const Eigen::Vector3d p = c->point;
  EXPECT_TRUE(std::abs(p.y()) < 1e-9 || std::abs(p.y() - 10) < 1e-9 || std::abs(p.z()) < 1e-9 ||
              std::abs(p.z() - 10) < 1e-9)
      << p.transpose();
  const std::string e = error_of(s);
  EXPECT_NE(e.find("part.stl lies on itself: triangles "), std::string::npos) << e;
  EXPECT_NE(e.find("facing the same way at ("), std::string::npos) << e;
  // A body written twice: the same box twice.
  EXPECT_NE(error_of(join(box({0, 0, 0}, {1, 1, 1}), box({0, 0, 0}, {1, 1, 1}))).find("lies on itself"),
            std::string::npos);
}

TEST(SurfaceCheck, SolidsTouchingAlongAFaceAreWarned) {
  // Two boxes meeting at x = 10 (each face triangulated its own way), as two solids: accepted, the
  // pair named as touching with a warning; boxes meeting at an edge only do not touch over an area.
  SurfaceMesh b = box({10, 0, 0}, {20, 10, 10});
  b.F.row(8) << 0, 4, 6;  // the x = 10 face split along its other diagonal
  b.F.row(9) << 0, 6, 2;
  hexdom::mesh::SurfaceCheckOptions opt;
  opt.several_solids = true;
  SurfaceMesh s = join(box({0, 0, 0}, {10, 10, 10}), b);
  std::vector<hexdom::mesh::Crossing> opposite;
  EXPECT_FALSE(find_self_intersection(s.V, s.F, nullptr, &opposite).has_value());
  EXPECT_EQ(opposite.size(), 4u);  // each of A's two triangles on x = 10 overlaps both of B's
  const auto r = check_solid_surface(s, "parts.stl", opt);
  EXPECT_EQ(r.solids, 2);
  EXPECT_EQ(r.cavities, 0);  // a vertex of B on A's face does not make B a cavity
  EXPECT_EQ(r.flipped_shells, 0);
  ASSERT_EQ(r.touching.size(), 1u);
  EXPECT_EQ(r.touching[0], (std::array<int, 2>{1, 2}));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("parts.stl: solids 1 and 2 touch"), std::string::npos) << r.warnings[0];
  SurfaceMesh edge = join(box({0, 0, 0}, {10, 10, 10}), box({10, 10, 0}, {20, 20, 10}));
  EXPECT_TRUE(check_solid_surface(edge, "parts.stl", opt).touching.empty());
  // The second box inside out: its face on x = 10 faces the first's way as written, the opposite
  // way once turned around, as the check judges it.
  reverse(b);
  SurfaceMesh inside_out = join(box({0, 0, 0}, {10, 10, 10}), b);
  const auto t = check_solid_surface(inside_out, "parts.stl", opt);
  EXPECT_EQ(t.flipped_shells, 1);
  ASSERT_EQ(t.touching.size(), 1u);
  EXPECT_EQ(t.warnings.size(), 2u);
}

TEST(SurfaceCheck, AWallOfNoThicknessIsRefused) {
  // A cavity whose wall touches the outer shell's face x = 10 from inside: one solid's surface lying
  // on itself facing opposite ways.
  SurfaceMesh cavity = box({4, 4, 4}, {10, 6, 6});
  reverse(cavity);
  const std::string e = error_of(join(box({0, 0, 0}, {10, 10, 10}), cavity));
  EXPECT_NE(e.find("part.stl touches itself: triangles "), std::string::npos) << e;
  EXPECT_NE(e.find("a wall of no thickness"), std::string::npos) << e;
}
