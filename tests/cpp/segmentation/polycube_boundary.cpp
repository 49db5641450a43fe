#include "hexdom/segmentation/polycube_boundary.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "seg_test_util.h"

using namespace hexdom;

TEST(PolycubeBoundary, BoxHasEightCornersTwelveEdgesSixQuads) {
  auto s = test::box_surface(2, 1, 3, 2);
  auto b = segmentation::polycube_boundary(s);
  EXPECT_EQ(b.corner_vertices.size(), 8u);
  EXPECT_EQ(b.edges.size(), 12u);
  ASSERT_EQ(b.faces.size(), 6u);
  EXPECT_TRUE(std::is_sorted(b.corner_vertices.begin(), b.corner_vertices.end()));
  for (int i = 0; i < 8; ++i) EXPECT_EQ(b.corners.row(i), s.V.row(b.corner_vertices[i]));
  for (const auto& e : b.edges) {
    EXPECT_EQ(e.path.front(), b.corner_vertices[e.corners[0]]);
    EXPECT_EQ(e.path.back(), b.corner_vertices[e.corners[1]]);
    // A box edge is straight: its length is 1, 2 or 3 voxels.
    const double len = (b.corners.row(e.corners[0]) - b.corners.row(e.corners[1])).norm();
    EXPECT_TRUE(std::abs(len - 1) < 1e-12 || std::abs(len - 2) < 1e-12 || std::abs(len - 3) < 1e-12) << len;
    EXPECT_NE(e.patches[0], e.patches[1]);
  }
  for (const auto& f : b.faces) {
    ASSERT_EQ(f.corners.size(), 4u);
    // Counter-clockwise seen from outside: the quad's normal is the face's axis.
    Eigen::Vector3d p0 = b.corners.row(f.corners[0]), p1 = b.corners.row(f.corners[1]), p2 = b.corners.row(f.corners[2]);
    Eigen::Vector3d n = (p1 - p0).cross(p2 - p0).normalized();
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    axis((f.id - 1) / 2) = f.id % 2 ? 1 : -1;
    EXPECT_NEAR(n.dot(axis), 1.0, 1e-12) << "patch " << f.patch;
  }
  auto shells = segmentation::polycube_shells(b);
  EXPECT_EQ(shells.count(mesh::CellType::Quad), 6);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(shells.region(c), c + 1);
}

TEST(PolycubeBoundary, PatchWithFiveCornersIsAGeometryError) {
  auto s = test::l_shape();
  try {
    segmentation::polycube_boundary(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("6 corners"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hexdom check"), std::string::npos) << e.what();
  }
}

TEST(PolycubeBoundary, WritesCornerFileAndEdgesVtk) {
  auto s = test::box_surface(1, 1, 1, 2);
  auto b = segmentation::polycube_boundary(s);
  const std::string corners = test::temp_path("box_corners.txt"), edges = test::temp_path("box_edges.vtk");
  segmentation::write_corner_file(corners, b);
  std::ifstream in(corners);
  int v, n = 0;
  double x, y, z;
  while (in >> v >> x >> y >> z) {
    EXPECT_EQ(v, b.corner_vertices[n]);
    EXPECT_EQ(Eigen::RowVector3d(x, y, z), s.V.row(v));
    ++n;
  }
  EXPECT_EQ(n, 8);
  segmentation::write_edges_vtk(edges, s, b);
  std::ifstream vin(edges);
  std::stringstream text;
  text << vin.rdbuf();
  EXPECT_NE(text.str().find("DATASET POLYDATA"), std::string::npos);
  EXPECT_NE(text.str().find("VERTICES 8 16"), std::string::npos);
  EXPECT_NE(text.str().find("LINES 12 "), std::string::npos);
}

// ---- the paper's patch files against the original's initial polycubes ----

class PolycubePaperFiles : public ::testing::TestWithParam<test::PaperPatches> {};

TEST_P(PolycubePaperFiles, SameCornersAndShellsAsTheOriginal) {
  const auto& m = GetParam();
  const std::string patches = test::data_path("hexdom/" + m.model + "/" + m.patches);
  const std::string initial = test::data_path("hexdom/" + m.model + "/" + m.initial);
  HEXDOM_REQUIRE_DATA(patches);
  HEXDOM_REQUIRE_DATA(initial);
  auto b = segmentation::polycube_boundary(io::read_surface(patches));
  auto shells = segmentation::polycube_shells(b);
  auto original = io::read_k(initial).mesh;
  ASSERT_EQ(shells.num_nodes(), original.num_nodes());
  ASSERT_EQ(shells.num_cells(), original.num_cells());
  // The original printed coordinates with 6 significant digits: ours, printed so, are its values.
  for (int i = 0; i < shells.num_nodes(); ++i)
    for (int k = 0; k < 3; ++k) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%g", shells.V(i, k));
      EXPECT_NEAR(std::stod(buf), original.V(i, k), 1e-9) << "corner " << i + 1;
    }
  // Same shells: same corners in the same order, same type.
  for (int c = 0; c < shells.num_cells(); ++c) {
    EXPECT_EQ(shells.types(c), original.types(c)) << "shell " << c + 1;
    EXPECT_EQ(shells.cells.row(c), original.cells.row(c)) << "shell " << c + 1;
  }
}

INSTANTIATE_TEST_SUITE_P(PaperModels, PolycubePaperFiles, ::testing::ValuesIn(test::paper_patch_files()),
                         [](const auto& info) { return info.param.model; });
