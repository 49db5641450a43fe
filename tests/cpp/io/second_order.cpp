// Second-order meshes through the writers and the VTK reader.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hexdom/io/inp.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/vtk.h"
#include "hexdom/mesh/second_order.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The volume cells of mixed_mesh() (two hexes, a wedge, a tet), second order, one mid-edge node
/// moved off its edge so that positions matter.
mesh::Mesh quadratic_mesh() {
  mesh::Mesh m = mesh::add_mid_edge_nodes(test::volume_part(test::mixed_mesh()));
  m.V(m.mid(0, 0), 1) -= 0.125;
  return m;
}

}  // namespace

TEST(SecondOrderIo, LegacyVtkRoundTripsAsciiAndBinary) {
  const mesh::Mesh m = quadratic_mesh();
  for (bool binary : {false, true}) {
    const std::string path = test::temp_path(binary ? "quadratic_binary.vtk" : "quadratic_ascii.vtk");
    io::write_vtk(path, m, binary);
    const mesh::Mesh r = io::read_vtk(path);
    EXPECT_TRUE(test::SameMesh(r, m));
    ASSERT_TRUE(r.second_order());
    EXPECT_TRUE(r.mid == m.mid);
  }
  const std::string text = slurp(test::temp_path("quadratic_ascii.vtk"));
  EXPECT_NE(text.find("CELL_TYPES 4\n25\n25\n26\n24\n"), std::string::npos) << text;
  EXPECT_NE(text.find("CELLS 4 69\n"), std::string::npos);  // 4 counts + 20 + 20 + 15 + 10 nodes
}

TEST(SecondOrderIo, InpWritesC3D20C3D15C3D10WithContinuationLines) {
  const mesh::Mesh m = quadratic_mesh();
  const std::string path = test::temp_path("quadratic.inp");
  io::write_inp(path, m);
  const std::string text = slurp(path);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D20\n"), std::string::npos);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D15\n"), std::string::npos);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D10\n"), std::string::npos);
  EXPECT_EQ(text.find("C3D8"), std::string::npos);
  // Hex 1: its 8 corners and 7 mid-edge nodes, then a line with the other 5 (16 entries at most).
  int nodes[20];
  mesh::cell_nodes(m, 0, nodes);
  std::string first = "1";
  for (int j = 0; j < 15; ++j) first += ", " + std::to_string(nodes[j] + 1);
  std::string second;
  for (int j = 15; j < 20; ++j) second += (j > 15 ? ", " : "") + std::to_string(nodes[j] + 1);
  EXPECT_NE(text.find(first + ",\n" + second + "\n"), std::string::npos) << text;
  // The wedge: corners a c b d f e (as C3D6), then its mid-edge nodes on the same edges.
  mesh::cell_nodes(m, 2, nodes);
  const int order[15] = {0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13};
  std::string wedge = "3";
  for (int j = 0; j < 15; ++j) wedge += ", " + std::to_string(nodes[order[j]] + 1);
  EXPECT_NE(text.find(wedge + "\n"), std::string::npos) << text;
}

TEST(SecondOrderIo, LsDynaRefusesSecondOrderAndWritesNothing) {
  const std::string path = test::temp_path("quadratic.k");
  std::filesystem::remove(path);
  EXPECT_TRUE(test::ThrowsInputError([&] { io::write_mesh(path, quadratic_mesh()); }, path, 0, "first-order solids only"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(SecondOrderIo, VtkReaderRefusesMixedOrdersAndShortCells) {
  const std::string mixed = test::temp_path("mixed_order.vtk");
  test::write_text(mixed,
                   "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 11 double\n"
                   "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.5 0 0\n0.5 0.5 0\n0 0.5 0\n0 0 0.5\n0.5 0 0.5\n0 0.5 0.5\n1 1 1\n"
                   "CELLS 2 16\n10 0 1 2 3 4 5 6 7 8 9\n4 1 2 3 10\nCELL_TYPES 2\n24\n10\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_vtk(mixed); }, mixed, 22, "mixed order"));
  const std::string shortcell = test::temp_path("short_tet10.vtk");
  test::write_text(shortcell,
                   "# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                   "0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n24\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_vtk(shortcell); }, shortcell, 11, "expected 10"));
}
