#include <fstream>
#include <sstream>

#include "hexdom/io/inp.h"
#include "io_test_util.h"

using namespace hexdom;

namespace {
std::string written(const mesh::Mesh& m, const std::string& name) {
  const std::string path = test::temp_path(name);
  io::write_inp(path, m);
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(WriteInp, ElementBlocksUseAbaqusNodeOrder) {
  const std::string text = written(test::mixed_mesh(), "mixed.inp");
  // Element ids are cell index + 1; nodes are 1-based. Wedge [4 6 5 12 13 14] -> a c b d f e.
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n2, 2, 9, 10, 3, 6, 11, 12, 7\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D6\n3, 5, 6, 7, 13, 15, 14\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D4\n4, 5, 6, 8, 13\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELEMENT, TYPE=S4\n6, 1, 4, 3, 2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELEMENT, TYPE=S3\n5, 1, 2, 16\n"), std::string::npos) << text;
}

TEST(WriteInp, ElementSetsPerRegionAndForAllVolumes) {
  const std::string text = written(test::mixed_mesh(), "sets.inp");
  EXPECT_NE(text.find("*ELSET, ELSET=REGION_1\n1, 2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELSET, ELSET=REGION_4\n6, 5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("*ELSET, ELSET=EALL\n1, 2, 3, 4\n"), std::string::npos) << text;
}

TEST(WriteInp, NodesKeepFullPrecision) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string text = written(m, "precision.inp");
  std::istringstream in(text.substr(text.find("*NODE\n") + 6));
  for (int i = 0; i < m.num_nodes(); ++i) {
    int id;
    char comma;
    double x, y, z;
    in >> id >> comma >> x >> comma >> y >> comma >> z;
    ASSERT_EQ(id, i + 1);
    EXPECT_EQ(x, m.V(i, 0));
    EXPECT_EQ(y, m.V(i, 1));
    EXPECT_EQ(z, m.V(i, 2));
  }
}
