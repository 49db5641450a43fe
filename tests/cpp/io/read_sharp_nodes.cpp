#include "hexdom/io/k_file.h"
#include "io_test_util.h"

using namespace hexdom;

TEST(ReadSharpNodes, RockerarmFileWithCrlf) {
  const std::string path = test::data_path("hexdom/rockerarm/sharp.txt");
  HEXDOM_REQUIRE_DATA(path);
  auto nodes = io::read_sharp_nodes(path);
  EXPECT_GT(nodes.size(), 100u);
  for (int n : nodes) {
    EXPECT_GE(n, 0);
    EXPECT_LT(n, 5110);  // nodes of rockerarm's hex mesh
  }
}

TEST(ReadSharpNodes, LastIntegerOfEachLine) {
  const std::string path = test::temp_path("sharp.txt");
  test::write_text(path, "0 1.5 2.5 3.5 17\r\n\r\n1 0 0 0 4\r\n");
  EXPECT_EQ(io::read_sharp_nodes(path), (std::vector<int>{17, 4}));
  test::write_text(path, "0 1 2 3 17\n1 0 0 0 four\n");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::read_sharp_nodes(path); }, path, 2, "0-based node index"));
}
