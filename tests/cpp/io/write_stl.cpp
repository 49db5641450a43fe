#include <fstream>

#include "hexdom/io/surface_formats.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(WriteStl, WritesBinaryWithUnitNormals) {
  mesh::SurfaceMesh s;
  s.V.resize(3, 3);
  s.V << 0, 0, 0, 2, 0, 0, 0, 2, 0;
  s.F.resize(1, 3);
  s.F << 0, 1, 2;
  const std::string path = test::temp_path("normal.stl");
  io::write_stl(path, s);
  std::ifstream in(path, std::ios::binary);
  char header[80];
  uint32_t n = 0;
  float rec[12];
  in.read(header, 80);
  in.read(reinterpret_cast<char*>(&n), 4);
  in.read(reinterpret_cast<char*>(rec), 48);
  ASSERT_TRUE(in);
  EXPECT_EQ(n, 1u);
  EXPECT_EQ(rec[0], 0.0f);
  EXPECT_EQ(rec[1], 0.0f);
  EXPECT_EQ(rec[2], 1.0f);
  EXPECT_EQ(std::filesystem::file_size(path), 84u + 50u);
}
