#include "hexdom/polycube/boundary_graph.h"

#include <gtest/gtest.h>

#include <cmath>

#include "autopolycube/auto_test_util.h"
#include "hexdom/common/error.h"
#include "hexdom/polycube/patch_layout.h"

using namespace hexdom;

namespace {

// The first and last vertex of signed curve sc (i or ~i) as a loop runs it.
int curve_end(const polycube::BoundaryGraph& g, int sc, bool last) {
  const auto& cv = g.curves[sc < 0 ? ~sc : sc];
  return (sc < 0) != last ? cv.vertices.back() : cv.vertices.front();
}

// Every loop's curves meet at its corners, the loops of a region run each of its curves once, and
// every curve has its left region's triangles on its left.
void expect_consistent(const mesh::SurfaceMesh& s, const polycube::BoundaryGraph& g) {
  for (int r = 0; r < g.num_regions(); ++r) {
    size_t runs = 0;
    for (const auto& loop : g.loops[r]) {
      const size_t n = loop.curves.size();
      runs += n;
      if (loop.corners.empty()) {
        ASSERT_EQ(n, 1u);
        EXPECT_TRUE(g.curves[loop.curves[0] < 0 ? ~loop.curves[0] : loop.curves[0]].closed);
        continue;
      }
      ASSERT_EQ(loop.corners.size(), n);
      for (size_t i = 0; i < n; ++i) {
        EXPECT_EQ(curve_end(g, loop.curves[i], false), loop.corners[i]);
        EXPECT_EQ(curve_end(g, loop.curves[i], true), curve_end(g, loop.curves[(i + 1) % n], false));
        const auto& cv = g.curves[loop.curves[i] < 0 ? ~loop.curves[i] : loop.curves[i]];
        EXPECT_EQ(loop.curves[i] >= 0 ? cv.left : cv.right, r);
      }
    }
    EXPECT_EQ(runs, g.region_curves[r].size()) << "region " << r;
  }
  for (const auto& c : g.curves) {
    EXPECT_LT(c.left, c.right);
    if (!c.closed) {
      EXPECT_GE(g.corner_of(c.vertices.front()), 0);
      EXPECT_GE(g.corner_of(c.vertices.back()), 0);
    }
    for (size_t k = 1; k + 1 < c.vertices.size(); ++k) EXPECT_LT(g.corner_of(c.vertices[k]), 0);
    // The edge (v0, v1) is an edge of a triangle of `left`, in that triangle's direction.
    bool found = false;
    for (int f : g.triangles[c.left])
      for (int k = 0; k < 3; ++k) found = found || (s.F(f, k) == c.vertices[0] && s.F(f, (k + 1) % 3) == c.vertices[1]);
    EXPECT_TRUE(found);
  }
}

}  // namespace

TEST(BoundaryGraph, CubeHasSixRegionsEightCornersTwelveCurves) {
  auto s = test::cell_surface({{0, 0, 0}}, 3);
  auto g = polycube::boundary_graph(s);
  EXPECT_EQ(g.num_regions(), 6);
  EXPECT_EQ(g.corners.size(), 8u);
  EXPECT_EQ(g.curves.size(), 12u);
  EXPECT_TRUE(g.pinches.empty());
  for (int n : g.corner_regions) EXPECT_EQ(n, 3);
  int tris = 0;
  for (int r = 0; r < 6; ++r) {
    ASSERT_EQ(g.loops[r].size(), 1u);
    EXPECT_EQ(g.loops[r][0].corners.size(), 4u);
    EXPECT_EQ(g.loops[r][0].curves.size(), 4u);
    EXPECT_EQ(g.region_curves[r].size(), 4u);
    EXPECT_EQ(g.triangles[r].size(), 18u);
    for (int f : g.triangles[r]) EXPECT_EQ(g.region(f), r);
    EXPECT_EQ(g.label[r], s.patch(g.triangles[r][0]));
    if (r > 0) {
      EXPECT_LT(g.triangles[r - 1][0], g.triangles[r][0]);
    }
    tris += static_cast<int>(g.triangles[r].size());
  }
  EXPECT_EQ(tris, s.F.rows());
  expect_consistent(s, g);
}

TEST(BoundaryGraph, LShapeLoopsRunCounterClockwiseAndChainAtCorners) {
  // The top and bottom are L-shaped regions with 6 corners, one of them concave.
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2);
  auto g = polycube::boundary_graph(s);
  EXPECT_EQ(g.num_regions(), 8);
  EXPECT_EQ(g.corners.size(), 12u);
  int six = 0;
  for (int r = 0; r < g.num_regions(); ++r)
    for (const auto& loop : g.loops[r]) six += loop.curves.size() == 6;
  EXPECT_EQ(six, 2);
  expect_consistent(s, g);
}

TEST(BoundaryGraph, RegionWithAHoleHasTwoLoops) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  // Two triangles in the middle of the +Z face get another id: an island in a region with a hole.
  int changed = 0;
  for (int f = 0; f < s.F.rows() && changed < 2; ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    if (s.patch(f) == 5 && std::abs(c(0) - 0.5) < 0.25 && std::abs(c(1) - 0.5) < 0.25) { s.patch(f) = 1; ++changed; }
  }
  ASSERT_EQ(changed, 2);
  auto g = polycube::boundary_graph(s);
  EXPECT_EQ(g.num_regions(), 7);
  int closed = 0;
  for (const auto& c : g.curves) closed += c.closed;
  EXPECT_EQ(closed, 1);
  const int top = g.region(std::find(s.patch.data(), s.patch.data() + s.patch.rows(), 5) - s.patch.data());
  ASSERT_EQ(g.loops[top].size(), 2u);
  EXPECT_EQ(g.loops[top][0].corners.size(), 4u);  // loops with corners first
  EXPECT_TRUE(g.loops[top][1].corners.empty());
  const int island = g.num_regions() - 1;
  ASSERT_EQ(g.loops[island].size(), 1u);
  EXPECT_TRUE(g.loops[island][0].corners.empty());
  EXPECT_EQ(g.loops[island][0].curves.size(), 1u);
  expect_consistent(s, g);
  // The layout view: the patch with the hole has two loops, the island one loop without corners.
  const auto layout = polycube::patch_layout(g);
  EXPECT_EQ(layout.patches[top].num_loops, 2);
  EXPECT_EQ(layout.patches[top].corners.size(), 4u);
  EXPECT_EQ(layout.patches[island].num_loops, 1);
  EXPECT_TRUE(layout.patches[island].corners.empty());
  EXPECT_EQ(layout.patches[island].loop.size(), 4u);  // two triangles: a quad
  EXPECT_EQ(layout.corners, g.corners);
}

TEST(BoundaryGraph, RegionMeetingItselfAtAVertexIsAPinch) {
  // On the +Z face (4 x 4 squares), a ring of squares around square (2, 1) that touches itself at
  // the square's corner (2, 2) (in quarters): (1, 1) and (2, 2) meet there diagonally.
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  const std::vector<std::array<int, 2>> ring = {{1, 1}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {2, 2}};
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    if (s.patch(f) != 5) continue;
    const std::array<int, 2> q = {static_cast<int>(std::floor(4 * c(0))), static_cast<int>(std::floor(4 * c(1)))};
    if (std::find(ring.begin(), ring.end(), q) != ring.end()) s.patch(f) = 9;
  }
  auto g = polycube::boundary_graph(s);
  EXPECT_EQ(g.num_regions(), 8);  // the six faces, the ring, the square it encloses
  int pinch = -1;
  for (int v = 0; v < s.V.rows(); ++v)
    if ((s.V.row(v) - Eigen::RowVector3d(0.5, 0.5, 1.0)).norm() < 1e-12) pinch = v;
  ASSERT_GE(pinch, 0);
  EXPECT_EQ(g.pinches, std::vector<int>{pinch});
  ASSERT_GE(g.corner_of(pinch), 0);
  EXPECT_EQ(g.corner_regions[g.corner_of(pinch)], 3);
  expect_consistent(s, g);
}

TEST(BoundaryGraph, OpenSurfaceIsRejected) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.F.conservativeResize(s.F.rows() - 1, 3);
  s.patch.conservativeResize(s.F.rows());
  EXPECT_THROW(polycube::boundary_graph(s), GeometryError);
}

// The graph of a relabelling built with the adjacency of the surface's own graph is the graph
// built from scratch: regions, corners, curves and loops alike; a wrong-sized adjacency is refused.
TEST(BoundaryGraph, ARelabellingWithTheGraphsAdjacencyGivesTheSameGraph) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2);
  const polycube::BoundaryGraph g = polycube::boundary_graph(s);
  ASSERT_EQ(g.adjacency.rows(), s.F.rows());
  mesh::SurfaceMesh t = s;
  for (int f = 0; f < t.F.rows(); ++f) t.patch(f) = 1 + (t.patch(f) + f / 7) % 4;  // other regions, other corners
  const polycube::BoundaryGraph fresh = polycube::boundary_graph(t);
  const polycube::BoundaryGraph reused = polycube::boundary_graph(t, g.adjacency);
  ASSERT_NE(fresh.num_regions(), g.num_regions());
  EXPECT_EQ(reused.region, fresh.region);
  EXPECT_EQ(reused.label, fresh.label);
  EXPECT_EQ(reused.triangles, fresh.triangles);
  EXPECT_EQ(reused.corners, fresh.corners);
  EXPECT_EQ(reused.pinches, fresh.pinches);
  ASSERT_EQ(reused.curves.size(), fresh.curves.size());
  for (size_t c = 0; c < fresh.curves.size(); ++c) EXPECT_EQ(reused.curves[c].vertices, fresh.curves[c].vertices);
  ASSERT_EQ(reused.loops.size(), fresh.loops.size());
  for (size_t r = 0; r < fresh.loops.size(); ++r) {
    ASSERT_EQ(reused.loops[r].size(), fresh.loops[r].size());
    for (size_t l = 0; l < fresh.loops[r].size(); ++l) {
      EXPECT_EQ(reused.loops[r][l].corners, fresh.loops[r][l].corners);
      EXPECT_EQ(reused.loops[r][l].curves, fresh.loops[r][l].curves);
    }
  }
  expect_consistent(t, reused);
  EXPECT_THROW(polycube::boundary_graph(t, g.adjacency.topRows(3)), GeometryError);
}
