#include "hexdom/optimize/compass_search.h"

#include <set>

#include "hexdom/quality/metrics.h"
#include "test_common.h"

using namespace hexdom;

namespace {

// 2 x 2 x 2 unit hexes (VTK order) over the 27 nodes i + 3 j + 9 k; the edge graph as neighbours.
mesh::Mesh cube_of_eight(std::vector<std::vector<int>>* neighbours) {
  Eigen::MatrixXd V(27, 3);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) V.row(i + 3 * j + 9 * k) << i, j, k;
  auto id = [](int i, int j, int k) { return i + 3 * j + 9 * k; };
  mesh::MeshBuilder b;
  std::vector<std::set<int>> nbr(27);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int h[8] = {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        b.add(mesh::CellType::Hex, h, 1);
        static const int E[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (const auto& e : E) {
          nbr[h[e[0]]].insert(h[e[1]]);
          nbr[h[e[1]]].insert(h[e[0]]);
        }
      }
  neighbours->clear();
  for (const auto& s : nbr) neighbours->emplace_back(s.begin(), s.end());
  return b.finish(V);
}


}  // namespace

TEST(CompassUntangle, MovesTheCentreOfEightHexesBackInsideAndKeepsFixedNodes) {
  std::vector<std::vector<int>> nbr;
  mesh::Mesh m = cube_of_eight(&nbr);
  m.V.row(13) << 1.1, 0.9, -0.2;  // the centre node pushed through the bottom: four cells inverted
  ASSERT_LE(test::worst_of(m).all, 0.0);
  std::vector<char> fixed(27, 1);
  fixed[13] = 0;
  const Eigen::MatrixXd before = m.V;
  const Eigen::VectorXd q = optimize::compass_untangle(m, fixed, nbr, {});
  EXPECT_GT(test::worst_of(m).all, 0.3);
  for (int v = 0; v < 27; ++v)
    if (v != 13) {
      EXPECT_EQ((m.V.row(v) - before.row(v)).norm(), 0.0) << "fixed node " << v << " moved";
    }
  ASSERT_EQ(q.size(), m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c)
    EXPECT_EQ(q(c), quality::signed_sj(m.type(c), quality::cell_points(m, c))) << "cell " << c;
}

TEST(CompassUntangle, LeavesNodesWhoseCellsReachTheTarget) {
  std::vector<std::vector<int>> nbr;
  mesh::Mesh m = cube_of_eight(&nbr);
  m.V.row(13) << 1.05, 1.0, 1.0;  // every cell still above 0.9
  std::vector<char> fixed(27, 1);
  fixed[13] = 0;
  optimize::CompassOptions o;
  o.target = 0.9;
  optimize::compass_untangle(m, fixed, nbr, o);
  EXPECT_DOUBLE_EQ(m.V(13, 0), 1.05);
}

TEST(CompassUntangle, AStepMayNotShortenAnEdgeBelowTheShareOfTheMeanEdge) {
  std::vector<std::vector<int>> nbr;
  mesh::Mesh m = cube_of_eight(&nbr);
  m.V.row(13) << 1.9, 1.8, 0.3;
  std::vector<char> fixed(27, 1);
  fixed[13] = 0;
  double mean = 0;
  for (int u : nbr[13]) mean += (m.V.row(u) - m.V.row(13)).norm();
  mean /= static_cast<double>(nbr[13].size());
  double shortest_start = 1e300;
  for (int u : nbr[13]) shortest_start = std::min(shortest_start, (m.V.row(u) - m.V.row(13)).norm());
  optimize::CompassOptions o;
  o.min_edge_share = 0.25;
  optimize::compass_untangle(m, fixed, nbr, o);
  double shortest = 1e300;
  for (int u : nbr[13]) shortest = std::min(shortest, (m.V.row(u) - m.V.row(13)).norm());
  EXPECT_GE(shortest, std::min(0.25 * mean, shortest_start));
}
