// Refinement by thirds of a hex-dominant mesh around marked nodes (mesh/refine.h). Checked on the
// mesh itself: boundary faces only on the input's boundary (no hanging node), the volume kept
// (affine parents: exactly), no inverted cell, the unmarked cells untouched, prisms never cut.
#include <gtest/gtest.h>

#include <cmath>

#include "../hex_grid.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/refine.h"
#include "hexdom/quality/metrics.h"

using namespace hexdom;

namespace {

// An n x n x n grid of unit cubes under the affine map A x + t (det A > 0).
mesh::Mesh grid(int n, bool two_prisms = false) {
  const int mx = n + 1;
  Eigen::Matrix3d A;
  A << 1.2, 0.3, 0.0, -0.1, 0.9, 0.2, 0.1, 0.0, 1.1;
  Eigen::MatrixXd V(mx * mx * mx, 3);
  for (int l = 0; l <= n; ++l)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        V.row(test::grid_node(i, j, l, mx, mx)) = (A * Eigen::Vector3d(i, j, l) + Eigen::Vector3d(3, -1, 2)).transpose();
  return test::grid_cells(V, n, n, mx, mx, two_prisms);
}

struct Summary {
  double volume = 0, worst_sj = 2, boundary_area = 0;  // worst_sj: of the hexes
  int boundary_faces = 0;
};

Summary summary(const mesh::Mesh& m) {
  Summary s;
  for (int c = 0; c < m.num_cells(); ++c) {
    const quality::CellPoints P = quality::cell_points(m, c);
    s.volume += std::abs(quality::volume(m.type(c), P));
    if (m.type(c) == mesh::CellType::Hex)  // (the fixture's wedges are not in VTK's orientation)
      s.worst_sj = std::min(s.worst_sj, quality::signed_sj(quality::scaled_jacobian(m.type(c), P)));
  }
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(m)) {
    s.boundary_area += mesh::face_area_vector(m, f).norm();
    ++s.boundary_faces;
  }
  return s;
}

std::vector<char> marks(const mesh::Mesh& m, std::initializer_list<int> nodes) {
  std::vector<char> out(m.num_nodes(), 0);
  for (int v : nodes) out[v] = 1;
  return out;
}

}  // namespace

TEST(Refine, TheTemplatesTableHasEveryPatternOnce) {
  const mesh::RefinementTemplates& t = mesh::refinement_templates();
  int corners = 0, edges = 0, faces = 0;
  for (int mask = 1; mask < 255; ++mask) {
    corners += t.kind[mask] == 1;
    edges += t.kind[mask] == 2;
    faces += t.kind[mask] == 3;
  }
  EXPECT_EQ(corners, 8);
  EXPECT_EQ(edges, 12);
  EXPECT_EQ(faces, 6);
  EXPECT_EQ(t.cells_for(255).size(), 27u);
  EXPECT_EQ(t.cells_for(1).size(), 4u);
  EXPECT_EQ(t.cells_for(3).size(), 11u);
  EXPECT_EQ(t.cells_for(0x0F).size(), 22u);
  EXPECT_THROW(t.cells_for(5), std::logic_error);  // two opposite corners of a face: not a pattern
}

TEST(Refine, OneMarkedNodeGivesCornerTemplatesAroundIt) {
  const mesh::Mesh m = grid(3);
  const Summary before = summary(m);
  const int centre = test::grid_node(1, 1, 1, 4, 4);  // an interior node: 8 cells around it
  const mesh::Refinement r = mesh::refine_by_thirds(m, marks(m, {centre}));
  EXPECT_EQ(r.split, 0);
  EXPECT_EQ(r.templates, 8);
  EXPECT_EQ(r.marked, 1);
  EXPECT_EQ(r.mesh.num_cells(), 27 - 8 + 8 * 4);
  const Summary after = summary(r.mesh);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * before.volume);
  EXPECT_NEAR(after.boundary_area, before.boundary_area, 1e-9 * before.boundary_area);
  EXPECT_EQ(after.boundary_faces, before.boundary_faces);  // the marked node is inside
  EXPECT_GT(after.worst_sj, 0.1);
  // The old nodes keep their numbers and places.
  EXPECT_TRUE(r.mesh.V.topRows(m.num_nodes()).isApprox(m.V));
  ASSERT_EQ(static_cast<int>(r.parent.size()), r.mesh.num_cells());
}

TEST(Refine, AFaceOfMarksIsCompletedAndGradedBack) {
  const mesh::Mesh m = grid(4);
  const Summary before = summary(m);
  // The nodes of the face z = 0: its cells split, the layer above gets face templates.
  std::vector<char> mk(m.num_nodes(), 0);
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) mk[test::grid_node(i, j, 0, 5, 5)] = 1;
  const mesh::Refinement r = mesh::refine_by_thirds(m, mk);
  EXPECT_EQ(r.split, 0);      // each bottom cell has one face (4 corners) marked
  EXPECT_EQ(r.templates, 16);
  const Summary after = summary(r.mesh);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * before.volume);
  EXPECT_NEAR(after.boundary_area, before.boundary_area, 1e-9 * before.boundary_area);
  EXPECT_GT(after.boundary_faces, before.boundary_faces + 16 * 8);  // the bottom quads in 9 at least
  EXPECT_GT(after.worst_sj, 0.1);
}

TEST(Refine, TwoLayersOfMarksSplitTheCellsBetween) {
  const mesh::Mesh m = grid(4);
  const Summary before = summary(m);
  std::vector<char> mk(m.num_nodes(), 0);
  for (int l = 0; l <= 1; ++l)
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) mk[test::grid_node(i, j, l, 5, 5)] = 1;
  const mesh::Refinement r = mesh::refine_by_thirds(m, mk);
  EXPECT_EQ(r.split, 16);
  EXPECT_EQ(r.templates, 16);
  const Summary after = summary(r.mesh);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * before.volume);
  EXPECT_NEAR(after.boundary_area, before.boundary_area, 1e-9 * before.boundary_area);
  EXPECT_GT(after.worst_sj, 0.1);
}

TEST(Refine, InvalidPatternsAreCompletedIntoAConformingMesh) {
  // Two diagonal corners of one cell and a node two cells away: completion splits what lies
  // between (the cells with the most marks first); the result is conforming and valid.
  const mesh::Mesh m = grid(4);
  const Summary before = summary(m);
  const mesh::Refinement r =
      mesh::refine_by_thirds(m, marks(m, {test::grid_node(1, 1, 1, 5, 5), test::grid_node(2, 2, 2, 5, 5),
                                          test::grid_node(3, 1, 1, 5, 5)}));
  EXPECT_GT(r.split, 0);
  const Summary after = summary(r.mesh);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * before.volume);
  EXPECT_NEAR(after.boundary_area, before.boundary_area, 1e-9 * before.boundary_area);
  EXPECT_GT(after.worst_sj, 0.1);
}

TEST(Refine, PrismsAreNeverCutAndTheirNodesNotMarked) {
  const mesh::Mesh m = grid(3, /*two_prisms=*/true);  // the last cell is two wedges
  const Summary before = summary(m);
  // A node of the wedges (the far corner) and one away from them.
  const mesh::Refinement r =
      mesh::refine_by_thirds(m, marks(m, {test::grid_node(3, 3, 3, 4, 4), test::grid_node(1, 1, 1, 4, 4)}));
  EXPECT_EQ(r.marked, 1);
  EXPECT_EQ(r.mesh.count(mesh::CellType::Wedge), 2);
  const Summary after = summary(r.mesh);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * before.volume);
  EXPECT_NEAR(after.boundary_area, before.boundary_area, 1e-9 * before.boundary_area);
  EXPECT_GT(after.worst_sj, 0.1);
}

TEST(Refine, ASecondOrderMeshIsRefused) {
  mesh::Mesh m = grid(1);
  m.mid = mesh::MidMatrix::Constant(1, 12, 0);
  EXPECT_THROW(mesh::refine_by_thirds(m, std::vector<char>(m.num_nodes(), 0)), InputError);
}

TEST(Refine, FixedNodesAreNeverMarked) {
  const mesh::Mesh m = grid(3);
  const int a = test::grid_node(1, 1, 1, 4, 4), b = test::grid_node(2, 2, 2, 4, 4);
  std::vector<char> fixed(m.num_nodes(), 0);
  fixed[b] = 1;
  // a and b are opposite corners of the middle cell: completion would split it, but b is fixed,
  // so the cut leaves a's corner templates alone.
  const mesh::Refinement r = mesh::refine_by_thirds(m, marks(m, {a, b}), &fixed);
  EXPECT_EQ(r.marked, 1);
  EXPECT_EQ(r.split, 0);
  EXPECT_EQ(r.templates, 8);
  int plain = 0;
  for (char p : r.plain) plain += p;
  EXPECT_EQ(plain, 27 - 8);  // the template pieces are not plain
}
