// The octree of the overlay path: cells split in 27 where asked, conforming through the
// 3-refinement templates. Checked on the mesh itself: every face is shared by two cells or lies on
// the box (no hanging node), the cells fill the box's volume exactly, none is inverted.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hexdom/mesh/cell_faces.h"
#include "hexdom/overlay/octree.h"
#include "hexdom/quality/metrics.h"

using namespace hexdom;

namespace {

overlay::Grid box_grid(int nx, int ny, int nz, double h) {
  overlay::Grid g;
  g.nx = nx;
  g.ny = ny;
  g.nz = nz;
  g.h = Eigen::Vector3d::Constant(h);
  g.origin = Eigen::Vector3d(-1.0, 2.0, 0.5);
  return g;
}

struct Checked {
  double volume = 0, worst_sj = 2;
  int interior_boundary_faces = 0;
};

// The mesh's volume, worst scaled Jacobian, and its boundary faces that are not on the box.
Checked check(const overlay::OctreeMesh& o, const overlay::Grid& g) {
  Checked r;
  const mesh::Mesh& m = o.mesh;
  for (int c = 0; c < m.num_cells(); ++c) {
    const quality::CellPoints P = quality::cell_points(m, c);
    r.volume += quality::volume(mesh::CellType::Hex, P);
    r.worst_sj = std::min(r.worst_sj, quality::signed_sj(mesh::CellType::Hex, P));
  }
  const Eigen::Vector3d lo = g.origin, hi = g.origin + g.h.cwiseProduct(Eigen::Vector3d(g.nx, g.ny, g.nz));
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(m)) {
    bool on_box = false;
    for (int a = 0; a < 3 && !on_box; ++a)
      for (double side : {lo(a), hi(a)}) {
        bool all = true;
        for (int n = 0; n < f.n; ++n) all = all && std::abs(m.V(f.v[n], a) - side) < 1e-9;
        on_box = on_box || all;
      }
    if (!on_box) ++r.interior_boundary_faces;
  }
  return r;
}

double box_volume(const overlay::Grid& g) { return g.h.prod() * g.nx * g.ny * g.nz; }

}  // namespace

TEST(Octree, NothingAskedGivesTheGrid) {
  const overlay::Grid g = box_grid(3, 4, 2, 0.5);
  const overlay::OctreeMesh o = overlay::octree_mesh(g, 2, [](const overlay::OctreeCell&) { return false; });
  EXPECT_EQ(o.mesh.num_cells(), 24);
  EXPECT_EQ(o.mesh.num_nodes(), 4 * 5 * 3);
  EXPECT_EQ(o.templates, 0);
  const Checked r = check(o, g);
  EXPECT_NEAR(r.volume, box_volume(g), 1e-11 * box_volume(g));
  EXPECT_NEAR(r.worst_sj, 1.0, 1e-12);
}

TEST(Octree, OneSplitCellIsSurroundedByFaceEdgeAndCornerTemplates) {
  // The middle cell of 3 x 3 x 3 split: its 6 face neighbours take the face template (22 hexes),
  // the 12 edge neighbours the edge template (11), the 8 corner neighbours the corner one (4).
  const overlay::Grid g = box_grid(3, 3, 3, 1.0);
  const overlay::OctreeMesh o = overlay::octree_mesh(g, 1, [](const overlay::OctreeCell& c) {
    return c.level == 0 && c.i == 1 && c.j == 1 && c.k == 1;
  });
  EXPECT_EQ(o.templates, 26);
  EXPECT_EQ(o.levels, 1);
  EXPECT_EQ(o.mesh.num_cells(), 27 + 6 * 22 + 12 * 11 + 8 * 4);
  const Checked r = check(o, g);
  EXPECT_EQ(r.interior_boundary_faces, 0);
  EXPECT_NEAR(r.volume, box_volume(g), 1e-11 * box_volume(g));
  EXPECT_GT(r.worst_sj, 0.15);
  RecordProperty("worst_sj", std::to_string(r.worst_sj));
}

TEST(Octree, CellsAlongASphereRefineTwoLevelsConformingly) {
  const overlay::Grid g = box_grid(8, 8, 8, 1.0);
  const Eigen::Vector3d centre = g.origin + Eigen::Vector3d::Constant(4.0);
  const overlay::OctreeMesh o = overlay::octree_mesh(g, 2, [&](const overlay::OctreeCell& c) {
    const Eigen::Vector3d lo = overlay::octree_cell_origin(g, c), size = overlay::octree_cell_size(g, c);
    const double d = (lo + size / 2 - centre).norm();
    return std::abs(d - 2.5) < size.norm();
  });
  EXPECT_EQ(o.levels, 2);
  int finest = 0;
  for (int l : o.level) finest += l == 2;
  EXPECT_GT(finest, 1000);
  const Checked r = check(o, g);
  EXPECT_EQ(r.interior_boundary_faces, 0);
  EXPECT_NEAR(r.volume, box_volume(g), 1e-11 * box_volume(g));
  EXPECT_GT(r.worst_sj, 0.15);
  RecordProperty("worst_sj", std::to_string(r.worst_sj));
}

TEST(Octree, RandomRequestsStayConforming) {
  // Requests with no shape at all (diagonal pairs, lone cells, cells on the box's faces) test the
  // completion and cutting of the marks.
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution ask(0.12);
    const overlay::Grid g = box_grid(5, 4, 6, 0.7);
    const overlay::OctreeMesh o = overlay::octree_mesh(g, 2, [&](const overlay::OctreeCell&) { return ask(rng); });
    const Checked r = check(o, g);
    EXPECT_EQ(r.interior_boundary_faces, 0) << "seed " << seed;
    EXPECT_NEAR(r.volume, box_volume(g), 1e-11 * box_volume(g)) << "seed " << seed;
    EXPECT_GT(r.worst_sj, 0.15) << "seed " << seed;
    EXPECT_GT(o.templates, 0);
  }
}

// A spherical shell of cells asked for in a large grid: the marks made valid split the cells asked
// for and fill the shell's inside, but do not spread beyond the box of the cells asked for (they did,
// over 8,640 of the 13,824 cells, when the completion took the cells in index order).
TEST(Octree, RefinementStaysWithinTheBoxOfWhatIsAsked) {
  const overlay::Grid g = box_grid(24, 24, 24, 1.0);
  const Eigen::Vector3d centre = g.origin + Eigen::Vector3d(8.3, 9.1, 10.7);
  Eigen::Array3i lo = Eigen::Array3i::Constant(1 << 20), hi = Eigen::Array3i::Constant(-1);
  int asked = 0;
  const overlay::OctreeMesh o = overlay::octree_mesh(g, 1, [&](const overlay::OctreeCell& c) {
    const Eigen::Vector3d x = overlay::octree_cell_origin(g, c) + overlay::octree_cell_size(g, c) / 2;
    const bool near = std::abs((x - centre).norm() - 4.0) < 1.0;
    if (near && c.level == 0) {
      ++asked;
      lo = lo.min(Eigen::Array3i(c.i, c.j, c.k));
      hi = hi.max(Eigen::Array3i(c.i, c.j, c.k));
    }
    return near;
  });
  int split = 0, outside = 0;
  for (int c = 0; c < o.mesh.num_cells(); ++c) {
    if (!o.plain[c] || o.level[c] != 1) continue;
    ++split;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < 8; ++i) x += o.mesh.V.row(o.mesh.cells(c, i)).transpose() / 8;
    const Eigen::Array3d cell = ((x - g.origin).array() / g.h.array()).floor();
    outside += (cell < lo.cast<double>()).any() || (cell > hi.cast<double>()).any();
  }
  const int box = (hi - lo + 1).prod();
  EXPECT_GE(split / 27, asked);
  EXPECT_LE(split / 27, box);
  EXPECT_EQ(outside, 0);
  const Checked r = check(o, g);
  EXPECT_EQ(r.interior_boundary_faces, 0);
  EXPECT_NEAR(r.volume, box_volume(g), 1e-9 * box_volume(g));
  EXPECT_GT(r.worst_sj, 0);
}
