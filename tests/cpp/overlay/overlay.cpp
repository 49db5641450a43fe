// The overlay path: its grid classification, its manifold core, and whole meshes of closed surfaces
// (valid cells, boundary on the surface, volume).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include "autopolycube/auto_test_util.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/overlay/core.h"
#include "hexdom/overlay/grid.h"
#include "hexdom/overlay/overlay.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/quality/report.h"

using namespace hexdom;

namespace {

// An icosahedron subdivided `levels` times, its vertices on the sphere of radius r.
mesh::SurfaceMesh sphere_surface(double r, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> F = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9},  {4, 9, 5},   {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto [it, fresh] = mid.emplace(key, static_cast<int>(V.size()));
      if (fresh) V.push_back((V[a] + V[b]) / 2);
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : F) {
      const int a = middle(f[0], f[1]), b = middle(f[1], f[2]), c = middle(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    F = next;
  }
  mesh::SurfaceMesh s;
  s.V.resize(static_cast<int>(V.size()), 3);
  for (size_t i = 0; i < V.size(); ++i) s.V.row(static_cast<int>(i)) = V[i].normalized().transpose() * r;
  s.F.resize(static_cast<int>(F.size()), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(static_cast<int>(i)) << F[i][0], F[i][1], F[i][2];
  s.patch = Eigen::VectorXi::Ones(s.F.rows());
  return s;
}

int inverted(const quality::QualityReport& q) { return q.hex.inverted + q.prism.inverted + q.tet.inverted; }

// Largest distance of a boundary node of `m` to the surface.
double boundary_distance(const mesh::Mesh& m, const mesh::SurfaceMesh& s) {
  const mesh::TriangleProjector proj(s.V, s.F);
  double worst = 0;
  for (const auto& f : mesh::boundary_faces(m))
    for (int i = 0; i < f.n; ++i) {
      const Eigen::Vector3d p = m.V.row(f.v[i]).transpose();
      worst = std::max(worst, (proj.project(p) - p).norm());
    }
  return worst;
}

double diagonal(const mesh::SurfaceMesh& s) { return (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm(); }

// A hollow sphere, radii 10 and 9: a wall 1 thick.
mesh::SurfaceMesh hollow_sphere() {
  mesh::SurfaceMesh shell = sphere_surface(10.0, 4);
  const mesh::SurfaceMesh inner = sphere_surface(9.0, 4);
  const int n = static_cast<int>(shell.V.rows()), f = static_cast<int>(shell.F.rows());
  shell.V.conservativeResize(2 * n, 3);
  shell.V.bottomRows(n) = inner.V;
  shell.F.conservativeResize(2 * f, 3);
  for (int t = 0; t < f; ++t) shell.F.row(f + t) << inner.F(t, 0) + n, inner.F(t, 2) + n, inner.F(t, 1) + n;  // facing in
  shell.patch = Eigen::VectorXi::Ones(2 * f);
  return shell;
}

}  // namespace

// Nodes strictly inside a box of cells are inside, the others outside; distances in the band are
// the distances to the box.
TEST(OverlayGrid, NodesOfABoxAreClassifiedByTheirSide) {
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, 1, 3.0);  // 6 x 6 x 3
  const overlay::Grid g = overlay::grid_around(s.V, Eigen::Vector3d(0.7, 0.7, 0.7));
  const overlay::NodeField f = overlay::classify_nodes(g, s, 1.0);
  int wrong = 0, checked = 0;
  for (int k = 0; k <= g.nz; ++k)
    for (int j = 0; j <= g.ny; ++j)
      for (int i = 0; i <= g.nx; ++i) {
        const Eigen::Vector3d p = g.position(i, j, k);
        const double d = std::min({p.x(), 6 - p.x(), p.y(), 6 - p.y(), p.z(), 3 - p.z()});
        if (std::abs(d) < 1e-9) continue;
        ++checked;
        wrong += (d > 0) != static_cast<bool>(f.inside[g.node(i, j, k)]);
        if (d > 0 && d < 0.9) {
          EXPECT_NEAR(f.distance[g.node(i, j, k)], d, 1e-12);
        }
      }
  EXPECT_GT(checked, 500);
  EXPECT_EQ(wrong, 0);
}

// A plate gets flat cells and a rod long ones: enough cells across, none longer than the ratio.
TEST(OverlayGrid, ThinPartsGetCellsAcrossWithoutNeedles) {
  const Eigen::Vector3d plate = overlay::grid_spacing({100, 100, 0.5}, 4.7, 3, 5);
  EXPECT_NEAR(plate.z(), 0.5 / 3, 1e-12);
  EXPECT_NEAR(plate.x(), 5 * 0.5 / 3, 1e-12);
  const Eigen::Vector3d rod = overlay::grid_spacing({1000, 1, 1}, 33, 3, 5);
  EXPECT_NEAR(rod.y(), 1.0 / 3, 1e-12);
  EXPECT_NEAR(rod.x(), 5.0 / 3, 1e-12);
  const Eigen::Vector3d block = overlay::grid_spacing({60, 40, 20}, 2.5, 3, 5);
  EXPECT_EQ(block, Eigen::Vector3d(2.5, 2.5, 2.5));
}

// A min size stops the thin-axis rule: the plate gets fewer cells across, none shorter than it, and
// the other axes follow the ratio from there; a min size above the element size gives cubes of it.
TEST(OverlayGrid, AMinSizeBoundsTheCellsAcross) {
  const Eigen::Vector3d plate = overlay::grid_spacing({100, 100, 0.5}, 4.7, 3, 5, 0.25);
  EXPECT_NEAR(plate.z(), 0.25, 1e-12);
  EXPECT_NEAR(plate.x(), 1.25, 1e-12);
  EXPECT_EQ(overlay::grid_spacing({100, 100, 0.5}, 4.7, 3, 5, 0.1), overlay::grid_spacing({100, 100, 0.5}, 4.7, 3, 5));
  EXPECT_EQ(overlay::grid_spacing({100, 100, 0.5}, 2, 3, 5, 9), Eigen::Vector3d(2, 2, 2));
}

// Two cells that share only an edge would give a boundary that is not a manifold: one is dropped.
TEST(OverlayCore, CellsMeetingAlongAnEdgeOnlyLoseOne) {
  overlay::Grid g;
  g.nx = g.ny = g.nz = 4;
  overlay::NodeField f;
  f.inside.assign(g.num_nodes(), 0);
  f.distance.assign(g.num_nodes(), 1.0);
  for (const auto& c : {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{2, 2, 1}})
    for (int64_t n : g.corners(c[0], c[1], c[2])) f.inside[n] = 1;
  const overlay::Core core = overlay::core_cells(g, f, 0.5);
  EXPECT_EQ(core.cells, 1);
  EXPECT_EQ(core.dropped, 1);
  const mesh::Mesh m = overlay::core_mesh(g, core);
  EXPECT_EQ(m.num_cells(), 1);
  EXPECT_EQ(m.num_nodes(), 8);
}

// By centres, a layer of cells one cell thick is a core (by corners it would need three).
TEST(OverlayCore, ALayerOneCellThickKeepsItsCellsByCentres) {
  overlay::Grid g;
  g.nx = g.ny = g.nz = 6;
  const overlay::Grid centres = overlay::cell_centres(g);
  EXPECT_EQ(centres.nx, 5);
  EXPECT_EQ(centres.position(0, 0, 0), Eigen::Vector3d(0.5, 0.5, 0.5));
  overlay::NodeField f;
  f.inside.assign(centres.num_nodes(), 0);
  f.distance.assign(centres.num_nodes(), 0.5);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) f.inside[centres.node(i, j, 2)] = 1;
  const overlay::Core core = overlay::core_cells_by_centres(g, f, 0.1);
  EXPECT_EQ(core.cells, 36);
  EXPECT_EQ(core.dropped, 0);
  EXPECT_EQ(overlay::core_cells_by_centres(g, f, 0.6).cells, 0);  // the centres are 0.5 inside
}

// A slot thinner than the cells between two columns of cells whose centres are all inside: its
// walls face each other, so of each pair of cells across it the one nearer it goes, no kept cell
// faces a kept one across it, and the two sides are apart (the larger kept). A single plane there
// (a surface whose two sides face the same way: no slot) parts nothing.
TEST(OverlayCore, CellsFacingEachOtherAcrossASlotArePartedByCentres) {
  overlay::Grid g;
  g.nx = g.ny = g.nz = 6;
  const overlay::Grid centres = overlay::cell_centres(g);
  overlay::NodeField f;
  f.inside.assign(centres.num_nodes(), 1);
  f.distance.assign(centres.num_nodes(), 0.4);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j) f.distance[centres.node(3, j, k)] = 0.45;  // the far side a little deeper
  // The slot's walls x = 2.95 (facing +x) and x = 3.05 (facing -x), between centres 2.5 and 3.5.
  Eigen::MatrixXd V(8, 3);
  V << 2.95, -1, -1, 2.95, 7, -1, 2.95, 7, 7, 2.95, -1, 7, 3.05, -1, -1, 3.05, 7, -1, 3.05, 7, 7, 3.05, -1, 7;
  Eigen::MatrixXi F(4, 3);
  F << 0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6;
  const mesh::TriangleProjector slot(V, F);
  EXPECT_EQ(overlay::core_cells_by_centres(g, f, 0.1).cells, 216);  // without the surface: every cell
  const overlay::Core core = overlay::core_cells_by_centres(g, f, 0.1, &slot, 0.5);
  EXPECT_EQ(core.parted, 36);
  EXPECT_EQ(core.cells, 108);  // x in 3..6 kept, 0..2 apart
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j) {
      EXPECT_FALSE(core.keep[g.cell(2, j, k)] && core.keep[g.cell(3, j, k)]);
      EXPECT_TRUE(core.keep[g.cell(3, j, k)]);
    }
  const mesh::TriangleProjector plane(V.topRows(4), F.topRows(2));
  EXPECT_EQ(overlay::core_cells_by_centres(g, f, 0.1, &plane, 0.5).parted, 0);
  // Centres deep enough that no slot can pass between them are not looked at.
  f.distance.assign(centres.num_nodes(), 0.5);
  EXPECT_EQ(overlay::core_cells_by_centres(g, f, 0.1, &slot, 0.5).parted, 0);
}

// A box: hexahedra only, none inverted, the volume exact, every corner of the box a node.
TEST(Overlay, ABoxIsMeshedExactly) {
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, 2, 10.0);  // 30 x 20 x 10
  overlay::OverlayOptions o;
  o.size = 2.0;
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.5);
  EXPECT_NEAR(r.quality.total_volume, 6000.0, 1e-6);
  EXPECT_EQ(r.corner_nodes, 8);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9);
  EXPECT_EQ(r.mesh.count(mesh::CellType::Hex), r.mesh.num_cells());
}

// A sphere (no feature at all): valid, on the surface, the volume within 1%.
TEST(Overlay, ASphereIsValidOnItsSurfaceWithItsVolume) {
  const auto s = sphere_surface(20.0, 4);
  const overlay::OverlayResult r = overlay::overlay_mesh(s);
  const double volume = mesh::enclosed_volume(s.V, s.F);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.3);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
  EXPECT_EQ(r.corner_nodes, 0);
  EXPECT_EQ(r.curve_nodes, 0);
}

// A cylinder: its two rims are captured as curves, cells valid, the volume within 1%.
TEST(Overlay, ACylindersRimsAreCurves) {
  const auto s = test::cylinder_surface(10.0, 30.0, 48, 12, 6);
  const overlay::OverlayResult r = overlay::overlay_mesh(s);
  const double volume = mesh::enclosed_volume(s.V, s.F);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
  EXPECT_GT(r.curve_nodes, 20);
}

// A plate 100 x 100 x 0.5 and a rod 1000 x 1 x 1 (the grid's cells flat or long, laid as cubes
// over the stretched surface): valid, on the surface, the volume exact, at least two cells across.
TEST(Overlay, APlateAndARodAreValidWithCellsAcross) {
  for (const Eigen::Vector3d& size : {Eigen::Vector3d(100, 100, 0.5), Eigen::Vector3d(1000, 1, 1)}) {
    SCOPED_TRACE(size.transpose());
    auto s = test::cell_surface({{0, 0, 0}}, 1, 1.0);
    s.V = s.V * size.asDiagonal();
    const overlay::OverlayResult r = overlay::overlay_mesh(s);
    EXPECT_EQ(inverted(r.quality), 0);
    EXPECT_NEAR(r.quality.total_volume, size.prod(), 1e-6 * size.prod());
    EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
    EXPECT_LE(r.thinnest, size.minCoeff() / 2);
    EXPECT_EQ(r.corner_nodes, 8);
  }
}

// An open box (a cup 20 x 20 x 10, walls and floor 1 thick) on a grid of spacing 0.5 laid so that
// two core nodes are equally near each inner corner of the rim: one takes the corner, and the
// other, whose nearest point on its curve is that curve's end, must not be put on the same point
// (a degenerate cell that the optimiser then leaves inverted). The first grid is valid.
TEST(Overlay, NodesBesideACornerAreNotPutOnIt) {
  std::vector<std::array<int, 3>> cells;
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i)
        if (k == 0 || i == 0 || j == 0 || i == 19 || j == 19) cells.push_back({i, j, k});
  const auto cup = test::cell_surface(cells, 1, 1.0);
  overlay::OverlayOptions o;
  o.size = 0.5;
  o.refinements = 0;
  o.refinements_for_quality = 0;
  const overlay::OverlayResult r = overlay::overlay_mesh(cup, o);
  EXPECT_EQ(r.grids, 1);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.3);
  EXPECT_NEAR(r.quality.total_volume, 20 * 20 * 10 - 18 * 18 * 9, 0.01 * 1084);
  EXPECT_LT(boundary_distance(r.mesh, cup), 1e-9 * diagonal(cup));
}

// The wall thickness by area: a slab 10 x 10 x 1 has 200 of its 240 units of area on a wall 1
// thick (top and bottom) and 40 on one 10 thick (the sides).
TEST(OverlayWalls, TheThicknessByArea) {
  std::vector<std::array<int, 3>> cells;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) cells.push_back({i, j, 0});
  const auto slab = test::cell_surface(cells, 1, 1.0);
  EXPECT_NEAR(overlay::wall_thickness(slab, 0.5), 1.0, 1e-12);
  EXPECT_NEAR(overlay::wall_thickness(slab, 0.8), 1.0, 1e-12);
  EXPECT_NEAR(overlay::wall_thickness(slab, 0.9), 10.0, 1e-12);
  EXPECT_EQ(overlay::wall_thickness(mesh::SurfaceMesh{}, 0.5), std::numeric_limits<double>::infinity());
}

// A hollow sphere, radii 10 and 9 (a wall 1 thick): at the default size (the diagonal / 30, 1.15)
// and wall_across 2 the wall gets two cells across on the first grid made; the mesh is valid, on
// the surface, its volume within 1%. Without wall_across (the default) the first grid has cells of
// the size.
TEST(OverlayWalls, AThinWallGetsCellsAcross) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  ASSERT_NEAR(overlay::wall_thickness(shell, 0.5), 1.0, 0.02);
  overlay::OverlayOptions o;
  o.wall_across = 2;
  std::vector<std::string> log;
  o.log = [&](int, const std::string& m) { log.push_back(m); };
  const overlay::OverlayResult r = overlay::overlay_mesh(shell, o);
  EXPECT_LE(r.spacing, 0.52);
  EXPECT_EQ(r.grids, 1);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, shell), 1e-9 * diagonal(shell));
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log.front().find("walls of"), std::string::npos) << log.front();
  o.wall_across = 0;
  o.wall_fallback = 0;  // not the one more grid for inverted cells either (the next test)
  o.refinements = 0;
  o.log = nullptr;
  try {
    EXPECT_GT(overlay::overlay_mesh(shell, o).spacing, 1.1);
  } catch (const GeometryError&) {  // no core on a grid that coarse: fewer cells across too
  }
}

// An empty surface has no mesh: a clear error, not a crash.
TEST(Overlay, AnEmptySurfaceIsAnError) {
  EXPECT_THROW(overlay::overlay_mesh(mesh::SurfaceMesh{}), GeometryError);
}

// A cancelled deadline stops the path with TimeoutError: before it starts, and while it optimises a
// fine grid (auto calls the overlay off this way once the polycube's first mesh is kept).
TEST(Overlay, ACancelledDeadlineStopsIt) {
  const auto s = sphere_surface(20.0, 4);
  overlay::OverlayOptions o;
  o.deadline = Deadline::cancellable();
  o.deadline.cancel();
  EXPECT_THROW(overlay::overlay_mesh(s, o), TimeoutError);
  o.deadline = Deadline::cancellable();
  o.size = 0.8;  // about 70000 cells: seconds of work
  std::thread later([d = o.deadline] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    d.cancel();
  });
  try {
    overlay::overlay_mesh(s, o);
    ADD_FAILURE() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_TRUE(e.cancelled());
    EXPECT_STREQ(e.what(), "overlay: cancelled");
  }
  later.join();
}

// A hollow cube 40 wide with walls of 2, thinner than the default cells (2.3): with one level of
// octree refinement the cells near the walls are split in 27 (transition templates between), and
// the mesh is valid, on the surface, with the solid's volume.
TEST(Overlay, OctreeRefinementMeshesThinWalls) {
  std::vector<std::array<int, 3>> cells;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i)
        if (i == 0 || j == 0 || k == 0 || i == 19 || j == 19 || k == 19) cells.push_back({i, j, k});
  const auto s = test::cell_surface(cells, 1, 2.0);
  overlay::OverlayOptions o;
  o.octree_levels = 1;
  o.refinements = 0;
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  const double volume = 40.0 * 40 * 40 - 36.0 * 36 * 36;
  EXPECT_EQ(r.octree_levels, 1);
  EXPECT_NEAR(r.thinnest, r.spacing / 3, 1e-9);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.2);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
  EXPECT_EQ(r.corner_nodes, 16);
}

// The hollow sphere (wall 1) on a grid of 0.7 with no halving keeps inverted cells and loses most
// of the shell (its core falls apart); the one more grid for the walls (wall_fallback 2: spacing
// 0.5) is kept instead: valid, the volume within 1%.
TEST(OverlayWalls, InvertedCellsOnThinWallsGetOneMoreGridForThem) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  overlay::OverlayOptions o;
  o.size = 0.7;
  o.refinements = 0;
  o.wall_fallback = 0;
  const overlay::OverlayResult without = overlay::overlay_mesh(shell, o);
  ASSERT_GT(inverted(without.quality), 0);
  o.wall_fallback = 2;
  const overlay::OverlayResult with = overlay::overlay_mesh(shell, o);
  EXPECT_EQ(with.grids, without.grids + 1);
  EXPECT_LE(with.spacing, 0.51);
  EXPECT_EQ(inverted(with.quality), 0);
  EXPECT_NEAR(with.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(with.mesh, shell), 1e-9 * diagonal(shell));
}

// The hollow sphere (wall 1) at `size`, whose first grid keeps inverted cells: the grid for the
// walls (spacing 0.5) is made and no halving; valid, the volume within 1%.
namespace {
overlay::OverlayResult walls_grid_without_halving(double size) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  overlay::OverlayOptions o;
  o.size = size;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  overlay::OverlayResult walls = overlay::overlay_mesh(shell, o);
  EXPECT_NE(log.find("for the walls"), std::string::npos) << log;
  EXPECT_EQ(log.find("halving"), std::string::npos) << log;
  EXPECT_NEAR(walls.spacing, 0.5, 0.01);
  EXPECT_EQ(inverted(walls.quality), 0);
  EXPECT_NEAR(walls.quality.total_volume, volume, 0.01 * volume);
  return walls;
}
}  // namespace

// Cheapest first: at size 0.7 the grid for the walls (spacing 0.5, fewer cells than a halving to
// 0.35) comes next and, valid with the volume within 1%, ends the search: no halving. Without it
// the halving is made instead, with more than twice the cells.
TEST(OverlayWalls, TheGridForTheWallsComesBeforeAHalvingWhenItIsCoarser) {
  const overlay::OverlayResult walls = walls_grid_without_halving(0.7);
  overlay::OverlayOptions o;
  o.size = 0.7;
  o.wall_fallback = 0;
  const overlay::OverlayResult halved = overlay::overlay_mesh(hollow_sphere(), o);
  EXPECT_NEAR(halved.spacing, 0.35, 0.01);
  EXPECT_EQ(inverted(halved.quality), 0);
  EXPECT_GT(halved.mesh.num_cells(), 2 * walls.mesh.num_cells());
}

// After a halving too, the grid for the walls comes before the next halving when it is coarser:
// the hollow sphere (wall 1) at size 3.2 keeps inverted cells on its grid of 0.8 (1.25 cells
// across), and the walls' grid (0.5) comes before the halving to 0.4. Meeting every target, it ends
// the search. When it does not (a worst SJ it cannot reach asked for), the halving still follows,
// judged by the grid before it, and the better of the two is kept.
TEST(OverlayWalls, AfterAHalvingTheGridForTheWallsComesFirstWhenCoarser) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  overlay::OverlayOptions o;
  o.size = 3.2;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(shell, o);
  const size_t at_08 = log.find("spacing 0.8:"), walls = log.find(" for the walls:");
  ASSERT_NE(at_08, std::string::npos) << log;
  ASSERT_NE(walls, std::string::npos) << log;
  EXPECT_LT(at_08, walls);
  EXPECT_EQ(log.find("spacing 0.4:"), std::string::npos) << log;
  EXPECT_NEAR(r.spacing, 0.5, 0.01);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GE(quality::worst_sj(r.quality), o.refine_below_sj);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, shell), 1e-9 * diagonal(shell));
  o.refine_below_sj = 0.99;
  log.clear();
  const overlay::OverlayResult halved = overlay::overlay_mesh(shell, o);
  EXPECT_NE(log.find(" for the walls:"), std::string::npos) << log;
  EXPECT_NE(log.find("spacing 0.4:"), std::string::npos) << log;
  EXPECT_EQ(inverted(halved.quality), 0);
  EXPECT_GE(quality::worst_sj(halved.quality), quality::worst_sj(r.quality));
}

// Walls a fifth of a cell thick (the hollow sphere, wall 1, at size 5) need a spacing 10 times
// smaller for their two cells across: the grid for the walls gets it (0.5), where a cap at 8 times
// (max_wall_refinement = 8) leaves them 1.6 cells across (0.625).
TEST(OverlayWalls, WallsAFifthOfACellThickGetTheirTwoCellsAcross) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  overlay::OverlayOptions o;
  o.size = 5;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(shell, o);
  EXPECT_NE(log.find("made 10.0"), std::string::npos) << log;  // 10.01: the wall measures 0.999
  EXPECT_NEAR(r.spacing, 0.5, 0.01);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, shell), 1e-9 * diagonal(shell));
  o.max_wall_refinement = 8;
  log.clear();
  overlay::overlay_mesh(shell, o);
  EXPECT_NE(log.find("made 8.00 times smaller"), std::string::npos) << log;
}

// Not much finer than a halving, the grid for the walls takes its place: at size 1.2 the walls'
// grid (spacing 0.5, 0.83 of the halving's 0.6) is the second grid and the last (a halving would
// leave the wall 1.7 cells across, for 1.7 times fewer cells).
TEST(OverlayWalls, TheGridForTheWallsTakesTheHalvingsPlaceWhenNotMuchFiner) {
  EXPECT_EQ(walls_grid_without_halving(1.2).grids, 2);
}

// Local sizes: the spacing as asked when one of its levels is within 1.2 of the smallest size,
// else the nearest that gives one (at most 1.2 coarser); none for sizes at the spacing or above;
// the min size bounds them.
TEST(LocalSize, TheSmallestSizeIsMetWithinAFifthAtSomeLevel) {
  overlay::LocalLevels l = overlay::local_levels(2.92, {{3, 1.0}, {4, 2.0}}, 0);  // 2.92 / 3 = 0.97
  EXPECT_EQ(l.levels, 1);
  EXPECT_EQ(l.factor, 1.0);
  l = overlay::local_levels(3.0, {{1, 0.1}}, 0);  // 3 / 27 = 0.111
  EXPECT_EQ(l.levels, 3);
  EXPECT_EQ(l.factor, 1.0);
  l = overlay::local_levels(2.92, {{1, 1.5}}, 0);  // level 1 would need 3.75 (1.28 coarser): the grid 1.8
  EXPECT_EQ(l.levels, 0);
  EXPECT_NEAR(2.92 * l.factor, 1.8, 1e-12);
  l = overlay::local_levels(3.0, {{1, 0.45}}, 0);  // level 1 up to 1.62, level 2 from 3.375 (1.125 coarser)
  EXPECT_EQ(l.levels, 2);
  EXPECT_NEAR(3.0 * l.factor, 3.375, 1e-12);
  EXPECT_EQ(overlay::local_levels(3.0, {{1, 2.6}}, 0).levels, 0);
  EXPECT_EQ(overlay::local_levels(3.0, {{1, 2.6}}, 0).factor, 1.0);
  EXPECT_EQ(overlay::local_levels(3.0, {{1, 30.0}}, 0).factor, 1.0);  // no coarsening
  EXPECT_EQ(overlay::local_levels(3.0, {}, 0).levels, 0);
  l = overlay::local_levels(3.0, {{1, 0.1}}, 0.5);  // not below the min size: 0.5, level 1 at 1.8
  EXPECT_EQ(l.levels, 1);
  EXPECT_NEAR(3.0 * l.factor / 3, 0.6, 1e-12);
}

TEST(LocalSize, AFaceThePartLacksOrASizeNotPositiveIsAnInputError) {
  const auto s = test::cell_surface({{0, 0, 0}}, 2, 10.0);
  int top = 0;
  for (int t = 0; t < s.patch.size(); ++t) top = std::max(top, s.patch(t));
  EXPECT_NO_THROW(overlay::check_local_sizes({{s.patch(0), 1.0}}, s));
  try {
    overlay::check_local_sizes({{top + 1, 1.0}}, s, "part.step");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face " + std::to_string(top + 1)), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("part.step"), std::string::npos) << e.what();
  }
  EXPECT_THROW(overlay::check_local_sizes({{s.patch(0), 0.0}}, s), InputError);
  EXPECT_THROW(overlay::check_local_sizes({{s.patch(0), -1.0}}, s), InputError);
}

// A local size on one end of a box 30 x 20 x 10 (element size 2): the quads on that face have
// the size asked (their median within 20%), those on the other end the spacing the size gave, neighbours within a factor 2.2 of each other (the 3-refinement templates' pieces are
// about 2.05 times the small cubes beside them by construction; issue 20 asks 2); valid, the
// volume exact.
TEST(LocalSize, AFaceOfABoxGetsItsSizeGradedToTheRest) {
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, 2, 10.0);
  auto patch_at_x = [&](double x) {
    for (int t = 0; t < s.F.rows(); ++t)
      if (std::abs(s.V(s.F(t, 0), 0) - x) + std::abs(s.V(s.F(t, 1), 0) - x) + std::abs(s.V(s.F(t, 2), 0) - x) < 1e-9)
        return s.patch(t);
    return -1;
  };
  overlay::OverlayOptions o;
  o.size = 2.0;
  o.local_sizes = {{patch_at_x(30.0), 0.5}};
  ASSERT_NE(o.local_sizes[0].patch, patch_at_x(0.0));
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_EQ(r.octree_levels, 1);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.3);
  EXPECT_NEAR(r.quality.total_volume, 6000.0, 0.1);
  const mesh::Mesh& m = r.mesh;
  auto mean_edge = [&](const std::array<int, 4>& q) {
    double e = 0;
    for (int i = 0; i < 4; ++i) e += (m.V.row(q[i]) - m.V.row(q[(i + 1) % 4])).norm() / 4;
    return e;
  };
  std::vector<double> asked, other;
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(m)) {
    const std::array<int, 4> q{f.v[0], f.v[1], f.v[2], f.v[3]};
    bool at30 = true, at0 = true;
    for (int v : q) {
      at30 = at30 && std::abs(m.V(v, 0) - 30) < 1e-9;
      at0 = at0 && std::abs(m.V(v, 0)) < 1e-9;
    }
    if (at30) asked.push_back(mean_edge(q));
    if (at0) other.push_back(mean_edge(q));
  }
  ASSERT_FALSE(asked.empty());
  ASSERT_FALSE(other.empty());
  // The grid's spacing: 1.8 (level 1 at 0.6 is within 1.2 of 0.5; level 2 would need 3.75).
  const double h = 2.0 * overlay::local_levels(2.0, o.local_sizes, 0).factor;
  EXPECT_NEAR(h, 1.8, 1e-9);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  int within = 0;
  for (double e : asked) {
    within += std::abs(e - 0.5) <= 0.1;
    EXPECT_LT(e, 0.85);  // the longest: along the box's edges, where the buffer layer adds to the cells
  }
  EXPECT_NEAR(median(asked), 0.5, 0.1);
  EXPECT_NEAR(median(other), h, 0.2 * h);  // the median: quads along the box's edges are longer
  // Neighbours: sizes (the cube root of the volume) within a factor 2.2.
  std::vector<double> size(m.num_cells());
  for (int c = 0; c < m.num_cells(); ++c)
    size[c] = std::cbrt(quality::volume(mesh::CellType::Hex, quality::cell_points(m, c)));
  double worst = 1;
  for (const auto& [a, b] : mesh::face_neighbours(m))
    worst = std::max(worst, std::max(size[a], size[b]) / std::min(size[a], size[b]));
  std::printf("local size: %zu quads on the face asked (%d within 20%%), %zu on the other end, worst neighbour size "
              "ratio %.2f\n", asked.size(), within, other.size(), worst);
  EXPECT_LE(worst, 2.2);
}

// The growth rate draws the band of each level: a slower growth (1.1) refines a wider band around
// the face (more cells), a faster one (3: only the cells touching the face) a narrower one; the
// quads on the face keep the size asked. Out of (1, 3]: InputError.
TEST(LocalSize, TheGrowthRateWidensOrNarrowsTheRefinedBand) {
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, 2, 10.0);
  int patch = -1;
  for (int t = 0; t < s.F.rows() && patch < 0; ++t)
    if ((s.V(s.F(t, 0), 0) == 30) + (s.V(s.F(t, 1), 0) == 30) + (s.V(s.F(t, 2), 0) == 30) == 3) patch = s.patch(t);
  ASSERT_GE(patch, 0);
  std::map<double, int> cells;
  for (double growth : {1.1, overlay::kGrowthRate, 3.0}) {
    overlay::OverlayOptions o;
    o.size = 2.0;
    o.local_sizes = {{patch, 0.6}};
    o.growth_rate = growth;
    const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
    EXPECT_EQ(inverted(r.quality), 0) << growth;
    EXPECT_EQ(r.octree_levels, 1) << growth;
    cells[growth] = r.mesh.num_cells();
  }
  std::printf("growth 1.1: %d cells, %.3f: %d, 3: %d\n", cells[1.1], overlay::kGrowthRate, cells[overlay::kGrowthRate],
              cells[3.0]);
  EXPECT_GT(cells[1.1], cells[overlay::kGrowthRate]);
  EXPECT_GT(cells[overlay::kGrowthRate], cells[3.0]);
  EXPECT_THROW(overlay::LocalSizeField(s, {{patch, 0.6}}, 1.0), InputError);
  EXPECT_THROW(overlay::LocalSizeField(s, {{patch, 0.6}}, 3.5), InputError);
}

// A local size along a polyline (a CAD edge's points): the box's edge along x at y = z = 0 gets
// boundary nodes about the size apart along it, the parallel edge at y = 20, z = 10 those of the
// spacing; a polyline of one point is an InputError.
TEST(LocalSize, APolylineGetsItsSizeAlongIt) {
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, 2, 10.0);
  overlay::LocalSize edge;
  edge.size = 0.6;
  edge.polyline.resize(31, 3);
  for (int i = 0; i <= 30; ++i) edge.polyline.row(i) << i, 0, 0;
  overlay::OverlayOptions o;
  o.size = 2.0;
  o.local_sizes = {edge};
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_EQ(r.octree_levels, 1);
  auto nodes_along = [&](double y, double z) {
    int n = 0;
    for (int v = 0; v < r.mesh.num_nodes(); ++v) n += std::abs(r.mesh.V(v, 1) - y) < 1e-9 && std::abs(r.mesh.V(v, 2) - z) < 1e-9;
    return n;
  };
  const int near = nodes_along(0, 0), far = nodes_along(20, 10);
  std::printf("nodes along the edge asked: %d, along the far one: %d\n", near, far);
  EXPECT_GE(near, 30 / (0.6 * 1.2));  // 30 long: cells within 20% of 0.6
  EXPECT_LE(near, 30 / (0.6 / 1.2) + 1);
  EXPECT_LT(far, near / 2);
  overlay::LocalSize dot;
  dot.size = 1;
  dot.polyline = Eigen::MatrixXd::Zero(1, 3);
  EXPECT_THROW(overlay::check_local_sizes({dot}, s), InputError);
}

// A box whose top is two coplanar CAD faces (a split face, as FEM users make for a load patch):
// with FeatureOptions::patch_edges (the default) the edge between them is a curve of the features,
// and no boundary face of the overlay's mesh straddles it, so that a load on either face finds all
// of it (12 straddle without). Without it the two faces are one region.
TEST(Overlay, TheEdgeOfASplitFaceIsFollowed) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, 2, 10.0);  // 30 x 20 x 10
  const int split_patch = 100;
  for (int t = 0; t < s.F.rows(); ++t) {
    const Eigen::Vector3d c = (s.V.row(s.F(t, 0)) + s.V.row(s.F(t, 1)) + s.V.row(s.F(t, 2))) / 3;
    if (std::abs(c.z() - 10) < 1e-9 && c.x() < 15) s.patch(t) = split_patch;
  }
  overlay::FeatureOptions joined;
  joined.patch_edges = false;
  EXPECT_EQ(overlay::SurfaceFeatures(s, joined).regions(), 6);
  ASSERT_EQ(overlay::SurfaceFeatures(s).regions(), 7);
  overlay::OverlayOptions o;
  o.size = 2.3;
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_TRUE(r.patch_edges);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_NEAR(r.quality.total_volume, 6000.0, 1e-6);
  int top = 0, straddling = 0;
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(r.mesh)) {
    bool on_top = true, left = false, right = false;
    for (int i = 0; i < f.n; ++i) {
      const Eigen::Vector3d p = r.mesh.V.row(f.v[i]);
      on_top = on_top && std::abs(p.z() - 10) < 1e-9;
      left = left || p.x() < 15 - 1e-9;
      right = right || p.x() > 15 + 1e-9;
    }
    top += on_top;
    straddling += on_top && left && right;
  }
  EXPECT_GT(top, 50);
  EXPECT_EQ(straddling, 0);
}

// A grid for the walls whose spacing a halving already had is not made again: the hollow sphere
// (wall 1) at size 8 (a grid of 6.67 over its extent) has walls of 0.15 cell, so the factor for
// them, cut at 1 / 8 here (max_wall_refinement), gives the spacing 0.83 of the third halving. The
// log says so and the mesh is that of the halvings alone.
TEST(OverlayWalls, TheGridForTheWallsIsNotMadeTwice) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  overlay::OverlayOptions o;
  o.size = 8;
  o.max_wall_refinement = 8;
  o.refinements_for_quality = 0;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(shell, o);
  EXPECT_NE(log.find("the grid for the walls has the spacing 0.833333, already meshed"), std::string::npos) << log;
  EXPECT_EQ(log.find("for the walls:"), std::string::npos) << log;
  EXPECT_NEAR(r.spacing, 20.0 / 24, 1e-9);
  o.wall_fallback = 0;
  o.log = nullptr;
  const overlay::OverlayResult halvings = overlay::overlay_mesh(shell, o);
  EXPECT_EQ(r.grids, halvings.grids);
  EXPECT_EQ(r.mesh.num_cells(), halvings.mesh.num_cells());
}

// A hollow sphere (wall 1) on a grid of spacing 3.6: the coarse grids keep a fraction of the wall,
// with cells inverted; a finer grid follows, so those are not mended (no node is let off its
// feature on them; the log says so), and the mesh kept, of a finer grid, is valid with the volume.
TEST(OverlayWalls, AGridThatLostPartOfTheSolidIsNotMended) {
  const mesh::SurfaceMesh shell = hollow_sphere();
  const double volume = mesh::enclosed_volume(shell.V, shell.F);
  overlay::OverlayOptions o;
  o.size = 3.6;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(shell, o);
  const size_t lost = log.find(" of the solid: its ");
  ASSERT_NE(lost, std::string::npos) << log;
  EXPECT_NE(log.find("inverted cells are left as they are, a finer grid follows", lost), std::string::npos) << log;
  EXPECT_EQ(log.rfind("let off their curves or corners", lost), std::string::npos) << log;
  EXPECT_LT(r.spacing, 1.0);
  EXPECT_EQ(quality::inverted_cells(r.quality), 0) << log;
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume) << log;
}

// A ledge 0.4 high along a block 100 x 100 x 20 whose cells are about 4.8: the two corners at each
// end of the ledge are 0.4 apart, and held there the cells between them would have an edge ratio
// of about 12. Their nodes are let off the corners (the log says so): every cell within the
// edge-ratio target, the mesh valid, on the surface, with the block's volume.
TEST(Overlay, ALedgeFarThinnerThanTheCellsMakesNoNeedleCells) {
  std::vector<std::array<int, 3>> cells;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      cells.push_back({i, j, 0});
      if (i < 5) cells.push_back({i, j, 1});
    }
  mesh::SurfaceMesh s = test::cell_surface(cells, 1, 1.0);
  for (int v = 0; v < s.V.rows(); ++v) {
    const double z = s.V(v, 2);
    s.V.row(v) << 10 * s.V(v, 0), 10 * s.V(v, 1), z <= 1 ? 20 * z : 20 + 0.4 * (z - 1);
  }
  const double volume = 100 * 100 * 20 + 50 * 100 * 0.4;
  ASSERT_NEAR(mesh::enclosed_volume(s.V, s.F), volume, 1e-6);
  overlay::OverlayOptions o;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_NE(log.find("nodes on the ends of the shortest edges let off"), std::string::npos) << log;
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_LE(quality::max_edge_ratio(r.quality), o.max_edge_ratio);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
}

// An L block (a plate 40 x 20 x 8 and an upright 8 x 20 x 30 on its end) on a grid of spacing 2.5
// whose cells by centres jut 0.75 past the upright's side and the plate's top. The quads on the
// core's sides next to those faces take the face they face (their normal line meets it 1.25
// away), not the face they jut past (0.5 from their centroid): the first grid is valid with a
// good worst cell (before: the side quads flattened onto the other face, 6 cells left inverted
// on this grid and the core by corners, worst SJ 0.012, kept instead).
TEST(Overlay, CoreCellsJuttingPastAFaceLeaveTheBufferValid) {
  std::vector<std::array<int, 3>> cells;
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 20; ++i) cells.push_back({i, j, k});
    for (int k = 4; k < 15; ++k)
      for (int i = 0; i < 4; ++i) cells.push_back({i, j, k});
  }
  const auto s = test::cell_surface(cells, 1, 2.0);
  const double volume = 40 * 20 * 8 + 8 * 20 * 22;
  ASSERT_NEAR(mesh::enclosed_volume(s.V, s.F), volume, 1e-6);
  overlay::OverlayOptions o;
  o.size = 2.5;
  o.refinements = 0;
  o.refinements_for_quality = 0;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_EQ(log.find("core by corners"), std::string::npos) << log;
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.5);
  EXPECT_NEAR(r.quality.total_volume, volume, 1e-3 * volume);
  EXPECT_LT(boundary_distance(r.mesh, s), 1e-9 * diagonal(s));
  EXPECT_EQ(r.corner_nodes, 12);
}

// A cylinder R 10 x 30 whose patches are its three faces: the grid's staircase along each rim
// (a circle at an angle to the grid) crosses it, and without pillow_curves some boundary quads
// have their nodes on no common face (a face load in FreeCAD leaves such quads out). With it, the
// rims get a sheet of wedges each side, every boundary quad lies on one face, the mesh is valid,
// conforming (every boundary face on the surface) and keeps the volume within 1%.
TEST(OverlayPillow, ACylindersRimsGetWedgesAndEveryBoundaryQuadLiesOnOneFace) {
  mesh::SurfaceMesh s = test::cylinder_surface(10.0, 30.0, 64, 12, 8);
  const double zmin = s.V.col(2).minCoeff(), zmax = s.V.col(2).maxCoeff();
  for (int t = 0; t < s.F.rows(); ++t) {
    const double z = (s.V(s.F(t, 0), 2) + s.V(s.F(t, 1), 2) + s.V(s.F(t, 2), 2)) / 3;
    s.patch(t) = std::abs(z - zmin) < 1e-9 ? 1 : std::abs(z - zmax) < 1e-9 ? 2 : 3;
  }
  std::vector<std::unique_ptr<mesh::TriangleProjector>> face;  // per patch 1..3
  for (int p = 1; p <= 3; ++p) {
    std::vector<int> keep;
    for (int t = 0; t < s.F.rows(); ++t)
      if (s.patch(t) == p) keep.push_back(t);
    Eigen::MatrixXi F(static_cast<int>(keep.size()), 3);
    for (size_t i = 0; i < keep.size(); ++i) F.row(static_cast<int>(i)) = s.F.row(keep[i]);
    face.push_back(std::make_unique<mesh::TriangleProjector>(s.V, F));
  }
  const double tol = 1e-9 * diagonal(s);
  // Boundary quads of m whose nodes lie on no common face.
  auto crossing = [&](const mesh::Mesh& m) {
    int n = 0;
    for (const mesh::BoundaryFace& f : mesh::boundary_faces(m)) {
      bool on_one = false;
      for (const auto& proj : face) {
        bool all = true;
        for (int i = 0; i < f.n && all; ++i) {
          const Eigen::Vector3d x = m.V.row(f.v[i]);
          all = (proj->project(x) - x).norm() < tol;
        }
        on_one = on_one || all;
      }
      n += !on_one;
    }
    return n;
  };
  const double volume = mesh::enclosed_volume(s.V, s.F);
  overlay::OverlayOptions o;
  o.size = 2.5;
  const overlay::OverlayResult plain = overlay::overlay_mesh(s, o);
  EXPECT_GT(plain.demoted, 0);
  EXPECT_GT(crossing(plain.mesh), 10);
  EXPECT_EQ(plain.mesh.count(mesh::CellType::Wedge), 0);
  o.pillow_curves = true;
  const overlay::OverlayResult r = overlay::overlay_mesh(s, o);
  EXPECT_EQ(inverted(r.quality), 0);
  EXPECT_GT(r.quality.hex.sj_min, 0.3);
  EXPECT_GT(r.quality.prism.sj_min, 0.3);
  EXPECT_EQ(r.demoted, 0);
  EXPECT_GT(r.prisms, 0);
  EXPECT_EQ(r.mesh.count(mesh::CellType::Wedge), r.prisms);
  EXPECT_EQ(crossing(r.mesh), 0);
  EXPECT_LT(boundary_distance(r.mesh, s), tol);
  EXPECT_NEAR(r.quality.total_volume, volume, 0.01 * volume);
}
