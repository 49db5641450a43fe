#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(ReadSurface, VolumeMeshIsNotASurface) {
  const std::string path = test::temp_path("volume.k");
  io::write_k(path, test::volume_part(test::mixed_mesh()));
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_surface(path); }, path, 0, "not a surface"));
}

TEST(ReadSurface, QuadsAreSplitAndKeepTheirPatch) {
  const std::string path = test::temp_path("quads.k");
  test::write_text(path, "*KEYWORD\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n*ELEMENT_SHELL\n1,9,1,2,3,4\n*END\n");
  auto s = io::read_surface(path);
  ASSERT_EQ(s.F.rows(), 2);
  EXPECT_EQ(s.patch(0), 9);
  EXPECT_EQ(s.patch(1), 9);
}

TEST(ReadSurface, RockerarmPatchFile) {
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm_indexPatch_hexdom.k");
  HEXDOM_REQUIRE_DATA(path);
  auto s = io::read_surface(path);
  EXPECT_EQ(s.F.rows(), 23410);
  EXPECT_EQ(s.V.rows(), 11705);
}
