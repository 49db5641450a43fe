#include <cstdint>
#include <cstring>

#include "hexdom/io/surface_formats.h"
#include "io_test_util.h"

using namespace hexdom;
using test::ThrowsInputError;

namespace {
const char* kTwoSolids =
    "solid first\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
    "    endloop\n  endfacet\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0\n      vertex 1 1 0\n      vertex 0 1 0\n"
    "    endloop\n  endfacet\n"
    "endsolid first\n"
    "solid second\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 0 1 0\n      vertex 0 0 1\n"
    "    endloop\n  endfacet\n"
    "endsolid second\n";
}  // namespace

TEST(ReadStl, AsciiMergesVerticesAndNumbersSolids) {
  const std::string path = test::temp_path("two_solids.stl");
  test::write_text(path, kTwoSolids);
  auto s = io::read_stl(path);
  EXPECT_EQ(s.V.rows(), 5);
  ASSERT_EQ(s.F.rows(), 3);
  EXPECT_EQ(s.patch(0), 1);
  EXPECT_EQ(s.patch(2), 2);
  EXPECT_EQ(s.F(0, 1), s.F(1, 0));  // (1,0,0) is one vertex
}

TEST(ReadStl, BinaryRoundTripKeepsTrianglesInSinglePrecision) {
  mesh::SurfaceMesh s;
  s.V.resize(4, 3);
  s.V << 0.1, 0.2, 0.3, 1.0 / 3.0, 0, 0, 0, 2.0 / 3.0, 0, 0, 0, 1e-3;
  s.F.resize(2, 3);
  s.F << 0, 1, 2, 0, 2, 3;
  s.patch = Eigen::VectorXi::Constant(2, 7);
  const std::string path = test::temp_path("round_trip.stl");
  io::write_stl(path, s);
  auto r = io::read_stl(path);
  ASSERT_EQ(r.F.rows(), 2);
  ASSERT_EQ(r.V.rows(), 4);
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        EXPECT_EQ(r.V(r.F(t, k), d), static_cast<double>(static_cast<float>(s.V(s.F(t, k), d))));
}

TEST(ReadStl, TruncatedAsciiNamesLastLine) {
  const std::string path = test::temp_path("truncated.stl");
  test::write_text(path, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_stl(path); }, path, 5, "file ends inside a facet"));
}

TEST(ReadStl, BadNumberNamesLine) {
  const std::string path = test::temp_path("bad_number.stl");
  test::write_text(path, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_stl(path); }, path, 5, "'zero' is not a finite number"));
}

TEST(ReadStl, TruncatedBinaryIsRejected) {
  std::string data(80, ' ');
  uint32_t n = 2;
  data.append(reinterpret_cast<const char*>(&n), 4);
  data.append(50, '\0');  // one of two triangles
  const std::string path = test::temp_path("truncated_binary.stl");
  test::write_text(path, data);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_stl(path); }, path, 1, "not an STL file"));
}

TEST(ReadStl, NonFiniteBinaryCoordinateIsRejected) {
  std::string data(80, ' ');
  uint32_t n = 1;
  data.append(reinterpret_cast<const char*>(&n), 4);
  float rec[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0};
  data.append(reinterpret_cast<const char*>(rec), 48);
  data.append(2, '\0');
  const std::string path = test::temp_path("inf_binary.stl");
  test::write_text(path, data);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_stl(path); }, path, 0, "triangle 1 has a non-finite coordinate"));
}
