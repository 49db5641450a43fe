#include <fstream>
#include <sstream>

#include "hexdom/io/k_file.h"
#include "io_test_util.h"

using namespace hexdom;
using mesh::CellType;

TEST(WriteK, RoundTripKeepsEveryNodeAndCellExactly) {
  const mesh::Mesh m = test::mixed_mesh();
  const std::string path = test::temp_path("round_trip.k");
  io::write_k(path, m);
  const auto k = io::read_k(path);
  // Shells are written first, then solids: compare in that order.
  mesh::MeshBuilder b;
  for (bool solid : {false, true})
    for (int c = 0; c < m.num_cells(); ++c)
      if (mesh::is_volume(m.type(c)) == solid) b.add(m.type(c), m.cells.row(c).data(), m.region(c));
  EXPECT_TRUE(test::SameMesh(k.mesh, b.finish(m.V)));
  for (int i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(k.node_ids(i), i + 1);
}

TEST(WriteK, PrismsAndTetsUseTheCollapsedHexPatterns) {
  const mesh::Mesh m = test::volume_part(test::mixed_mesh());
  const std::string path = test::temp_path("patterns.k");
  io::write_k(path, m);
  std::ifstream in(path);
  std::string line, solids;
  bool in_solid = false;
  while (std::getline(in, line)) {
    if (line.rfind("*", 0) == 0) { in_solid = line == "*ELEMENT_SOLID"; continue; }
    if (in_solid) solids += line + "\n";
  }
  // Wedge [4 6 5 12 13 14] (0-based) -> a c b b d f e e, 1-based; tet [4 5 7 12] -> a b c d d d d d.
  EXPECT_NE(solids.find("       3       2       5       6       7       7      13      15      14      14\n"),
            std::string::npos) << solids;
  EXPECT_NE(solids.find("       4       3       5       6       8      13      13      13      13      13\n"),
            std::string::npos) << solids;
}

TEST(WriteK, PaperStructureRoundTrips) {
  const std::string src = test::data_path("hexdom/rockerarm/rockerarm_polycube_withtet.k");
  HEXDOM_REQUIRE_DATA(src);
  const auto a = io::read_k(src);
  const std::string path = test::temp_path("rockerarm_structure.k");
  io::write_k(path, a.mesh);
  EXPECT_TRUE(test::SameMesh(io::read_k(path).mesh, a.mesh));
}

TEST(WriteK, MissingDirectoryIsInputErrorAndLeavesNothing) {
  const std::string path = test::temp_path("no_such_dir/out.k");
  EXPECT_TRUE(test::ThrowsInputError([&] { io::write_k(path, test::mixed_mesh()); }, path, 0, "cannot create file"));
  EXPECT_FALSE(std::filesystem::exists(path));
}
