#include "hexdom/common/error.h"
#include "hexdom/io/k_file.h"
#include "io_test_util.h"
#include "test_common.h"

using namespace hexdom;
using mesh::CellType;
using test::ThrowsInputError;

namespace {
// A one-hex file: line 1 *KEYWORD, 2 *ELEMENT_SOLID, 3 the hex, 4 *NODE, 5..12 nodes 1..8.
std::string one_hex(const std::string& solid = "       1       1       1       2       3       4       5       6       7       8",
                    const std::string& node7 = "7,1,1,1", const std::string& extra_nodes = "") {
  return "*KEYWORD\n*ELEMENT_SOLID\n" + solid +
         "\n*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n" + node7 + "\n8,0,1,1\n" + extra_nodes +
         "*END\n";
}
}  // namespace

TEST(ReadK, RockerarmStructureHasPaperBlockCounts) {
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm_polycube_withtet.k");
  HEXDOM_REQUIRE_DATA(path);
  auto k = io::read_k(path);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Hex), 60);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Wedge), 11);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Tet), 2);
}

TEST(ReadK, EveryPaperStructureReadsWithPositiveBlocks) {
  for (const auto& model : test::paper_models()) {
    const std::string dir = test::data_path("hexdom/" + model);
    HEXDOM_REQUIRE_DATA(dir);
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.find("withtet.k") == std::string::npos) continue;
      auto k = io::read_k(entry.path().string());
      EXPECT_GT(k.mesh.count(CellType::Tet), 0) << name;
      EXPECT_GT(k.mesh.count(CellType::Wedge), 0) << name;
      for (int c = 0; c < k.mesh.num_cells(); ++c)
        EXPECT_GT(quality::volume(k.mesh.type(c), quality::cell_points(k.mesh, c)), 0) << name << " cell " << c;
    }
  }
}

TEST(ReadK, MissingNodeNamesFileAndLine) {
  const std::string path = test::temp_path("missing_node.k");
  test::write_text(path, "*KEYWORD\n*ELEMENT_SHELL\n1 1 1 2 3 3\n*NODE\n1 0 0 0\n2 1 0 0\n*END\n");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 3, "refers to node 3"));
}

TEST(ReadK, TruncatedNodeSectionNamesTheElementLine) {
  const std::string full = one_hex();
  const std::string path = test::temp_path("truncated.k");
  test::write_text(path, full.substr(0, full.find("6,1,0,1")));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 3, "node 6"));
}

TEST(ReadK, TruncatedElementLineNamesIt) {
  const std::string path = test::temp_path("truncated_element.k");
  test::write_text(path, "*KEYWORD\n*ELEMENT_SOLID\n       1       1       1       2");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 3, "expects 10 fields"));
}

TEST(ReadK, NonFiniteCoordinateNamesLine) {
  for (const std::string bad : {"7,1,nan,1", "7,inf,1,1", "7,1,1,1e999", "7,1,1,x"}) {
    const std::string path = test::temp_path("nonfinite.k");
    test::write_text(path, one_hex("1,1,1,2,3,4,5,6,7,8", bad));
    EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 11, "not a finite number")) << bad;
  }
}

TEST(ReadK, UnknownKeywordNamesLine) {
  const std::string path = test::temp_path("unknown_keyword.k");
  std::string text = one_hex();
  text.replace(text.find("*NODE"), 5, "*NODES");
  test::write_text(path, text);
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 4, "unknown keyword *NODES"));
}

TEST(ReadK, OtherLsDynaKeywordsAreSkipped) {
  const std::string path = test::temp_path("skipped_keywords.k");
  std::string text = one_hex();
  text.insert(text.find("*ELEMENT_SOLID"), "*PART\npart one\n1,1,1\n*MAT_ELASTIC\n1,7.8e-9,210000,0.3\n");
  test::write_text(path, text);
  EXPECT_EQ(io::read_k(path).mesh.count(CellType::Hex), 1);
}

TEST(ReadK, DuplicateNodeNamesBothLines) {
  const std::string path = test::temp_path("duplicate_node.k");
  test::write_text(path, one_hex("1,1,1,2,3,4,5,6,7,8", "7,1,1,1", "3,9,9,9\n"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 13, "node id 3 is defined twice (first on line 7)"));
}

TEST(ReadK, PyramidIsRejectedWithItsLine) {
  const std::string path = test::temp_path("pyramid.k");
  test::write_text(path, one_hex("1,1,1,2,3,4,5,5,5,5"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 3, "solid 1 (nodes 1 2 3 4 5 5 5 5)"));
}

TEST(ReadK, DataBeforeKeywordIsRejected) {
  const std::string path = test::temp_path("no_keyword.k");
  test::write_text(path, "1,0,0,0\n" + one_hex());
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 1, "not an LS-DYNA keyword file"));
}

TEST(ReadK, IdsBeyondIntAreRejected) {
  const std::string path = test::temp_path("big_ids.k");
  test::write_text(path, one_hex("1,99999999999,1,2,3,4,5,6,7,8"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 3, "32-bit"));
  test::write_text(path, one_hex("1,1,1,2,3,4,5,6,7,8", "7,1,1,1", "4294967297,0,0,0\n"));
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 13, "32-bit"));
}

TEST(ReadK, EmptyFileNamesFile) {
  const std::string path = test::temp_path("empty.k");
  test::write_text(path, "");
  EXPECT_TRUE(ThrowsInputError([&] { io::read_k(path); }, path, 0, "no *NODE data"));
}

TEST(ReadK, FixedWidthCommaAndBlankFieldsAgree) {
  const std::string fixed = test::temp_path("fixed.k"), comma = test::temp_path("comma.k");
  // Fixed width: 8-character integers and 16-character reals, running together.
  test::write_text(fixed,
                   "*KEYWORD\n*ELEMENT_SHELL\n      11       5      21      22      23      23\n*NODE\n"
                   "      21-1.234567890e+002.0000000000e+00-3.000000000e-01\n"
                   "      22            10.5               0               0\n"
                   "      23               0            10.5               0\n*END\n");
  test::write_text(comma, "*KEYWORD\r\n$ a comment\r\n*NODE\r\n21, -1.23456789, 2, -0.3\r\n22,10.5,0,0\r\n"
                          "23 0 10.5 0\r\n*ELEMENT_SHELL\r\n11,5,21,22,23,23\r\n*END\r\n");
  auto a = io::read_k(fixed), b = io::read_k(comma);
  EXPECT_TRUE(test::SameMesh(a.mesh, b.mesh));
  ASSERT_EQ(a.mesh.num_cells(), 1);
  EXPECT_EQ(a.mesh.type(0), CellType::Triangle);
  EXPECT_EQ(a.mesh.region(0), 5);
  EXPECT_EQ(a.element_ids(0), 11);
  EXPECT_DOUBLE_EQ(a.mesh.V(0, 0), -1.23456789);
  EXPECT_DOUBLE_EQ(a.mesh.V(0, 2), -0.3);
}

TEST(ReadK, NodeIdsAreMappedNotAssumed) {
  const std::string path = test::temp_path("mapped.k");
  test::write_text(path, "*KEYWORD\n*NODE\n30,3,0,0\n10,1,0,0\n20,2,0,0\n99,9,9,9\n*ELEMENT_SHELL\n7,2,10,20,30,0\n*END\n");
  auto k = io::read_k(path);
  ASSERT_EQ(k.mesh.num_nodes(), 4);  // the unused node 99 is kept
  EXPECT_EQ(k.node_ids(0), 30);
  EXPECT_EQ(k.node_ids(3), 99);
  EXPECT_EQ(k.mesh.type(0), CellType::Triangle);  // n4 = 0
  EXPECT_EQ(k.mesh.cells(0, 0), 1);
  EXPECT_EQ(k.mesh.cells(0, 1), 2);
  EXPECT_EQ(k.mesh.cells(0, 2), 0);
  EXPECT_EQ(k.mesh.cells(0, 3), -1);
}

TEST(ReadK, CollapsedHexesBecomePrismsAndTets) {
  const std::string path = test::temp_path("collapsed.k");
  test::write_text(path,
                   "*KEYWORD\n*ELEMENT_SOLID\n1,1,1,2,3,3,5,6,7,7\n2,1,1,2,3,4,5,5,7,7\n3,1,1,2,3,4,4,4,4,4\n*NODE\n"
                   "1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n*END\n");
  auto k = io::read_k(path);
  ASSERT_EQ(k.mesh.num_cells(), 3);
  EXPECT_EQ(k.mesh.type(0), CellType::Wedge);
  EXPECT_EQ(k.mesh.type(1), CellType::Wedge);
  EXPECT_EQ(k.mesh.type(2), CellType::Tet);
  // h1 h2 h3 h3 h5 h6 h7 h7 -> [h1 h3 h2 h5 h7 h6] (0-based ids)
  EXPECT_EQ(k.mesh.cells.row(0).head(6), (Eigen::Matrix<int, 1, 6>() << 0, 2, 1, 4, 6, 5).finished());
}
