// mesh::triangulate_polygon: ear clipping of loops with holes, used for CAD faces that BRepMesh
// could not triangulate.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "hexdom/mesh/triangulate_polygon.h"

using hexdom::mesh::loops_intersect;
using hexdom::mesh::triangulate_polygon;
using P = Eigen::Vector2d;

namespace {

double tri_area(const std::vector<P>& pts, const std::array<int, 3>& t) {
  const P a = pts[t[0]], b = pts[t[1]], c = pts[t[2]];
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

/// Checks that `tris` cover the loops exactly: counter-clockwise, the total area the loops' (outer
/// minus holes), every boundary segment used once and every other edge twice in opposite directions.
void expect_exact_cover(const std::vector<std::vector<P>>& loops, const std::vector<std::array<int, 3>>& tris,
                        double area) {
  std::vector<P> pts;
  for (const auto& l : loops) pts.insert(pts.end(), l.begin(), l.end());
  double sum = 0;
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : tris) {
    EXPECT_GT(tri_area(pts, t), 0);
    sum += tri_area(pts, t);
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  EXPECT_NEAR(sum, area, 1e-9 * area);
  std::map<std::pair<int, int>, int> boundary;  // undirected boundary segments
  int base = 0;
  for (const auto& l : loops) {
    const int n = static_cast<int>(l.size());
    for (int i = 0; i < n; ++i) {
      const int a = base + i, b = base + (i + 1) % n;
      ++boundary[{std::min(a, b), std::max(a, b)}];
    }
    base += n;
  }
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << e.first << "-" << e.second << " used twice one way";
    const bool on_boundary = boundary.count({std::min(e.first, e.second), std::max(e.first, e.second)}) > 0;
    const bool paired = directed.count({e.second, e.first}) > 0;
    EXPECT_NE(on_boundary, paired) << e.first << "-" << e.second;
  }
  for (const auto& [e, n] : boundary)
    EXPECT_EQ(directed.count(e) + directed.count({e.second, e.first}), 1u) << "segment " << e.first << "-" << e.second;
}

std::vector<P> square(double x0, double y0, double side, int per_side, bool ccw) {
  std::vector<P> l;
  const P c[4] = {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k < per_side; ++k) l.push_back(c[s] + (c[(s + 1) % 4] - c[s]) * (static_cast<double>(k) / per_side));
  if (!ccw) std::reverse(l.begin(), l.end());
  return l;
}

}  // namespace

TEST(TriangulatePolygon, SquareWithCollinearNodes) {
  const std::vector<std::vector<P>> loops{square(0, 0, 4, 5, true)};
  const auto tris = triangulate_polygon(loops);
  EXPECT_EQ(tris.size(), 18u);  // n - 2
  expect_exact_cover(loops, tris, 16.0);
}

TEST(TriangulatePolygon, EitherOrientationAndTwoHoles) {
  // The outer loop clockwise, the holes counter-clockwise: each is turned as needed.
  const std::vector<std::vector<P>> loops{square(0, 0, 10, 4, false), square(2, 2, 2, 3, true), square(6, 5, 3, 2, true)};
  const auto tris = triangulate_polygon(loops);
  ASSERT_FALSE(tris.empty());
  expect_exact_cover(loops, tris, 100.0 - 4.0 - 9.0);
}

TEST(TriangulatePolygon, NonConvexOuterLoop) {
  // An L and a comb: reflex corners.
  const std::vector<std::vector<P>> loops{{{0, 0}, {6, 0}, {6, 1}, {1, 1}, {1, 2}, {6, 2}, {6, 3}, {1, 3}, {1, 4}, {6, 4}, {6, 5}, {0, 5}}};
  const auto tris = triangulate_polygon(loops);
  ASSERT_EQ(tris.size(), 10u);
  expect_exact_cover(loops, tris, 30.0 - 10.0);
}

TEST(TriangulatePolygon, CrossingLoopsAreRefusedWithAReason) {
  std::string why;
  const std::vector<std::vector<P>> bow{{{0, 0}, {4, 2}, {4, 0}, {0, 3}}};  // lobes of unequal area
  EXPECT_TRUE(triangulate_polygon(bow, &why).empty());
  EXPECT_NE(why.find("cross"), std::string::npos) << why;
  EXPECT_TRUE(loops_intersect(bow));
  const std::vector<std::vector<P>> hole_out{square(0, 0, 4, 1, true), square(3, 1, 2, 1, false)};
  EXPECT_TRUE(triangulate_polygon(hole_out, &why).empty());
  EXPECT_FALSE(loops_intersect({square(0, 0, 4, 1, true), square(1, 1, 2, 1, false)}));
  EXPECT_TRUE(triangulate_polygon({{{0, 0}, {1, 1}}}, &why).empty());
  EXPECT_NE(why.find("fewer than three"), std::string::npos) << why;
}
