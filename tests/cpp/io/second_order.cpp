// Second-order meshes through the writers and the VTK reader.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hexdom/io/inp.h"
#include "hexdom/io/k_file.h"
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

TEST(SecondOrderIo, LsDynaRefusesFifteenNodeWedgesAndWritesNothing) {
  const std::string path = test::temp_path("quadratic.k");
  std::filesystem::remove(path);
  EXPECT_TRUE(test::ThrowsInputError([&] { io::write_mesh(path, quadratic_mesh()); }, path, 0,
                                     "no 15-node pentahedron, and 1 of the cells are 15-node wedges (the first: cell 3)"));
  EXPECT_FALSE(std::filesystem::exists(path));
}

// 20-node hexes and 10-node tets: *ELEMENT_SOLID_H20 and the ten-node format, in the cells' order,
// read back as the same second-order mesh.
TEST(SecondOrderIo, LsDynaWritesAndReadsTwentyNodeHexesAndTenNodeTets) {
  const mesh::Mesh mixed = test::volume_part(test::mixed_mesh());
  mesh::MeshBuilder b;
  for (int c : {0, 3, 1})  // hex, tet, hex: three keyword blocks
    b.add(mixed.type(c), mixed.cells.row(c).data(), mixed.region(c));
  mesh::Mesh m = mesh::add_mid_edge_nodes(b.finish(mixed.V));
  m.V(m.mid(0, 0), 1) -= 0.125;
  const std::string path = test::temp_path("quadratic_hex_tet.k");
  io::write_mesh(path, m);
  const std::string text = slurp(path);
  EXPECT_NE(text.find("*ELEMENT_SOLID_H20\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELEMENT_SOLID (ten nodes format)\n"), std::string::npos) << text;
  // Element 2 (the tet): "eid pid", then its 10 nodes on one card.
  int nodes[20];
  mesh::cell_nodes(m, 1, nodes);
  std::string card;
  for (int j = 0; j < 10; ++j) {
    char field[16];
    std::snprintf(field, sizeof field, "%8d", nodes[j] + 1);
    card += field;
  }
  EXPECT_NE(text.find("       2       3\n" + card + "\n"), std::string::npos) << text;
  const io::KFile k = io::read_k(path);
  EXPECT_TRUE(test::SameMesh(k.mesh, m));
  ASSERT_TRUE(k.mesh.second_order());
  EXPECT_TRUE(k.mesh.mid == m.mid);
  EXPECT_EQ(k.element_ids, (Eigen::VectorXi(3) << 1, 2, 3).finished());
}

TEST(SecondOrderIo, LsDynaReaderNamesTheLineOfAShortNodeCard) {
  const std::string path = test::temp_path("short_h20.k");
  test::write_text(path,
                   "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n*ELEMENT_SOLID_H20\n       7       1\n"
                   "       1       2       3       4       5       6       7       8       9      10\n"
                   "      11      12\n*END\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_k(path); }, path, 8, "element 7: a card of 10 node ids expected, found 2"));
  const std::string mixed = test::temp_path("mixed_order.k");
  test::write_text(mixed,
                   "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n5,.5,0,0\n6,.5,.5,0\n7,0,.5,0\n8,0,0,.5\n"
                   "9,.5,0,.5\n10,0,.5,.5\n11,1,1,1\n*ELEMENT_SOLID\n       1       1\n"
                   "       1       2       3       4       5       6       7       8       9      10\n"
                   "       2       1       1       2       3      11      11      11      11      11\n*END\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_k(mixed); }, mixed, 17, "order"));
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
