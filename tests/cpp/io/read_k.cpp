#include "hexdom/common/error.h"
#include "hexdom/io/k_file.h"
#include "test_common.h"

using namespace hexdom;

TEST(ReadK, RockerarmStructureHasPaperBlockCounts) {
  const std::string path = test::data_path("hexdom/rockerarm/rockerarm_polycube_withtet.k");
  HEXDOM_REQUIRE_DATA(path);
  auto k = io::read_k(path);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Hex), 60);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Wedge), 11);
  EXPECT_EQ(k.mesh.count(mesh::CellType::Tet), 2);
}

TEST(ReadK, MissingNodeNamesFileAndLine) {
  const std::string path = test::temp_path("missing_node.k");
  test::write_text(path, "*KEYWORD\n*ELEMENT_SHELL\n1 1 1 2 3 3\n*NODE\n1 0 0 0\n2 1 0 0\n*END\n");
  try {
    io::read_k(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing_node.k:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node 3"), std::string::npos) << e.what();
  }
}
