#include "hexdom/io/surface_formats.h"
#include "io_test_util.h"

using namespace hexdom;
using test::ThrowsInputError;

TEST(ReadObj, PolygonsNegativeIndicesAndGroups) {
  const std::string path = test::temp_path("groups.obj");
  test::write_text(path,
                   "# comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
                   "f 1/1/1 2/1/1 3/1/1 4/1/1\ng wing\nf -4//1 -2//1 -1//1\ng patch_42\nf 1 2 3\ng wing\nf 2 3 4\n");
  auto s = io::read_obj(path);
  ASSERT_EQ(s.F.rows(), 5);  // the quad is fanned into two triangles
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.patch(0), 0);   // before any group
  EXPECT_EQ(s.patch(2), 1);   // "wing": first named group
  EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.patch(3), 42);  // our own writer's names keep their ids
  EXPECT_EQ(s.patch(4), 1);
}

TEST(ReadObj, MissingVertexNamesLine) {
  const std::string path = test::temp_path("missing_vertex.obj");
  test::write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_obj(path); }, path, 4, "refers to vertex 9"));
}

TEST(ReadObj, BadCoordinateNamesLine) {
  const std::string path = test::temp_path("bad_coordinate.obj");
  test::write_text(path, "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_obj(path); }, path, 2, "'x' is not a finite number"));
}

TEST(ReadObj, FileWithoutFacesIsRejected) {
  const std::string path = test::temp_path("no_faces.obj");
  test::write_text(path, "v 0 0 0\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_obj(path); }, path, 0, "no faces"));
}
