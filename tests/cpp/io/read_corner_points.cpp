#include "hexdom/io/k_file.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(ReadCornerPoints, PrismgenCornerFile) {
  const std::string path = test::data_path("hexdom/rockerarm/prismgen/prism_0000_tri.k_Output_CornerPoints.txt");
  HEXDOM_REQUIRE_DATA(path);
  auto pts = io::read_corner_points(path);
  ASSERT_EQ(pts.size(), 6u);  // a prism has six corners
  for (const auto& c : pts)
    for (double x : c.p) {
      EXPECT_GE(x, 0.0);
      EXPECT_LE(x, 8.0);
    }
}

TEST(ReadCornerPoints, MalformedLineNamesIt) {
  const std::string path = test::temp_path("corners.txt");
  test::write_text(path, "0 0 0 0\n1 8 0 0\n2 0 eight 0\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_corner_points(path); }, path, 3, "'eight' is not a finite number"));
  test::write_text(path, "0 0 0 0\n-1 8 0 0\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_corner_points(path); }, path, 2, "not a non-negative integer"));
}
