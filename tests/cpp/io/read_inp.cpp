// The .inp reader: round trips through write_inp (first and second order), an .inp as FreeCAD's and
// Gmsh's writers lay it out, and a file:line error for every kind of malformed input.
#include "hexdom/io/inp.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/mesh/second_order.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(ReadInp, RoundTripsTheMixedMeshAndItsSurfaceCells) {
  const mesh::Mesh m = test::mixed_mesh();
  // Cells come back in the order of their ids (the writer groups them by type); surface cells only
  // from a file without solids.
  const mesh::Mesh vol = test::volume_part(m);
  const std::string path = test::temp_path("read_inp_mixed.inp");
  io::write_inp(path, vol);
  EXPECT_TRUE(test::SameMesh(io::read_inp(path), vol));
  mesh::MeshBuilder b;
  for (int c = 0; c < m.num_cells(); ++c)
    if (!mesh::is_volume(m.type(c))) b.add(m.type(c), m.cells.row(c).data(), m.region(c));
  const mesh::Mesh surf = b.finish(m.V);
  io::write_inp(path, surf);
  EXPECT_TRUE(test::SameMesh(io::read_inp(path), surf));
  // A file with both keeps the solids only.
  io::write_inp(path, m);
  EXPECT_TRUE(test::SameMesh(io::read_inp(path), vol));
}

TEST(ReadInp, RoundTripsASecondOrderMesh) {
  mesh::Mesh m = mesh::add_mid_edge_nodes(test::volume_part(test::mixed_mesh()));
  m.V(m.mid(2, 4), 2) += 0.0625;  // a wedge's mid node off its edge: positions must follow
  const std::string path = test::temp_path("read_inp_quadratic.inp");
  io::write_inp(path, m);
  const mesh::Mesh r = io::read_mesh(path);
  EXPECT_TRUE(test::SameMesh(r, m));
  ASSERT_TRUE(r.second_order());
  EXPECT_EQ(r.mid, m.mid);
}

TEST(ReadInp, ReadsTheLayoutOfOtherWriters) {
  // Lower-case keywords, sparse node ids, a C3D10 continued on a second line, an element set per
  // *ELEMENT, comments, and keywords the reader skips (materials, a step).
  const std::string path = test::temp_path("read_inp_foreign.inp");
  test::write_text(path,
                   "** written by hand like FreeCAD's and Gmsh's writers\n"
                   "*Heading\n free text, with, commas\n"
                   "*Node, NSET=Nall\n"
                   "10, 0, 0, 0\n20, 1, 0, 0\n30, 0, 1, 0\n40, 0, 0, 1\n"
                   "11, 0.5, 0, 0\n21, 0.5, 0.5, 0\n31, 0, 0.5, 0\n41, 0, 0, 0.5\n51, 0.5, 0, 0.5\n61, 0, 0.5, 0.5\n"
                   "*element, type=C3D10, elset=Evolumes\n"
                   "7, 10, 20, 30, 40, 11, 21, 31,\n"
                   "   41, 51, 61\n"
                   "*NSET, NSET=Fixed\n10, 20, 30\n"
                   "*ELSET, ELSET=Copy, GENERATE\n7, 7, 1\n"
                   "*MATERIAL, NAME=Steel\n*ELASTIC\n210000, 0.3\n"
                   "*STEP\n*STATIC\n*END STEP\n");
  const mesh::Mesh r = io::read_inp(path);
  ASSERT_EQ(r.num_nodes(), 10);
  ASSERT_EQ(r.num_cells(), 1);
  ASSERT_TRUE(r.second_order());
  EXPECT_EQ(r.type(0), mesh::CellType::Tet);
  EXPECT_EQ(r.region(0), 1);
  int nodes[20];
  ASSERT_EQ(mesh::cell_nodes(r, 0, nodes), 10);
  for (int j = 0; j < 10; ++j) EXPECT_EQ(nodes[j], j);  // nodes numbered in file order
  EXPECT_DOUBLE_EQ(r.V(9, 2), 0.5);
}

TEST(ReadInp, ReadsAPrismInAbaqusOrderAsVtkOrder) {
  // C3D6 numbers its first face the other way round from VTK's wedge.
  const std::string path = test::temp_path("read_inp_prism.inp");
  test::write_text(path, "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n5,1,0,1\n6,0,1,1\n"
                         "*ELEMENT, TYPE=C3D6, ELSET=REGION_5\n1, 1, 2, 3, 4, 5, 6\n");
  const mesh::Mesh r = io::read_inp(path);
  ASSERT_EQ(r.num_cells(), 1);
  EXPECT_EQ(r.type(0), mesh::CellType::Wedge);
  EXPECT_EQ(r.region(0), 5);
  const std::vector<int> vtk = {0, 2, 1, 3, 5, 4};
  for (int j = 0; j < 6; ++j) EXPECT_EQ(r.cells(0, j), vtk[j]);
}

TEST(ReadInp, AnElementSetMayNameASetOfTheElementLines) {
  // "*ELSET, ELSET=All" listing the set that "*ELEMENT, ..., ELSET=Solid" made, as FreeCAD's and
  // CalculiX users' files do; a REGION_<n> set given by name takes that set's elements.
  const std::string path = test::temp_path("read_inp_set_of_sets.inp");
  test::write_text(path, "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n5,1,1,1\n"
                         "*ELEMENT, TYPE=C3D4, ELSET=Solid\n1, 1, 2, 3, 4\n"
                         "*ELEMENT, TYPE=C3D4, ELSET=Other\n2, 2, 3, 4, 5\n"
                         "*ELSET, ELSET=All\nSolid, Other\n"
                         "*ELSET, ELSET=REGION_3\nSolid\n*ELSET, ELSET=REGION_4\n2\n");
  const mesh::Mesh r = io::read_inp(path);
  ASSERT_EQ(r.num_cells(), 2);
  EXPECT_EQ(r.region(0), 3);
  EXPECT_EQ(r.region(1), 4);
}

TEST(ReadInp, NamesFileAndLineOfWhatIsWrong) {
  const std::string head = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";  // lines 1..5
  struct Case { std::string body; long line; std::string text; };
  const std::vector<Case> cases = {
      {"*ELEMENT, TYPE=C3D27\n1, 1, 2, 3, 4\n", 6, "element type C3D27 is not supported"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 9\n", 7, "element 1 refers to node 9"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3\n*END\n", 8, "element 1 (C3D4) has 3 nodes, expected 4"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4, 1\n", 7, "has 5 nodes, expected 4"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n1, 1, 2, 3, 4\n", 8, "element 1 is defined twice"},
      {"*ELEMENT\n1, 1, 2, 3, 4\n", 6, "*ELEMENT without TYPE="},
      {"*NODE\n2, 5, 5, 5\n", 7, "node 2 is defined twice"},
      {"*NODE\n5, 1, nan, 0\n", 7, "is not a finite number"},
      {"*NODE\n-5, 1, 0, 0\n", 7, "node id '-5' is not a positive integer"},
      {"*INCLUDE, INPUT=more.inp\n", 6, "*INCLUDE is not supported"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*NSET, NSET=A\n1, 77\n", 9, "node 77 of a set is not defined"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*ELSET, ELSET=A\nNOSUCH\n", 9, "neither an id nor a set"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*ELSET, ELSET=A, GENERATE\n1, 100000000000\n", 9, "too long"},
      {"*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*ELEMENT, TYPE=C3D10\n2, 1, 2, 3, 4, 1, 2, 3, 4, 1, 2\n", 9, "mixed order"},
      {"", 0, "no *ELEMENT data"},
  };
  const std::string path = test::temp_path("read_inp_bad.inp");
  for (const Case& c : cases) {
    test::write_text(path, head + c.body);
    EXPECT_TRUE(test::ThrowsInputError([&] { io::read_inp(path); }, path, c.line, c.text)) << c.body;
  }
  test::write_text(path, "** a comment\n1, 0, 0, 0\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_inp(path); }, path, 2, "data line outside a keyword"));
  test::write_text(path, "*HEADING\nnothing\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_inp(path); }, path, 0, "no *NODE data"));
}
