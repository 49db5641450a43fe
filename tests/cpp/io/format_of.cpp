#include "hexdom/io/mesh_io.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(FormatOf, ExtensionsAreCaseInsensitive) {
  EXPECT_EQ(io::format_of("a/b.K"), io::Format::K);
  EXPECT_EQ(io::format_of("b.key"), io::Format::K);
  EXPECT_EQ(io::format_of("b.dyn"), io::Format::K);
  EXPECT_EQ(io::format_of("x.y/b.VTK"), io::Format::Vtk);
  EXPECT_EQ(io::format_of("b.vtu"), io::Format::Vtu);
  EXPECT_EQ(io::format_of("b.inp"), io::Format::Inp);
  EXPECT_EQ(io::format_of("b.Stl"), io::Format::Stl);
  EXPECT_EQ(io::format_of("b.obj"), io::Format::Obj);
}

TEST(FormatOf, UnknownExtensionNamesThePath) {
  for (const std::string path : {"mesh.xyz", "mesh", "dir.vtk/mesh", "mesh.vtk.bak"})
    EXPECT_TRUE(test::ThrowsInputError([&] { io::format_of(path); }, path, 0, "unknown file format")) << path;
}
