#include "hexdom/io/mesh_io.h"
#include "io_test_util.h"

using namespace hexdom;
using test::ThrowsInputError;

TEST(WriteMesh, EveryFormatWritesAndReadableOnesReadBack) {
  const mesh::Mesh m = test::mixed_mesh();
  for (const char* ext : {"k", "vtk", "vtu", "inp"}) {
    const std::string path = test::temp_path(std::string("every_format.") + ext);
    std::filesystem::remove(path);
    io::write_mesh(path, m);
    EXPECT_GT(std::filesystem::file_size(path), 100u) << ext;
  }
  io::WriteOptions binary;
  binary.binary = true;
  const std::string path = test::temp_path("every_format_binary.vtk");
  io::write_mesh(path, m, binary);
  EXPECT_TRUE(test::SameMesh(io::read_mesh(path), m));
}

TEST(WriteMesh, UnknownExtensionLeavesNoFile) {
  const std::string path = test::temp_path("unknown_ext.xyz");
  std::filesystem::remove(path);
  EXPECT_TRUE(ThrowsInputError([&] { io::write_mesh(path, test::mixed_mesh()); }, path, 0, "unknown file format"));
  EXPECT_EQ(test::files_starting_with(path), 0);
}

TEST(WriteMesh, VolumeCellsToASurfaceFormatLeaveNoFile) {
  for (const char* ext : {"stl", "obj"}) {
    const std::string path = test::temp_path(std::string("volume_as_surface.") + ext);
    std::filesystem::remove(path);
    EXPECT_TRUE(ThrowsInputError([&] { io::write_mesh(path, test::mixed_mesh()); }, path, 0,
                                 "cannot write volume cells to a surface format"));
    EXPECT_EQ(test::files_starting_with(path), 0) << ext;
  }
}

TEST(WriteMesh, SurfaceFormatsTakeTrianglesAndQuads) {
  mesh::MeshBuilder b;
  const int quad[4] = {0, 1, 2, 3};
  b.add(mesh::CellType::Quad, quad, 3);
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  const mesh::Mesh m = b.finish(V);
  const std::string path = test::temp_path("quad.obj");
  io::write_mesh(path, m);
  auto s = io::read_surface(path);
  EXPECT_EQ(s.F.rows(), 2);
  EXPECT_EQ(s.patch(0), 3);
}

TEST(WriteMesh, MissingDirectoryIsAnInputError) {
  const std::string path = test::temp_path("missing_dir/out.vtk");
  EXPECT_TRUE(ThrowsInputError([&] { io::write_mesh(path, test::mixed_mesh()); }, path, 0, "cannot create file"));
}
