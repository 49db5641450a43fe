// Face neighbours of volume cells, and rays against a triangle surface (closest_point.h).
#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "test_common.h"

#include <cmath>
#include <limits>

using namespace hexdom;
using mesh::CellType;

// A row of three hexes (0-1 and 1-2 share a face), a wedge on the third's top face (its quad), a tet
// on the wedge's triangle, a hex touching the first along an edge only: the pairs sharing a whole
// face, in order.
TEST(FaceNeighbours, PairsTheCellsSharingAFace) {
  mesh::MeshBuilder b;
  const int h0[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int h1[8] = {1, 8, 9, 2, 5, 10, 11, 6};
  const int h2[8] = {8, 12, 13, 9, 10, 14, 15, 11};
  const int w[6] = {10, 14, 16, 11, 15, 17};  // quad (10, 14, 15, 11): h2's top
  const int t[4] = {11, 15, 17, 18};           // on the wedge's triangle (11, 15, 17)
  b.add(CellType::Hex, h0, 1);
  b.add(CellType::Hex, h1, 1);
  b.add(CellType::Hex, h2, 1);
  b.add(CellType::Wedge, w, 1);
  b.add(CellType::Tet, t, 1);
  const int h3[8] = {3, 2, 19, 20, 21, 22, 23, 24};  // the edge (2, 3) of h0 only
  b.add(CellType::Hex, h3, 1);
  const mesh::Mesh m = b.finish(Eigen::MatrixXd::Zero(25, 3));
  EXPECT_EQ(mesh::face_neighbours(m), (std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {2, 3}, {3, 4}}));
  // Node ids beyond the nodes given (a mesh not checked yet; the table sorts them another way):
  // the same pairs and the same boundary faces.
  mesh::Mesh unchecked = m;
  unchecked.V = Eigen::MatrixXd::Zero(10, 3);
  EXPECT_EQ(mesh::face_neighbours(unchecked), mesh::face_neighbours(m));
  const auto faces = mesh::boundary_faces(m), same = mesh::boundary_faces(unchecked);
  ASSERT_EQ(same.size(), faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    EXPECT_EQ(same[f].cell, faces[f].cell);
    EXPECT_EQ(same[f].v, faces[f].v);
  }
}

TEST(FaceNeighbours, AFaceOfThreeCellsIsAnError) {
  mesh::MeshBuilder b;
  const int h0[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int h1[8] = {4, 5, 6, 7, 8, 9, 10, 11};
  const int h2[8] = {4, 5, 6, 7, 12, 13, 14, 15};
  b.add(CellType::Hex, h0, 1);
  b.add(CellType::Hex, h1, 1);
  b.add(CellType::Hex, h2, 1);
  EXPECT_THROW(mesh::face_neighbours(b.finish(Eigen::MatrixXd::Zero(16, 3))), GeometryError);
}

// The first triangle along a ray: two unit squares, in z = 0 and z = 2.
TEST(TriangleProjector, RayDistance) {
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 2, 1, 0, 2, 1, 1, 2, 0, 1, 2;
  Eigen::MatrixXi F(4, 3);
  F << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  const mesh::TriangleProjector s(V, F);
  using P = Eigen::Vector3d;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(s.ray_distance(P(0.3, 0.2, -1), P(0, 0, 5), 0, inf), 1.0, 1e-12);  // any length of direction
  EXPECT_NEAR(s.ray_distance(P(0.3, 0.2, -1), P(0, 0, 1), 1.5, inf), 3.0, 1e-12);  // beyond `from`
  EXPECT_EQ(s.ray_distance(P(0.3, 0.2, -1), P(0, 0, 1), 0, 0.5), inf);             // short of `up_to`
  int t = -5;
  EXPECT_NEAR(s.ray_distance(P(0.75, 0.25, 0), P(0, 0, 1), 0, inf, 0, &t), 2.0, 1e-12);  // its own triangle left out
  EXPECT_EQ(t, 2);
  EXPECT_TRUE(s.normal(2).isApprox(P(0, 0, 1)));
  EXPECT_EQ(s.ray_distance(P(0.3, 0.2, -1), P(0, 0, -1), 0, inf, -1, &t), inf);     // away from both
  EXPECT_EQ(t, -1);
  EXPECT_NEAR(s.ray_distance(P(3, 0.5, 1), P(-1, 0, 0.4), 0, inf), 2.5 * std::sqrt(1.16), 1e-12);  // at (0.5, 0.5, 2)
}

// A hint changes nothing but the time: on a folded grid of triangles (a flat half and a half at 90
// degrees, so that many queries are equally near several triangles: above shared vertices and
// edges, on the fold's bisector), every query gives the same point, bit for bit, and the same
// triangle with any hint as without one.
TEST(TriangleProjector, AHintGivesTheSameAnswer) {
  const int n = 8;
  Eigen::MatrixXd V((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      V.row(j * (n + 1) + i) << std::min(x, 0.5), y, std::max(0.0, x - 0.5);  // folded up at x = 0.5
    }
  Eigen::MatrixXi F(2 * n * n, 3);
  for (int j = 0, f = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      F.row(f++) << a, b, c;
      F.row(f++) << a, c, d;
    }
  const mesh::TriangleProjector s(V, F);
  int checked = 0;
  for (int j = -2; j <= 2 * n + 2; ++j)
    for (int i = -2; i <= 2 * n + 2; ++i)
      for (const double h : {0.0, 0.05, -0.3}) {
        const Eigen::Vector3d p(double(i) / (2 * n), double(j) / (2 * n), h + 0.25 * (i % 3 == 0));
        int t0 = -2;
        const Eigen::Vector3d q0 = s.project(p, &t0);
        for (const int hint : {0, static_cast<int>(F.rows()) - 1, (i * 7 + j * 13) % static_cast<int>(F.rows()), t0}) {
          int t = -2;
          const Eigen::Vector3d q = s.project(p, &t, hint);
          ASSERT_EQ(t, t0) << p.transpose() << " hint " << hint;
          ASSERT_TRUE(q == q0) << p.transpose() << " hint " << hint;
          ++checked;
        }
      }
  EXPECT_GT(checked, 3000);
}
