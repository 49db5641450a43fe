#include "hexdom/io/k_file.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/io/vtk.h"
#include "io_test_util.h"

using namespace hexdom;
using test::ThrowsInputError;

TEST(ReadMesh, KeywordFileNamedVtkIsSniffed) {
  const std::string path = test::data_path("hexdom/fertility/fertility_hex.vtk");
  HEXDOM_REQUIRE_DATA(path);
  auto m = io::read_mesh(path);
  EXPECT_EQ(m.count(mesh::CellType::Hex), 3712);
  EXPECT_EQ(m.num_nodes(), 5060);
}

TEST(ReadMesh, VtkFileNamedKIsSniffed) {
  const std::string path = test::temp_path("really_vtk.k");
  io::write_vtk(path, test::mixed_mesh());
  EXPECT_TRUE(test::SameMesh(io::read_mesh(path), test::mixed_mesh()));
}

TEST(ReadMesh, SameMeshFromEveryFormat) {
  const mesh::Mesh m = test::volume_part(test::mixed_mesh());
  const std::string k = test::temp_path("every.k"), v = test::temp_path("every.vtk");
  io::write_k(k, m);
  io::write_vtk(v, m, true);
  EXPECT_TRUE(test::SameMesh(io::read_mesh(k), io::read_mesh(v)));
}

TEST(ReadMesh, EveryWrittenFormatReadsBack) {
  const mesh::Mesh m = test::volume_part(test::mixed_mesh());
  for (const char* ext : {"k", "vtk", "vtu", "inp"}) {
    const std::string path = test::temp_path(std::string("every_format.") + ext);
    io::write_mesh(path, m);
    EXPECT_TRUE(test::SameMesh(io::read_mesh(path), m)) << ext;
  }
}

TEST(ReadMesh, UnknownExtensionNamesPath) {
  const std::string path = test::temp_path("mesh.unv");
  test::write_text(path, "    -1\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_mesh(path); }, path, 0, "unknown file format '.unv'"));
}

TEST(ReadMesh, MissingFileNamesPath) {
  const std::string path = test::temp_path("does_not_exist.k");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_mesh(path); }, path, 0, "cannot open file"));
}
