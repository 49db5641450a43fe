#include <cmath>

#include "hexdom/common/error.h"
#include "hexdom/mesh/second_order.h"
#include "hexdom/optimize/curve_mid_nodes.h"
#include "hexdom/quality/second_order.h"
#include "hex_grid.h"
#include "test_common.h"

using namespace hexdom;

namespace {

mesh::Mesh unit_grid(int n, double height = 1.0) {
  const int m = n + 1;
  Eigen::MatrixXd V(m * m * m, 3);
  for (int l = 0; l < m; ++l)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) V.row(test::grid_node(i, j, l, m, m)) << i, j, l * height;
  return mesh::add_mid_edge_nodes(test::grid_cells(V, n, n, m, m));
}

double cell_sj(const mesh::Mesh& m, int c) {
  double p[20][3];
  mesh::second_order_points(m, c, p);
  return quality::second_order_scaled_jacobian(m.type(c), p);
}

/// Mid-edge nodes of the top face's edges (z = n * height) of the grid.
std::vector<int> top_mid_nodes(const mesh::Mesh& m, int linear_nodes, double top) {
  std::vector<int> r;
  for (int v = linear_nodes; v < m.num_nodes(); ++v)
    if (std::abs(m.V(v, 2) - top) < 1e-12) r.push_back(v);
  return r;
}

}  // namespace

TEST(CurveMidNodes, SmallOffsetsAreTakenWhole) {
  mesh::Mesh m = unit_grid(2);
  const int linear = 27;
  Eigen::MatrixXd target = m.V;
  std::vector<char> has(m.num_nodes(), 0);
  for (int v : top_mid_nodes(m, linear, 2.0)) target(v, 2) += 0.1, has[v] = 1;  // a gentle bulge
  const optimize::CurveReport r = optimize::curve_mid_nodes(m, target, has);
  EXPECT_EQ(r.targets, 12);
  EXPECT_EQ(r.placed, 12);
  EXPECT_EQ(r.straight + r.shortened, 0);
  EXPECT_EQ(r.max_gap, 0);
  EXPECT_EQ(r.inverted, 0);
  for (int v = 0; v < m.num_nodes(); ++v) EXPECT_TRUE(m.V.row(v) == target.row(v));
}

TEST(CurveMidNodes, OffsetsThatWouldFoldAThinLayerAreShortenedOrUndone) {
  // Cells 0.1 high whose top edges are asked to bow 0.3 down: through the cells. Every cell must
  // end at least at min(min_sj, its straight value) = min(0.2, 1).
  mesh::Mesh m = unit_grid(2, 0.1);
  const int linear = 27;
  Eigen::MatrixXd target = m.V;
  std::vector<char> has(m.num_nodes(), 0);
  const std::vector<int> top = top_mid_nodes(m, linear, 0.2);
  ASSERT_EQ(top.size(), 12u);
  for (int v : top) target(v, 2) -= 0.3, has[v] = 1;
  optimize::CurveOptions o;
  o.min_sj = 0.2;
  const optimize::CurveReport r = optimize::curve_mid_nodes(m, target, has, o);
  EXPECT_EQ(r.placed, 0);
  EXPECT_EQ(r.shortened + r.straight, 12);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_GE(r.worst_sj, 0.2);
  for (int c = 0; c < m.num_cells(); ++c) EXPECT_GE(cell_sj(m, c), 0.2) << "cell " << c;
  EXPECT_GT(r.max_gap, 0.3 * 0.5);
}

TEST(CurveMidNodes, ACellWorseThanTheBarStraightKeepsItsStraightValue) {
  // One hex squashed to a sliver: its straight value is below min_sj, so any curving that lowers it
  // is undone, and it ends exactly straight.
  mesh::Mesh m = unit_grid(1, 0.05);
  Eigen::MatrixXd target = m.V;
  std::vector<char> has(m.num_nodes(), 0);
  for (int v : top_mid_nodes(m, 8, 0.05)) target(v, 2) -= 0.04, has[v] = 1;
  optimize::CurveOptions o;
  o.min_sj = 1.1;  // no cell reaches it: each must keep its straight value
  const double straight = cell_sj(m, 0);
  const optimize::CurveReport r = optimize::curve_mid_nodes(m, target, has, o);
  EXPECT_EQ(r.straight, 4);
  EXPECT_DOUBLE_EQ(cell_sj(m, 0), straight);
}

TEST(CurveMidNodes, RefusesFirstOrderMeshesAndMismatchedTargets) {
  mesh::Mesh m = unit_grid(1);
  mesh::Mesh linear = m;
  linear.mid.resize(0, 12);
  EXPECT_THROW(optimize::curve_mid_nodes(linear, linear.V, std::vector<char>(linear.num_nodes(), 0)), InputError);
  EXPECT_THROW(optimize::curve_mid_nodes(m, m.V.topRows(3), std::vector<char>(m.num_nodes(), 0)), std::invalid_argument);
}
