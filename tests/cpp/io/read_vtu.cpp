// The .vtu reader on hand-written files: ascii and base64 arrays, several pieces, and a file:line
// error for each malformed input. (VTK's and meshio's own files: tests/cli/test_cli_read_formats.py.)
#include <string>

#include "hexdom/io/vtk.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {

// One piece: a tet on points 0..3 with region `r`; `types` and `extra` let a test break it.
std::string piece(const std::string& conn = "0 1 2 3", const std::string& types = "10", int r = 7) {
  return "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n"
         "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
         "0 0 0 1 0 0 0 1 0 0 0 1\n</DataArray></Points>\n"
         "<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">" + conn + "</DataArray>\n"
         "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>\n"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types + "</DataArray>\n</Cells>\n"
         "<CellData><DataArray type=\"Int32\" Name=\"BlockId\" format=\"ascii\">" + std::to_string(r) +
         "</DataArray></CellData>\n</Piece>\n";
}

std::string file(const std::string& pieces, const std::string& root_attrs = "type=\"UnstructuredGrid\"") {
  return "<?xml version=\"1.0\"?>\n<VTKFile " + root_attrs + ">\n<UnstructuredGrid>\n" + pieces +
         "</UnstructuredGrid>\n</VTKFile>\n";
}

}  // namespace

TEST(ReadVtu, ReadsEveryPieceWithItsRegions) {
  const std::string path = test::temp_path("read_vtu_pieces.vtu");
  test::write_text(path, file(piece() + piece("3 2 1 0", "10", 9)));
  const mesh::Mesh m = io::read_vtu(path);
  ASSERT_EQ(m.num_nodes(), 8);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_EQ(m.region(0), 7);
  EXPECT_EQ(m.region(1), 9);
  EXPECT_EQ(m.cells(1, 0), 7);  // the second piece's points follow the first's
}

TEST(ReadVtu, DecodesBase64WithItsHeaderEncodedApart) {
  // Points as VTK writes binary arrays: base64 of the UInt32 byte count, then base64 of the data.
  const std::string path = test::temp_path("read_vtu_base64.vtu");
  std::string f = file(piece());
  // 12 floats (48 bytes) of the tet as Float32, header 48: "MAAAAA==" then the data.
  const std::string data =
      "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/";
  const std::string ascii = "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  f.replace(f.find(ascii), ascii.size(),
            "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">\nMAAAAA==" + data + "\n");
  test::write_text(path, f);
  const mesh::Mesh m = io::read_vtu(path);
  ASSERT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.V(1, 0), 1.0);
  EXPECT_EQ(m.V(3, 2), 1.0);
  EXPECT_EQ(m.V(2, 0), 0.0);
}

TEST(ReadVtu, LeavesOutTheFacesBesideVolumeCells) {
  // A tet with one of its faces as a triangle (type 5) and a second-order triangle (22): the mesh
  // is the tet; the triangle alone is a surface; the second-order triangle alone is refused.
  const std::string path = test::temp_path("read_vtu_faces.vtu");
  auto with = [](const std::string& conn, const std::string& offsets, const std::string& types, int n) {
    std::string p = piece(conn, types);
    p.replace(p.find("NumberOfCells=\"1\""), 17, "NumberOfCells=\"" + std::to_string(n) + "\"");
    p.replace(p.find(">4</DataArray>"), 14, ">" + offsets + "</DataArray>");
    p.replace(p.find(">7</DataArray>"), 14, ">" + std::string(n == 2 ? "7 0" : "7") + "</DataArray>");
    return file(p);
  };
  test::write_text(path, with("0 1 2 3 0 2 1", "4 7", "10 5", 2));
  mesh::Mesh m = io::read_vtu(path);
  ASSERT_EQ(m.num_cells(), 1);
  EXPECT_EQ(m.type(0), mesh::CellType::Tet);
  test::write_text(path, with("0 2 1", "3", "5", 1));
  m = io::read_vtu(path);
  ASSERT_EQ(m.num_cells(), 1);
  EXPECT_EQ(m.vtk_type(0), 5);
  test::write_text(path, with("0 1 2 3 0 2", "6", "22", 1));
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_vtu(path); }, path, 0, "types 22 and 23) are read only beside volume cells"));
}

TEST(ReadVtu, NamesFileAndLineOfWhatIsWrong) {
  const std::string path = test::temp_path("read_vtu_bad.vtu");
  struct Case { std::string text; long line; std::string what; };
  const std::vector<Case> cases = {
      {"<?xml version=\"1.0\"?>\n<VTKFil>\n", 2, "not a VTK XML file"},
      {file(piece(), "type=\"PolyData\""), 2, "only UnstructuredGrid"},
      {file(piece(), "type=\"UnstructuredGrid\" header_type=\"UInt16\""), 2, "header_type 'UInt16'"},
      {file(piece(), "type=\"UnstructuredGrid\" compressor=\"vtkLZ4DataCompressor\""), 2, "vtkLZ4DataCompressor is not supported"},
      {file(piece("0 1 2 9")), 9, "refers to point 9"},
      {file(piece("0 1 2")), 9, "connectivity: 3 values, expected 4"},
      {file(piece("0 1 2 3", "14")), 11, "unsupported VTK cell type 14"},
      {file(piece("0 1 2 x")), 9, "'x' is not a finite number"},
      {file(piece()).substr(0, 200), 5, "DataArray Points is not closed"},
      {file(piece()).substr(0, file(piece()).size() - 11), 16, "ends before </VTKFile>"},
      {file(""), 0, "no <Piece>"},
  };
  for (const Case& c : cases) {
    test::write_text(path, c.text);
    EXPECT_TRUE(test::ThrowsInputError([&] { io::read_vtu(path); }, path, c.line, c.what)) << c.what;
  }
}
