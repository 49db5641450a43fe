#include "hexdom/optimize/improve.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <thread>

#include "hexdom/common/interrupt.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/optimize/node_kinds.h"
#include "hexdom/quality/metrics.h"
#include "hex_grid.h"
#include "test_common.h"

using namespace hexdom;

namespace {

// n x n x n grid of hexes filling the unit cube; interior nodes jittered by up to `jitter` cells.
mesh::Mesh cube_grid(int n, double jitter, unsigned seed = 7) { return test::jittered_cube_grid(n, jitter, seed, 1.0 / n); }

Eigen::VectorXd sj_of(const mesh::Mesh& m) { return quality::compute_metrics(m).scaled_jacobian; }

// Cylinder of radius 1 and height 1 as a polycube gives it: an n x n grid of the square [-1, 1]^2
// mapped onto the disk (x sqrt(1 - y^2 / 2), y sqrt(1 - x^2 / 2)), k layers high. The square's 4
// corners land on the round side, so the corner quads of each cap have three nodes on the rim and
// the hexes along those 4 vertical lines have two side faces meeting at about 180 degrees.
mesh::Mesh polycube_cylinder(int n, int k) {
  const int m = n + 1;
  auto id = [&](int i, int j, int l) { return i + m * (j + m * l); };
  Eigen::MatrixXd V(m * m * (k + 1), 3);
  for (int l = 0; l <= k; ++l)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
        V.row(id(i, j, l)) << x * std::sqrt(1 - y * y / 2), y * std::sqrt(1 - x * x / 2), static_cast<double>(l) / k;
      }
  return test::grid_cells(V, n, k, n + 1, n + 1);
}

}  // namespace

TEST(Pillow, LayerOverPartOfTheBoundaryEndsOnTheFacesLeftOut) {
  const mesh::Mesh m = cube_grid(2, 0.0);
  const auto faces = mesh::boundary_faces(m);
  std::vector<char> mask(faces.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    bool on_x1 = true;
    for (int i = 0; i < faces[f].n; ++i) on_x1 &= m.V(faces[f].v[i], 0) == 1.0;
    mask[f] = on_x1;
  }
  std::vector<int> copy;
  const mesh::Mesh p = optimize::pillow(m, 0.2, mask, &copy);
  EXPECT_EQ(p.num_cells(), 8 + 4);  // the 4 quads of the face x = 1
  EXPECT_GT(sj_of(p).minCoeff(), 0.0);
  EXPECT_NEAR(quality::compute_metrics(p).volume.sum(), 1.0, 1e-12);  // the boundary keeps its place
  // Every boundary face of the result still lies on a face of the unit cube: the layer's side
  // faces lie on y = 0, y = 1, z = 0, z = 1.
  for (const auto& f : mesh::boundary_faces(p)) {
    bool on_cube_face = false;
    for (int k = 0; k < 3; ++k)
      for (double c : {0.0, 1.0}) {
        bool all = true;
        for (int i = 0; i < f.n; ++i) all &= std::fabs(p.V(f.v[i], k) - c) < 1e-12;
        on_cube_face |= all;
      }
    EXPECT_TRUE(on_cube_face) << "boundary face of cell " << f.cell;
  }
  // Copies only for the 9 nodes of x = 1; the old ones moved inward by 0.2 x the shortest boundary
  // edge (0.5), along x only: the rim nodes slid along the faces left out.
  int copies = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (copy[v] < 0) {
      EXPECT_EQ((p.V.row(v) - m.V.row(v)).norm(), 0.0) << "node " << v;
      continue;
    }
    ++copies;
    EXPECT_EQ((p.V.row(copy[v]) - m.V.row(v)).norm(), 0.0);
    EXPECT_NEAR(p.V(v, 0), 0.9, 1e-12) << "node " << v;
    EXPECT_NEAR(p.V(v, 1), m.V(v, 1), 1e-12) << "node " << v;
    EXPECT_NEAR(p.V(v, 2), m.V(v, 2), 1e-12) << "node " << v;
  }
  EXPECT_EQ(copies, 9);
}

TEST(Pillow, LayerCannotEndInsideAFlatFace) {
  // One quad of the face x = 1: its edge lies inside that face, where no inward move keeps the old
  // nodes on the faces left out.
  const mesh::Mesh m = cube_grid(2, 0.0);
  const auto faces = mesh::boundary_faces(m);
  std::vector<char> mask(faces.size(), 0);
  int chosen = 0;
  for (size_t f = 0; f < faces.size() && !chosen; ++f) {
    bool on_x1 = true;
    for (int i = 0; i < faces[f].n; ++i) on_x1 &= m.V(faces[f].v[i], 0) == 1.0;
    if (on_x1) mask[f] = 1, chosen = 1;
  }
  ASSERT_EQ(chosen, 1);
  EXPECT_THROW(optimize::pillow(m, 0.2, mask), GeometryError);
  EXPECT_THROW(optimize::pillow(m, 0.2, std::vector<char>(3, 1)), GeometryError);  // wrong size
}

TEST(Improve, LayerOverTheRoundSideOfAPolycubeCylinder) {
  const int n = 6, k = 3;
  const mesh::Mesh m = polycube_cylinder(n, k);
  const Eigen::VectorXd sj0 = sj_of(m);
  ASSERT_LT(sj0.minCoeff(), 0.35);  // 0.290: the corner hexes, their two side faces nearly in line
  const auto r = optimize::improve(m);
  // The layer covers the round side only (4 n k quads), not the caps: they get a ring of layer
  // sides instead, and their corner quads can open up (0.862 measured).
  EXPECT_EQ(r.pillow_cells, 4 * n * k);
  const Eigen::VectorXd sj1 = sj_of(r.mesh);
  EXPECT_GE(sj1.minCoeff(), 0.5);
  // A layer everywhere copies the caps' corner quads, three nodes on the rim, as they are: however
  // long it is optimised, their hexes stay poor (0.276 measured).
  optimize::ImproveOptions full;
  full.pillow = true;
  full.smooth = 10;
  full.optimize = 40;
  EXPECT_LT(sj_of(optimize::improve(m, full).mesh).minCoeff(), 0.4);
  const double v0 = quality::compute_metrics(m).volume.sum(), v1 = quality::compute_metrics(r.mesh).volume.sum();
  EXPECT_NEAR(v1, v0, 0.01 * v0);
  for (const auto& f : mesh::boundary_faces(r.mesh))
    for (int i = 0; i < f.n; ++i) {
      const Eigen::RowVector3d x = r.mesh.V.row(f.v[i]);
      EXPECT_LE(std::hypot(x(0), x(1)), 1 + 1e-12);
      EXPECT_TRUE(x(2) >= -1e-12 && x(2) <= 1 + 1e-12);
    }
}

TEST(Pillow, NoHexKeepsMoreThanOneBoundaryFace) {
  const mesh::Mesh m = cube_grid(2, 0.0);
  std::vector<int> copy;
  const mesh::Mesh p = optimize::pillow(m, 0.2, &copy);
  // 24 boundary quads of the 2x2x2 cube each get a layer hex.
  EXPECT_EQ(p.num_cells(), 8 + 24);
  std::map<int, int> per_cell;
  for (const auto& f : mesh::boundary_faces(p)) ++per_cell[f.cell];
  for (const auto& [c, count] : per_cell) EXPECT_EQ(count, 1) << "cell " << c;
  // The new boundary nodes keep the old boundary positions; the old ones moved inward.
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (copy[v] < 0) continue;
    EXPECT_EQ((p.V.row(copy[v]) - m.V.row(v)).norm(), 0.0);
    EXPECT_GT((p.V.row(v) - m.V.row(v)).norm(), 0.0);
  }
  const Eigen::VectorXd sj = sj_of(p);
  EXPECT_GT(sj.minCoeff(), 0.0);
}

// A layer as thick as a share of the cell under it: over a 2 x 2 x 2 grid of the unit cube (cells
// 0.5) the old rule (0.2 of the shortest boundary edge) gives layer cells 0.1 thick, edge ratio 5;
// with share 0.4 they are 0.2 thick (ratio 2.5), every cell valid, the volume kept. A layer is
// never thinner than the old rule gives, and never thicker than its shortest face edge.
TEST(Pillow, ALayerTakesAShareOfTheCellUnderIt) {
  const mesh::Mesh m = cube_grid(2, 0.0);
  auto largest_ratio = [](const mesh::Mesh& p) { return quality::compute_metrics(p).edge_ratio.maxCoeff(); };
  const mesh::Mesh old_rule = optimize::pillow_faces(m, 0.2, nullptr, nullptr);
  const mesh::Mesh shared = optimize::pillow_faces(m, 0.2, nullptr, nullptr, nullptr, 0.4);
  EXPECT_NEAR(largest_ratio(old_rule), 5.0, 1e-9);
  EXPECT_NEAR(largest_ratio(shared), 2.5, 1e-9);
  EXPECT_GT(sj_of(shared).minCoeff(), 0.0);
  EXPECT_NEAR(quality::compute_metrics(shared).volume.sum(), 1.0, 1e-12);
  // A share that would crush the cells under the layer: thinned where cells would invert.
  const mesh::Mesh capped = optimize::pillow_faces(m, 0.2, nullptr, nullptr, nullptr, 3.0);
  EXPECT_GT(sj_of(capped).minCoeff(), 0.0);
  EXPECT_NEAR(quality::compute_metrics(capped).volume.sum(), 1.0, 1e-12);
}

TEST(Improve, RaisesTheMeanWithoutLoweringTheWorstAndKeepsTheCube) {
  const mesh::Mesh m = cube_grid(4, 0.35);
  const Eigen::VectorXd sj0 = sj_of(m);
  ASSERT_LT(sj0.minCoeff(), 0.7);  // the jitter made bad cells
  const auto r = optimize::improve(m);
  const Eigen::VectorXd sj1 = sj_of(r.mesh);
  EXPECT_GT(sj1.minCoeff(), 0.0);
  EXPECT_GE(sj1.minCoeff(), sj0.minCoeff());
  // 0.743 -> 0.841 measured (the pillow layer's cells at the cube's corners and edges stay below
  // the rest): the mean rises by a clear margin.
  EXPECT_GE(sj1.mean(), sj0.mean() + 0.05);
  // The box stays the box: every boundary node on a face of the unit cube, the 8 cube corners
  // (feature corners) where they were, volume 1.
  for (const auto& f : mesh::boundary_faces(r.mesh))
    for (int i = 0; i < f.n; ++i) {
      const Eigen::RowVector3d x = r.mesh.V.row(f.v[i]);
      const double d = std::min({std::fabs(x(0)), std::fabs(x(1)), std::fabs(x(2)), std::fabs(1 - x(0)),
                                 std::fabs(1 - x(1)), std::fabs(1 - x(2))});
      EXPECT_LE(d, 1e-12) << "boundary node " << f.v[i];
      EXPECT_TRUE(x.minCoeff() >= -1e-12 && x.maxCoeff() <= 1 + 1e-12) << "boundary node " << f.v[i];
    }
  int corners = 0;
  for (int v = 0; v < r.mesh.num_nodes(); ++v) {
    const Eigen::RowVector3d x = r.mesh.V.row(v);
    bool corner = true;
    for (int k = 0; k < 3; ++k) corner &= std::fabs(x(k)) < 1e-12 || std::fabs(x(k) - 1) < 1e-12;
    corners += corner;
  }
  EXPECT_EQ(corners, 8);
  EXPECT_NEAR(quality::compute_metrics(r.mesh).volume.sum(), 1.0, 1e-9);
}

TEST(Improve, FeatureCurveNodesStayOnTheCubeEdges) {
  // Nodes on the 12 cube edges may slide along them only (explicit stages keep node numbers).
  const mesh::Mesh m = cube_grid(4, 0.3);
  optimize::ImproveOptions opt;
  opt.smooth = 5;
  opt.optimize = 10;
  const auto r = optimize::improve(m, opt);
  ASSERT_EQ(r.mesh.num_nodes(), m.num_nodes());
  EXPECT_EQ(r.corner_nodes, 8);
  EXPECT_EQ(r.feature_nodes, 12 * 3);
  for (int v = 0; v < m.num_nodes(); ++v) {
    int on_faces = 0;
    for (int k = 0; k < 3; ++k) on_faces += m.V(v, k) == 0.0 || m.V(v, k) == 1.0;
    if (on_faces < 2) continue;
    // Coordinates at 0 or 1 before stay exactly there after.
    for (int k = 0; k < 3; ++k) {
      if (m.V(v, k) == 0.0 || m.V(v, k) == 1.0) {
        EXPECT_NEAR(r.mesh.V(v, k), m.V(v, k), 1e-12) << "node " << v;
      }
    }
  }
}

TEST(Improve, FloorKeepsTheCellsUntanglingDoesNotNeed) {
  // A regular 4^3 grid whose bottom-face node (2, 2, 0) is pushed 1.3 cells up and held, as the
  // snap to the B-rep holds a boundary node it moved: the cells above it invert, and only their
  // neighbours' moves mend them. With no floor the untangling lets cells far from the trouble
  // drop below 0.6; with ImproveOptions::floor = 0.6 no cell at or above it ends below it, even
  // while cells are inverted. The price, measured: the untangling stalls (worst -0.57 with the
  // floor, 0.371 without), since its path goes through states where good cells give way; so the
  // snap falls back to no floor when the floor leaves cells inverted.
  mesh::Mesh m = cube_grid(4, 0.0);
  const int pushed = 2 + 5 * 2;  // node (2, 2, 0)
  m.V(pushed, 2) += 1.3 / 4;
  const Eigen::VectorXd sj0 = sj_of(m);
  ASSERT_LE(sj0.minCoeff(), 0.0);
  optimize::ImproveOptions opt;
  opt.smooth = 3;
  opt.optimize = 20;
  opt.fixed_nodes = {pushed};
  const double floor = 0.6;
  opt.floor = floor;
  const Eigen::VectorXd sj1 = sj_of(optimize::improve(m, opt).mesh);
  opt.floor = -2;
  const Eigen::VectorXd sj2 = sj_of(optimize::improve(m, opt).mesh);
  int dropped = 0;
  for (int c = 0; c < m.num_cells(); ++c) {
    if (sj0(c) < floor) continue;
    EXPECT_GE(sj1(c), floor - 1e-9) << "cell " << c << " was " << sj0(c);
    dropped += sj2(c) < floor - 1e-9;
  }
  std::printf("floor %.2f: worst %.3f, mean %.3f; no floor: worst %.3f, mean %.3f, %d cells dropped below it\n", floor,
              sj1.minCoeff(), sj1.mean(), sj2.minCoeff(), sj2.mean(), dropped);
  EXPECT_GT(sj2.minCoeff(), 0.0) << "untangled without the floor";
  EXPECT_GT(dropped, 0) << "without the floor the same stages lower cells that were above it";
}

TEST(Improve, MeanAfterExplicitStagesRaisesTheMeanAndKeepsTheWorst) {
  // Explicit smoothing pulls an optimised mesh back toward centroids and lowers its mean; with
  // mean_after the mean passes follow the stages, raising the mean without lowering the worst.
  const mesh::Mesh m = polycube_cylinder(6, 3);  // the round side keeps the cells below 1
  optimize::ImproveOptions opt;
  opt.smooth = 3;
  opt.optimize = 10;
  const Eigen::VectorXd plain = sj_of(optimize::improve(m, opt).mesh);
  opt.mean_after = true;
  const Eigen::VectorXd with_mean = sj_of(optimize::improve(m, opt).mesh);
  std::printf("mean %.4f -> %.4f, worst %.4f -> %.4f\n", plain.mean(), with_mean.mean(), plain.minCoeff(), with_mean.minCoeff());
  EXPECT_GE(with_mean.minCoeff(), plain.minCoeff() - 1e-12);
  EXPECT_GT(with_mean.mean(), plain.mean() + 0.001);  // measured 0.8654 -> 0.8673, worst 0.2903 kept
}

// optimised_at: the passes start from the cells changed since the input was optimised. With nothing
// changed, the smoothing and the mean passes leave a jittered grid where it is (every node would move
// otherwise); with one node moved since, the passes start there (and, the grid being far from
// converged, spread from it).
TEST(Improve, OptimisedAtStartsThePassesFromTheCellsChangedSince) {
  const mesh::Mesh m = cube_grid(6, 0.3);
  optimize::ImproveOptions opt;
  opt.smooth = 2;
  opt.mean_after = true;
  auto moved = [&](const mesh::Mesh& out) {
    int n = 0;
    for (int v = 0; v < m.num_nodes(); ++v) n += (out.V.row(v) - m.V.row(v)).norm() > 1e-12;
    return n;
  };
  const int everywhere = moved(optimize::improve(m, opt).mesh);
  opt.optimised_at = m.V;
  const int unchanged = moved(optimize::improve(m, opt).mesh);
  // One interior node (the grid's node (3, 3, 3)) was elsewhere when the mesh was optimised.
  const int centre = 3 + 7 * (3 + 7 * 3);
  opt.optimised_at.row(centre) += Eigen::RowVector3d(0.05, 0, 0);
  const mesh::Mesh out = optimize::improve(m, opt).mesh;
  const int near = moved(out);
  double farthest = 0;
  for (int v = 0; v < m.num_nodes(); ++v)
    if ((out.V.row(v) - m.V.row(v)).norm() > 1e-12) farthest = std::max(farthest, (m.V.row(v) - m.V.row(centre)).norm());
  std::printf("nodes moved: %d from every node, %d with nothing changed, %d (farthest %.3f) around one node\n", everywhere,
              unchanged, near, farthest);
  EXPECT_GT(everywhere, 100);
  EXPECT_EQ(unchanged, 0);
  EXPECT_GT(near, 0);
  EXPECT_THROW(
      {
        optimize::ImproveOptions bad = opt;
        bad.optimised_at = Eigen::MatrixXd::Zero(3, 3);
        optimize::improve(m, bad);
      },
      GeometryError);
}

// changed_nodes: with optimised_at, the nodes whose constraint changed although their cells did
// not are where the passes start, untangling included. A column of 4 x 4 x 40 jittered cubes with a
// node near its foot pushed through its neighbours' faces, said to be optimised where it is now but
// for that node; the recommended sequence's first two rounds (with the nodes' kinds given, as the
// overlay path does: no pillowed run), no mean pass. From every node, the untangling round smooths
// the whole column; from the changed node, the moves spread a ring per pass and leave the column's
// top half (20 cells and more above the node) where it was.
TEST(Improve, ChangedNodesStartTheUntanglingAroundThem) {
  const int n = 4, nz = 40, mx = n + 1;
  Eigen::MatrixXd V(mx * mx * (nz + 1), 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int l = 0; l <= nz; ++l)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        Eigen::RowVector3d p(i, j, l);
        if (i > 0 && j > 0 && l > 0 && i < n && j < n && l < nz)
          for (int d = 0; d < 3; ++d) p(d) += u(rng);
        V.row(test::grid_node(i, j, l, mx, mx)) = p;
      }
  // A bad spot the optimiser may not mend: a node at the foot skewed, it and its neighbours fixed.
  V.row(test::grid_node(2, 2, 1, mx, mx)) += Eigen::RowVector3d(0.4, 0.4, 0);
  std::vector<int> fixed;
  for (const auto& [i, j, l] : std::vector<std::array<int, 3>>{{2, 2, 1}, {1, 2, 1}, {3, 2, 1}, {2, 1, 1}, {2, 3, 1}, {2, 2, 2}})
    fixed.push_back(test::grid_node(i, j, l, mx, mx));
  mesh::Mesh m = test::grid_cells(V, n, nz, mx, mx);
  const int pushed = test::grid_node(2, 2, 6, mx, mx);
  m.V.row(pushed) += Eigen::RowVector3d(1.5, 1.5, 1.5);
  int inverted = 0;
  for (double sj : sj_of(m)) inverted += sj <= 0;
  ASSERT_GT(inverted, 0) << "the pushed node must invert cells, or the test would not tell";
  optimize::ImproveOptions opt;
  opt.max_rounds = 2;
  opt.mean_passes = 0;
  opt.fixed_nodes = fixed;
  const optimize::NodeKinds kinds = optimize::node_kinds(m, opt.feature_angle, nullptr);
  opt.kinds = kinds.kind;
  opt.curve_neighbours = kinds.curve_nbrs;
  // Nodes moved: all, and those of the column's top half.
  auto moved = [&](const mesh::Mesh& out, int* top) {
    int all = 0;
    *top = 0;
    for (int v = 0; v < m.num_nodes(); ++v)
      if ((out.V.row(v) - m.V.row(v)).norm() > 1e-12) {
        ++all;
        *top += v >= test::grid_node(0, 0, 24, mx, mx);
      }
    return all;
  };
  int top_all = 0, top_local = 0;
  const optimize::ImproveResult everywhere = optimize::improve(m, opt);
  opt.optimised_at = m.V;
  opt.changed_nodes = {pushed};
  const optimize::ImproveResult local = optimize::improve(m, opt);
  const int n_all = moved(everywhere.mesh, &top_all), n_local = moved(local.mesh, &top_local);
  std::printf("inverted %d -> %d / %d, worst %.3f / %.3f; nodes moved: %d (%d in the top half) from every node, %d (%d) "
              "from the changed one\n", inverted, quality::inverted_cells(everywhere.after), quality::inverted_cells(local.after),
              everywhere.after.hex.sj_min, local.after.hex.sj_min, n_all, top_all, n_local, top_local);
  EXPECT_EQ(quality::inverted_cells(local.after), 0);
  EXPECT_GT(n_local, 0);
  EXPECT_GT(top_all, 100);
  EXPECT_EQ(top_local, 0);
  EXPECT_THROW(
      {
        optimize::ImproveOptions bad = opt;
        bad.changed_nodes = {m.num_nodes()};
        optimize::improve(m, bad);
      },
      GeometryError);
}

// The recommended sequence: a pillowed run below the bar goes on with the pattern search only when
// the run without a layer misses the bar too. A nearly regular grid of cubes (worst SJ near 1, the
// bar): the layer's cells at the cube's edges stay far below it, the run without a layer keeps it,
// so the pillowed run makes its gradient rounds alone (one log line of its worst stage, not two).
TEST(Improve, APillowedRunBelowTheBarSkipsThePatternWhenTheRunWithoutALayerReachesIt) {
  const mesh::Mesh m = cube_grid(4, 0.02);
  optimize::ImproveOptions opt;
  std::vector<std::string> lines;
  opt.log = [&](int, const std::string& s) { lines.push_back(s); };
  const optimize::ImproveResult r = optimize::improve(m, opt);
  int pillowed_stages = 0;
  bool kept_without = false;
  for (const std::string& s : lines) {
    std::printf("%s\n", s.c_str());
    pillowed_stages += s.rfind("pillowed: worst scaled Jacobian", 0) == 0 && s.find(" rounds (") != std::string::npos;
    kept_without |= s.find("kept the result without pillowing") != std::string::npos;
  }
  EXPECT_EQ(r.pillow_cells, 0);
  EXPECT_TRUE(kept_without);
  EXPECT_EQ(pillowed_stages, 1);
  EXPECT_GE(r.after.hex.sj_min, r.before.hex.sj_min);
}

// With optimised_at, the first smoothing pass starts from the changed cells that are inverted,
// below the worst cell as optimised, or above the edge-ratio target (and worse than before):
// smoothing the others only undoes what the mean stage reached. A jittered grid (far from what
// smoothing makes of it) whose centre node moved since it was optimised: a little (its cells change
// by more than 1e-3 and stay above the grid's worst), no node smooths, unless a ratio target lies
// below the largest ratio the move raised; far enough for a cell to fall below the grid's worst,
// or to invert, they smooth.
TEST(Improve, OptimisedAtSmoothsOnlyAroundPoorCells) {
  const mesh::Mesh m = cube_grid(6, 0.15);
  const int centre = 3 + 7 * (3 + 7 * 3);
  optimize::ImproveOptions opt;
  opt.smooth = 1;
  opt.ratio_rounds = 0;  // the ratio stage itself moves nothing: what moves is the smoothing
  opt.optimised_at = m.V;
  struct Moved {
    int nodes = 0;
    double worst_changed = 2, raised_ratio = 0;  // over the cells the move changed
  };
  auto after_moving_centre = [&](const Eigen::RowVector3d& d) {
    mesh::Mesh now = m;
    now.V.row(centre) += d;
    const quality::CellMetrics before = quality::compute_metrics(m), after = quality::compute_metrics(now);
    Moved r;
    for (int c = 0; c < m.num_cells(); ++c) {
      if (!(std::abs(after.scaled_jacobian(c) - before.scaled_jacobian(c)) > 1e-3)) continue;
      r.worst_changed = std::min(r.worst_changed, after.scaled_jacobian(c));
      if (after.edge_ratio(c) > before.edge_ratio(c)) r.raised_ratio = std::max(r.raised_ratio, after.edge_ratio(c));
    }
    const mesh::Mesh out = optimize::improve(now, opt).mesh;
    for (int v = 0; v < m.num_nodes(); ++v) r.nodes += (out.V.row(v) - now.V.row(v)).norm() > 1e-12;
    return r;
  };
  const double worst = sj_of(m).minCoeff();
  const Eigen::RowVector3d little(0.004, 0.003, 0), far(0.15, 0.15, 0.15);
  const Moved a = after_moving_centre(little);
  opt.max_edge_ratio = a.raised_ratio - 1e-9;
  const Moved b = after_moving_centre(little);
  opt.max_edge_ratio = 0;
  const Moved c = after_moving_centre(far);
  Moved d;  // the shortest move along the diagonal that takes a valid cell below the grid's worst
  for (int k = 1; k <= 30 && !(d.worst_changed > 0 && d.worst_changed < worst); ++k) d = after_moving_centre(far * k / 30.0);
  std::printf("grid's worst %.3f; changed cells' worst %.3f: %d nodes smoothed, %d with a ratio target of %.4f; "
              "%.3f: %d; %.3f: %d\n", worst, a.worst_changed, a.nodes, b.nodes, a.raised_ratio, d.worst_changed, d.nodes,
              c.worst_changed, c.nodes);
  ASSERT_LT(a.worst_changed, 2) << "the small move must change cells by more than 1e-3, or the test would not tell";
  ASSERT_GE(a.worst_changed, worst);
  ASSERT_GT(a.raised_ratio, 1);
  ASSERT_LE(c.worst_changed, 0);
  ASSERT_GT(d.worst_changed, 0);
  ASSERT_LT(d.worst_changed, worst);
  EXPECT_EQ(a.nodes, 0);
  EXPECT_GT(b.nodes, 0);
  EXPECT_GT(c.nodes, 0);
  EXPECT_GT(d.nodes, 0);
  // Without optimised_at the same pass smooths the whole grid.
  opt.optimised_at.resize(0, 0);
  const mesh::Mesh out = optimize::improve(m, opt).mesh;
  int all = 0;
  for (int v = 0; v < m.num_nodes(); ++v) all += (out.V.row(v) - m.V.row(v)).norm() > 1e-12;
  EXPECT_GT(all, 100);
}

// With its time budget passed, the improvement ends after its first round: one run, no mean pass,
// still a valid mesh of the same box (no inverted cell, the unit volume), and the log says why.
TEST(Improve, APassedDeadlineStopsAfterOneRoundWithAValidMesh) {
  const mesh::Mesh m = cube_grid(4, 0.35);
  const optimize::ImproveResult full = optimize::improve(m);
  ASSERT_GT(full.rounds, 1) << "the unlimited sequence makes several rounds: the test would not tell";
  EXPECT_FALSE(full.stopped);

  optimize::ImproveOptions opt;
  opt.deadline = Deadline::in(1e-6);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  std::string log;
  opt.log = [&](int, const std::string& s) { log += s + "\n"; };
  const optimize::ImproveResult r = optimize::improve(m, opt);
  EXPECT_TRUE(r.stopped);
  EXPECT_LE(r.rounds, 1);
  EXPECT_NE(log.find("improve: stopped after the time budget of 1e-06 s"), std::string::npos) << log;
  EXPECT_NE(log.find("mean scaled Jacobian"), std::string::npos) << log;
  EXPECT_NE(log.find(" in 0 passes"), std::string::npos) << "a mean pass ran:\n" << log;
  const Eigen::VectorXd sj = sj_of(r.mesh);
  EXPECT_GT(sj.minCoeff(), 0.0);
  EXPECT_EQ(r.after.hex.inverted + r.after.prism.inverted + r.after.tet.inverted, 0);
  EXPECT_NEAR(quality::compute_metrics(r.mesh).volume.sum(), 1.0, 1e-9);

  // Explicit stages: one smoothing pass, no optimisation round.
  opt.smooth = 5;
  opt.optimize = 5;
  const optimize::ImproveResult e = optimize::improve(m, opt);
  EXPECT_TRUE(e.stopped);
  EXPECT_EQ(e.rounds, 1);
  EXPECT_GT(sj_of(e.mesh).minCoeff(), 0.0);
  EXPECT_NEAR(quality::compute_metrics(e.mesh).volume.sum(), 1.0, 1e-9);
}

// A layer of cells squeezed to a tenth of a cell (their scaled Jacobians still high, their edge
// ratios about 12): with max_edge_ratio the nodes of those cells move apart until the ratio is
// below the target, while no type's worst scaled Jacobian drops (the stage's first step reaches
// the target), measured against the same sequence without it.
TEST(Improve, EdgeRatioTargetOpensASqueezedLayerWithoutLoweringTheWorst) {
  mesh::Mesh m = cube_grid(4, 0.08, 11);
  const int k = 5;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) m.V(i + k * (j + k * 2), 2) = m.V(i + k * (j + k * 1), 2) + 0.025;
  auto max_ratio = [](const mesh::Mesh& x) { return quality::compute_metrics(x).edge_ratio.maxCoeff(); };
  const double ratio0 = max_ratio(m);
  ASSERT_GT(ratio0, 9.0);
  ASSERT_GT(sj_of(m).minCoeff(), 0.3);
  optimize::ImproveOptions opt;  // explicit stages: no pillow layer (its own thin cells)
  opt.optimize = 3;
  const optimize::ImproveResult plain = optimize::improve(m, opt);
  opt.max_edge_ratio = 4;
  const optimize::ImproveResult with = optimize::improve(m, opt);
  const Eigen::VectorXd sj_plain = sj_of(plain.mesh), sj_with = sj_of(with.mesh);
  std::printf("edge ratio %.2f -> %.2f without the target, %.2f with it; worst SJ %.4f / %.4f\n", ratio0,
              max_ratio(plain.mesh), max_ratio(with.mesh), sj_plain.minCoeff(), sj_with.minCoeff());
  EXPECT_LE(max_ratio(with.mesh), 4.0 + 1e-9);
  EXPECT_GT(max_ratio(plain.mesh), 4.0) << "the sequence alone mends the ratio: the test would not tell";
  EXPECT_GE(sj_with.minCoeff(), sj_plain.minCoeff() - 1e-12);
  EXPECT_NEAR(quality::compute_metrics(with.mesh).volume.sum(), 1.0, 1e-9);
}

// A layer 0.02-0.024 thick on the bottom face of a 4 x 4 x 4 grid (edge ratio 12.5) under cells
// sheared by 0.6 in x (scaled Jacobian 0.857, the worst, which no optimiser can raise: the part is
// a parallelepiped there). Opening the layer shortens the sheared cells above it and lowers them:
// with the worst cell kept the ratio stage could not open it (7.2 left). It lowers its bar in
// steps towards ratio_sj_floor and stops at the first that reaches the target: here the second,
// half the worst's margin above the floor (0.853 -> 0.582), not the floor itself.
TEST(Improve, EdgeRatioTargetLowersTheWorstCellInStepsNotToTheFloorAtOnce) {
  mesh::Mesh m = cube_grid(4, 0.0);
  for (int v = 0; v < m.num_nodes(); ++v) {
    const long level = std::lround(m.V(v, 2) / 0.25);
    // Heights 0.020-0.024 by node: a uniform layer's cells keep each other's shortest edge.
    const long i = std::lround(m.V(v, 0) / 0.25), j = std::lround(m.V(v, 1) / 0.25);
    if (level == 1) m.V(v, 2) = 0.02 + 0.001 * ((7 * i + 3 * j) % 5);
    if (level >= 1) m.V(v, 0) += 0.6 * (m.V(v, 2) - 0.02);
  }
  auto max_ratio = [](const mesh::Mesh& x) { return quality::compute_metrics(x).edge_ratio.maxCoeff(); };
  const double ratio0 = max_ratio(m), worst0 = sj_of(m).minCoeff();
  ASSERT_GT(ratio0, 12.4);
  ASSERT_NEAR(worst0, 1 / std::sqrt(1.36), 0.005);
  optimize::ImproveOptions opt;  // explicit stages: no pillow layer
  opt.optimize = 3;
  opt.max_edge_ratio = 4;
  const optimize::ImproveResult r = optimize::improve(m, opt);
  const double worst = sj_of(r.mesh).minCoeff();
  std::printf("edge ratio %.2f -> %.2f, worst SJ %.4f -> %.4f\n", ratio0, max_ratio(r.mesh), worst0, worst);
  EXPECT_LE(max_ratio(r.mesh), 4.0 + 1e-9);
  EXPECT_LT(worst, worst0) << "the target was reached with the worst cell kept: the test would not tell";
  EXPECT_GE(worst, opt.ratio_sj_floor + 0.5 * (worst0 - opt.ratio_sj_floor));
  EXPECT_EQ(r.after.hex.inverted, 0);
}

// Two thin layers, 0.102 and 0.103 of the cells' width, the one node inside them (between the
// layers) 0.004 lower: its edge below gives the largest ratio, 10.2. Within the target 10 it must
// lie within a window of 0.005 of the width, narrower than the smallest step of its typical edge
// (about 0.009): such steps swap the largest ratio between the layers (10.16 after one), steps of
// its shortest edge reach the window.
TEST(Improve, EdgeRatioStepsFitTheWindowBetweenTwoThinLayers) {
  mesh::Mesh m = cube_grid(2, 0.0, 7);  // 2 x 2 x 2 cells 0.5 wide
  const double w = 0.5;
  int inside = -1;
  for (int v = 0; v < m.num_nodes(); ++v) {
    const long k = std::lround(m.V(v, 2) / w);
    m.V(v, 2) = k == 0 ? 0.0 : k == 1 ? 0.102 * w : 0.205 * w;
    if (k == 1 && std::lround(m.V(v, 0) / w) == 1 && std::lround(m.V(v, 1) / w) == 1) inside = v;
  }
  ASSERT_GE(inside, 0);
  m.V(inside, 2) -= 0.004 * w;
  auto max_ratio = [](const mesh::Mesh& x) { return quality::compute_metrics(x).edge_ratio.maxCoeff(); };
  ASSERT_NEAR(max_ratio(m), 1 / 0.098, 1e-4);
  optimize::ImproveOptions opt;  // explicit stages; the optimisation moves nothing (every SJ is 1)
  opt.optimize = 1;
  opt.max_edge_ratio = 10;
  const optimize::ImproveResult r = optimize::improve(m, opt);
  std::printf("edge ratio %.3f -> %.3f\n", max_ratio(m), max_ratio(r.mesh));
  EXPECT_LE(max_ratio(r.mesh), 10.0 + 1e-9);
  EXPECT_GT(sj_of(r.mesh).minCoeff(), 0.99);
  EXPECT_NEAR(quality::compute_metrics(r.mesh).volume.sum(), 4 * w * w * 0.205 * w, 1e-12);
}

// The user's Cancel: another thread raises the interrupt the call runs under (common/interrupt.h)
// 0.2 s into an optimisation that takes several seconds; the call throws InterruptedError soon
// after (the bound is generous, the latency itself is bench/bench_cancel.py's), and the input mesh
// is as it was.
TEST(Improve, AnInterruptFromAnotherThreadStopsALongRun) {
  const mesh::Mesh m = test::jittered_cube_grid(40, 0.45, 7);
  const mesh::Mesh copy = m;
  const Interrupt interrupt;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    interrupt.raise();
  });
  const auto t0 = std::chrono::steady_clock::now();
  bool stopped = false;
  try {
    const InterruptScope scope(&interrupt);
    optimize::ImproveOptions opt;
    opt.threads = 2;
    optimize::improve(m, opt);
  } catch (const InterruptedError&) {
    stopped = true;
  }
  const double seconds = seconds_since(t0);
  canceller.join();
  EXPECT_TRUE(stopped) << "the optimisation ended in " << seconds << " s, before the interrupt: a larger grid is needed";
  EXPECT_LT(seconds, 5.0);
  EXPECT_TRUE(copy.V == m.V && copy.cells == m.cells);
}
