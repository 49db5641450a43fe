#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

#include "hexdom/io/vtk.h"
#include "io_test_util.h"

using namespace hexdom;
using mesh::CellType;
using test::ThrowsInputError;

namespace {

// One unit hex: lines 1-4 header, 5 POINTS, 6-13 points, 14 CELLS, 15 the cell, 16 CELL_TYPES, 17 type.
std::string one_hex(const std::string& cell = "8 0 1 2 3 4 5 6 7", const std::string& type = "12",
                    const std::string& point6 = "1 1 1", const std::string& header3 = "ASCII",
                    const std::string& dataset = "UNSTRUCTURED_GRID") {
  return "# vtk DataFile Version 3.0\nunit hex\n" + header3 + "\nDATASET " + dataset +
         "\nPOINTS 8 float\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n" + point6 + "\n0 1 1\nCELLS 1 " +
         std::to_string(1 + std::count(cell.begin(), cell.end(), ' ')) + "\n" + cell + "\nCELL_TYPES 1\n" + type + "\n";
}

void put_be(std::string& s, const void* p, size_t w) {
  unsigned char b[8];
  std::memcpy(b, p, w);
  for (size_t i = 0; i < w; ++i) s += static_cast<char>(b[w - 1 - i]);
}

// Binary one-hex file: header lines 1-5, point bytes on line 6, CELLS line 7, cell bytes line 8,
// CELL_TYPES line 9, type bytes line 10.
std::string binary_hex(double bad = 0.0, int32_t last_node = 7) {
  std::string s = "# vtk DataFile Version 4.2\nbinary\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n";
  const double P[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, bad + 1}};
  for (const auto& p : P)
    for (double x : p) put_be(s, &x, 8);
  s += "\nCELLS 1 9\n";
  for (int32_t v : {8, 0, 1, 2, 3, 4, 5, 6}) put_be(s, &v, 4);
  put_be(s, &last_node, 4);
  s += "\nCELL_TYPES 1\n";
  int32_t t = 12;
  put_be(s, &t, 4);
  return s + "\n";
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = test::temp_path(name);
  test::write_text(path, text);
  return path;
}

}  // namespace

TEST(ReadVtk, AsciiRoundTripKeepsCells) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string path = test::temp_path("ascii_round_trip.vtk");
  io::write_vtk(path, m, false);
  EXPECT_TRUE(test::SameMesh(io::read_vtk(path), m));
}

TEST(ReadVtk, BinaryRoundTripKeepsCells) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string path = test::temp_path("binary_round_trip.vtk");
  io::write_vtk(path, m, true);
  EXPECT_TRUE(test::SameMesh(io::read_vtk(path), m));
}

TEST(ReadVtk, ReadsVersion51OffsetsLayout) {
  const std::string path = write("v51.vtk",
                                 "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                                 "POINTS 5 double\n0 0 0 1 0 0 0 1 0\n0 0 1 1 1 1\n"
                                 "CELLS 3 7\nOFFSETS vtktypeint64\n0 4 7\nCONNECTIVITY vtktypeint64\n0 1 2 3\n1 2 4\n"
                                 "CELL_TYPES 2\n10\n5\n\nCELL_DATA 2\nFIELD FieldData 1\nregion 1 2 int\n7 8\n");
  auto m = io::read_vtk(path);
  ASSERT_EQ(m.num_cells(), 2);
  EXPECT_EQ(m.type(0), CellType::Tet);
  EXPECT_EQ(m.type(1), CellType::Triangle);
  EXPECT_EQ(m.region(0), 7);
  EXPECT_EQ(m.region(1), 8);
  EXPECT_EQ(m.cells(1, 2), 4);
}

TEST(ReadVtk, OriginalPrismsAsDegenerateHexesBecomeWedges) {
  const std::string path = write("degenerate_hex.vtk", one_hex("8 0 1 2 2 4 5 6 6"));
  auto m = io::read_vtk(path);
  ASSERT_EQ(m.num_cells(), 1);
  EXPECT_EQ(m.type(0), CellType::Wedge);
  EXPECT_EQ(m.cells.row(0).head(6), (Eigen::Matrix<int, 1, 6>() << 0, 2, 1, 4, 6, 5).finished());
}

TEST(ReadVtk, RegionComesFromCellScalars) {
  const std::string path = write("region.vtk", one_hex() + "CELL_DATA 1\nSCALARS other float\nLOOKUP_TABLE default\n9\n"
                                                            "SCALARS BlockId int 1\nLOOKUP_TABLE default\n4\n");
  EXPECT_EQ(io::read_vtk(path).region(0), 4);
}

TEST(ReadVtk, ReferenceHexMeshReads) {
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm3_hex.vtk");
  HEXDOM_REQUIRE_DATA(path);
  auto m = io::read_vtk(path);
  EXPECT_EQ(m.num_nodes(), 5110);
  EXPECT_EQ(m.count(CellType::Hex), 3840);
}

TEST(ReadVtk, FirstLineMustBeTheVtkHeader) {
  const std::string path = write("not_vtk.vtk", "hello\nworld\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 1, "not a legacy VTK file"));
}

TEST(ReadVtk, BadModeNamesLineThree) {
  const std::string path = write("mode.vtk", one_hex("8 0 1 2 3 4 5 6 7", "12", "1 1 1", "ASCIX"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 3, "ASCII or BINARY"));
}

TEST(ReadVtk, OtherDatasetNamesLineFour) {
  const std::string path = write("dataset.vtk", one_hex("8 0 1 2 3 4 5 6 7", "12", "1 1 1", "ASCII", "STRUCTURED_POINTS"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 4, "structured_points"));
}

TEST(ReadVtk, TruncatedPointsNamesLastLine) {
  const std::string full = one_hex();
  const std::string path = write("truncated_points.vtk", full.substr(0, full.find("1 1 0") + 3));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 8, "file ends after 8 of 24 values (truncated?)"));
}

TEST(ReadVtk, TruncatedCellsNamesLastLine) {
  const std::string full = one_hex();
  const std::string path = write("truncated_cells.vtk", full.substr(0, full.find("4 5 6 7")));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 15, "truncated"));
}

TEST(ReadVtk, NonFinitePointNamesLine) {
  const std::string path = write("nan_point.vtk", one_hex("8 0 1 2 3 4 5 6 7", "12", "1 nan 1"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 12, "'nan' is not a finite number"));
}

TEST(ReadVtk, MissingPointNamesTheCellLine) {
  const std::string path = write("missing_point.vtk", one_hex("8 0 1 2 3 4 5 6 8"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 15, "cell 0 refers to point 8, but there are 8 points"));
}

TEST(ReadVtk, UnsupportedCellTypeNamesTheTypeLine) {
  const std::string path = write("pyramid_type.vtk", one_hex("8 0 1 2 3 4 5 6 7", "14"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 17, "unsupported VTK cell type 14"));
}

TEST(ReadVtk, WrongNodeCountNamesTheCellLine) {
  const std::string path = write("node_count.vtk", one_hex("4 0 1 2 3"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 15, "has 4 nodes, expected 8"));
}

TEST(ReadVtk, FractionalIndexIsRejected) {
  const std::string path = write("fraction.vtk", one_hex("8 0 1 2 3 4 5 6.5 7"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 15, "'6.5' is not a valid integer"));
}

TEST(ReadVtk, CorruptCountIsAnInputErrorNotAnAllocation) {
  std::string text = one_hex();
  text.replace(text.find("POINTS 8"), 8, "POINTS 900000000000000000");
  const std::string path = write("huge_count.vtk", text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 5, "larger than the file can hold"));
}

TEST(ReadVtk, OffsetsOutsideConnectivityAreRejected) {
  const std::string path = write("bad_offsets.vtk",
                                 "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                                 "0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 2 4\nOFFSETS vtktypeint64\n2 6\n"
                                 "CONNECTIVITY vtktypeint64\n0 1 2 3\nCELL_TYPES 1\n10\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 12, "OFFSETS: offset 0 is 2"));
}

TEST(ReadVtk, RegionOutOfIntRangeIsRejected) {
  const std::string path = write("huge_region.vtk", one_hex() + "CELL_DATA 1\nSCALARS region double\nLOOKUP_TABLE default\n1e300\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 21, "region id 1.0000000000000001e+300"));
}

TEST(ReadVtk, BinaryFileReads) {
  const std::string path = write("binary_ok.vtk", binary_hex());
  auto m = io::read_vtk(path);
  ASSERT_EQ(m.num_cells(), 1);
  EXPECT_EQ(m.type(0), CellType::Hex);
  EXPECT_EQ(m.V(7, 2), 1.0);
}

TEST(ReadVtk, TruncatedBinaryNamesTheDataLine) {
  const std::string path = write("binary_truncated.vtk", binary_hex().substr(0, 150));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 6, "(truncated?)"));
}

TEST(ReadVtk, NonFiniteBinaryValueIsRejected) {
  const std::string path = write("binary_nan.vtk", binary_hex(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 6, "value 23 is not finite"));
}

TEST(ReadVtk, BinaryBadIndexNamesTheCellDataLine) {
  const std::string path = write("binary_index.vtk", binary_hex(0.0, 99));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_vtk(path); }, path, 8, "refers to point 99"));
}
