#include "hexdom/autopolycube/blocks/grid_structure.h"

#include <algorithm>

#include "test_common.h"

using namespace hexdom;

namespace {

// A 3 x 3 x 3 block of grid cells whose boundary vertices sit at their grid points, the -X side moved
// in Y and Z and every one moved in X by a deterministic pseudo-random amount (xorshift, `seed`).
struct Jittered {
  autopolycube::PolycubeGrid grid;
  std::map<std::array<int, 3>, int> grid_vertex;
  Eigen::MatrixXd V;
};

Jittered jittered_box(unsigned long long seed) {
  Jittered j;
  const int N = 3;
  for (int x = 0; x < N; ++x)
    for (int y = 0; y < N; ++y)
      for (int z = 0; z < N; ++z) j.grid.cells.push_back({x, y, z});
  for (int a = 0; a < 3; ++a)
    for (int pl : {0, N})
      for (int i = 0; i < N; ++i)
        for (int k = 0; k < N; ++k) {
          autopolycube::GridSquare q;
          q.axis = a;
          q.sign = pl ? 1 : -1;
          q.plane = pl;
          q.i = i;
          q.j = k;
          j.grid.squares.push_back(q);
        }
  unsigned long long state = 88172645463325252ull + seed;
  auto u = [&] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return 0.9 * static_cast<double>(state >> 11) / 9007199254740992.0 - 0.45;
  };
  std::vector<Eigen::RowVector3d> P;
  for (int x = 0; x <= N; ++x)
    for (int y = 0; y <= N; ++y)
      for (int z = 0; z <= N; ++z) {
        if (x > 0 && y > 0 && z > 0 && x < N && y < N && z < N) continue;
        j.grid_vertex[{x, y, z}] = static_cast<int>(P.size());
        Eigen::RowVector3d p(x, y, z);
        if (x == 0) {
          p(2) += u();
          p(1) += u();
        }
        p(0) += 0.3 * u();
        P.push_back(p);
      }
  j.V.resize(static_cast<int>(P.size()), 3);
  for (size_t i = 0; i < P.size(); ++i) j.V.row(static_cast<int>(i)) = P[i];
  return j;
}

double shortest_block_edge(const mesh::Mesh& T) {
  static const int E[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double e = 1e300;
  for (int b = 0; b < T.num_cells(); ++b)
    for (const auto& ed : E) e = std::min(e, (T.V.row(T.cells(b, ed[0])) - T.V.row(T.cells(b, ed[1]))).norm());
  return e;
}

}  // namespace

TEST(GridStructure, UntanglingDoesNotPushAnInteriorVertexOntoItsNeighbour) {
  // The scaled Jacobian of a block does not drop when the block flattens to a slab, so raising the
  // worst block around an interior vertex could move it onto its neighbour (rockerarm's arm: two
  // block vertices 0.050 apart harmonically, 4.3e-5 after untangling). Without the edge limit this
  // box ends with an edge of 0.003 (grid edges are about 1); with it, none shorter than a quarter.
  const Jittered j = jittered_box(420);
  autopolycube::GridStructureOptions unlimited;
  unlimited.min_edge_share = 0;
  const auto old = autopolycube::grid_structure(j.grid, j.grid_vertex, j.V, unlimited);
  EXPECT_LT(shortest_block_edge(old.structure), 0.01);
  const auto r = autopolycube::grid_structure(j.grid, j.grid_vertex, j.V);
  EXPECT_EQ(r.interior_vertices, 8);
  EXPECT_GT(shortest_block_edge(r.structure), 0.25 * 0.9);
  // The worst block is as good as without the limit.
  EXPECT_GT(r.min_quality, r.min_quality_harmonic);
  EXPECT_GE(r.min_quality, old.min_quality - 1e-3);
}
