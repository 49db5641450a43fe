#include "hexdom/mesh/mesh.h"
#include "test_common.h"

using namespace hexdom::mesh;

TEST(ClassifyHexNodes, PrismPatternsFollowTheReference) {
  // h1 h2 h3 h3 h5 h6 h7 h7 -> [h1 h3 h2 h5 h7 h6]
  auto a = classify_hex_nodes({1, 2, 3, 3, 5, 6, 7, 7});
  EXPECT_EQ(a.type, CellType::Wedge);
  EXPECT_EQ((std::array<int, 6>{a.nodes[0], a.nodes[1], a.nodes[2], a.nodes[3], a.nodes[4], a.nodes[5]}),
            (std::array<int, 6>{1, 3, 2, 5, 7, 6}));
  // h1 h2 h3 h4 h5 h5 h7 h7 -> [h1 h2 h5 h4 h3 h7]
  auto b = classify_hex_nodes({1, 2, 3, 4, 5, 5, 7, 7});
  EXPECT_EQ(b.type, CellType::Wedge);
  EXPECT_EQ((std::array<int, 6>{b.nodes[0], b.nodes[1], b.nodes[2], b.nodes[3], b.nodes[4], b.nodes[5]}),
            (std::array<int, 6>{1, 2, 5, 4, 3, 7}));
}

TEST(ClassifyHexNodes, TetAndHex) {
  auto t = classify_hex_nodes({1, 2, 3, 4, 4, 4, 4, 4});
  EXPECT_EQ(t.type, CellType::Tet);
  EXPECT_EQ(t.nodes[3], 4);
  EXPECT_EQ(classify_hex_nodes({0, 1, 2, 3, 4, 5, 6, 7}).type, CellType::Hex);
}

TEST(ClassifyHexNodes, PyramidIsRejected) {
  EXPECT_THROW(classify_hex_nodes({0, 1, 2, 3, 4, 4, 4, 4}), std::invalid_argument);
}

TEST(ClassifyHexNodes, WedgeRoundTripsThroughHexNodes) {
  const int w[6] = {10, 11, 12, 13, 14, 15};
  auto h = to_hex_nodes(CellType::Wedge, w);
  auto back = classify_hex_nodes(h);
  ASSERT_EQ(back.type, CellType::Wedge);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(back.nodes[i], w[i]);
}
