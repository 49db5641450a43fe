#include <fstream>
#include <sstream>

#include "hexdom/io/vtk.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(WriteVtk, AsciiAndBinaryHoldTheSameMesh) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string a = test::temp_path("same_ascii.vtk"), b = test::temp_path("same_binary.vtk");
  io::write_vtk(a, m, false);
  io::write_vtk(b, m, true);
  EXPECT_TRUE(test::SameMesh(io::read_vtk(a), io::read_vtk(b)));
  EXPECT_NE(slurp(b).find("BINARY\n"), std::string::npos);
}

TEST(WriteVtk, UsesNativeWedgeAndTetTypes) {
  const std::string path = test::temp_path("native_types.vtk");
  io::write_vtk(path, test::mixed_mesh(), false);
  const std::string text = slurp(path);
  EXPECT_NE(text.find("CELL_TYPES 6\n12\n12\n13\n10\n5\n9\n"), std::string::npos) << text;
  EXPECT_NE(text.find("CELLS 6 39\n"), std::string::npos);
  EXPECT_NE(text.find("SCALARS region int 1\n"), std::string::npos);
}

TEST(WriteVtk, ReplacesAnExistingFileWithoutTemporaries) {
  const std::string path = test::temp_path("replace_me.vtk");
  test::write_text(path, "old");
  io::write_vtk(path, test::mixed_mesh(), true);
  EXPECT_TRUE(test::SameMesh(io::read_vtk(path), test::mixed_mesh()));
  EXPECT_EQ(test::files_starting_with(path), 1);
}
