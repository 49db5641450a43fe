#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/autopolycube/map/polycube_map.h"
#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/autopolycube/repair/repair_labels.h"

#include <chrono>
#include <map>
#include <string>
#include <thread>

#include "auto_test_util.h"
#include "hexdom/generation/generate.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/report.h"
#include "hexdom/segmentation/segment_cvt.h"
#include "test_common.h"

using namespace hexdom;

namespace {
autopolycube::AutoPolycubeOptions cell_options(double h, int level) {
  autopolycube::AutoPolycubeOptions o;
  o.level = level;
  o.size = h / (1 << level);
  return o;
}
}  // namespace

TEST(Autopolycube, BoxGivesOneBlockPerCell) {
  // 2 x 1 x 1 box, cells of 0.5: 4 x 2 x 2 blocks, 2 (8 + 8 + 4) boundary squares.
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 3);
  auto r = autopolycube::autopolycube(s, cell_options(0.5, 1));
  EXPECT_EQ(r.blocks, 16);
  EXPECT_EQ(r.structure.num_cells(), 16);
  EXPECT_EQ(r.squares, 40);
  EXPECT_EQ(r.relabelled, 0);
  EXPECT_EQ(r.inverted_blocks, 0);
  EXPECT_NEAR(r.min_block_quality, 1.0, 1e-9);
  // A box is its own polycube: every structure vertex sits on the grid of 0.5.
  for (int v = 0; v < r.structure.num_nodes(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = r.structure.V(v, k) / 0.5;
      EXPECT_NEAR(x, std::round(x), 1e-9) << v;
    }
}

TEST(Autopolycube, EveryPatchIsOneSquareOfTheSurface) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 3);
  auto r = autopolycube::autopolycube(s, cell_options(0.5, 1));
  const auto layout = polycube::patch_layout(r.patches);
  ASSERT_EQ(static_cast<int>(layout.patches.size()), r.squares);
  for (const auto& p : layout.patches) {
    double area = 0;
    for (int f : p.triangles) {
      const Eigen::Vector3d a = r.patches.V.row(r.patches.F(f, 0)), b = r.patches.V.row(r.patches.F(f, 1)),
                            c = r.patches.V.row(r.patches.F(f, 2));
      area += 0.5 * (b - a).cross(c - a).norm();
    }
    EXPECT_NEAR(area, 0.25, 1e-9);
    EXPECT_EQ(p.num_loops, 1);
    EXPECT_EQ(p.corners.size(), 4u);
  }
  // The re-split surface keeps the volume.
  EXPECT_NEAR(test::enclosed_volume(r.patches), 3.0, 1e-9);
}

TEST(Autopolycube, GenerateTakesTheTwoOutputsUnchanged) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 2);
  auto r = autopolycube::autopolycube(s, cell_options(0.5, 1));
  generation::GenerateOptions go;
  go.level = 1;
  const mesh::Mesh m = generation::generate(r.patches, r.structure, go);
  EXPECT_EQ(m.count(mesh::CellType::Hex), 8 * r.blocks);
  const auto q = quality::quality_report(m);
  EXPECT_EQ(q.hex.inverted, 0);
  EXPECT_NEAR(q.hex.sj_min, 1.0, 1e-9);
  EXPECT_NEAR(q.total_volume, 4.0, 1e-9);
}

TEST(Autopolycube, RingWithAHoleWorks) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}}, 2);
  auto r = autopolycube::autopolycube(s, cell_options(1.0, 0));
  EXPECT_EQ(r.blocks, 8);
  EXPECT_EQ(r.inverted_blocks, 0);
}

TEST(Autopolycube, AHolesSideAndAnOuterSideWhoseSpansTouchStayACellApart) {
  // A slab (one cell thick) with a square hole at cell (1, 1). On the +Z chart, the hole's side at
  // x = 2 (y 1..2) and the outer side at x = 3 (y 0..1) are one unit apart and their spans along Y
  // only touch at y = 1; on a grid of 2 units they must still lie on planes in their input order, at
  // least a cell apart, and no chart may fold. (Here the other curves' orders already keep them
  // apart; i11o_s1 is the part where only the touching-span separation does, see test_snap.py.)
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                               {0, 1, 0}, {2, 1, 0}, {3, 1, 0}, {4, 1, 0},
                               {0, 2, 0}, {1, 2, 0}, {2, 2, 0}, {3, 2, 0}, {4, 2, 0}}, 2);
  const auto g = autopolycube::chart_graph(s);
  const auto pg = autopolycube::plane_groups(s, g);
  auto group_at = [&](int label, double x) {  // plane group of the chart of `label` at coordinate x
    for (int f = 0; f < s.F.rows(); ++f)
      if (s.patch(f) == label && std::abs(s.V(s.F(f, 0), 0) - x) < 1e-9) return pg.of_chart[g.region(f)];
    return -1;
  };
  const int hole_side = group_at(2, 2.0), outer_side = group_at(1, 3.0);
  ASSERT_GE(hole_side, 0);
  ASSERT_GE(outer_side, 0);
  autopolycube::PolycubeMapOptions mo;
  mo.cell = 2.0;
  const auto m = autopolycube::polycube_map(s, g, pg, mo);
  EXPECT_GE(m.plane(outer_side) - m.plane(hole_side), 1);
  int flipped = 0;
  for (int n : m.flipped) flipped += n;
  EXPECT_EQ(flipped, 0);
  // The whole step gives blocks, none inverted.
  auto r = autopolycube::autopolycube(s, cell_options(2.0, 1));
  EXPECT_GT(r.blocks, 0);
  EXPECT_EQ(r.inverted_blocks, 0);
}

TEST(Autopolycube, CylinderMapsOntoABoxOfCells) {
  auto s = test::cylinder_surface(1.0, 2.0, 48, 12, 6);
  ASSERT_GT(test::enclosed_volume(s), 0);
  auto r = autopolycube::autopolycube(s, cell_options(0.25, 1));
  EXPECT_GT(r.blocks, 0);
  EXPECT_EQ(r.inverted_blocks, 0);
  generation::GenerateOptions go;
  go.level = 1;
  const mesh::Mesh m = generation::generate(r.patches, r.structure, go);
  optimize::ImproveOptions io;
  io.surface = r.patches;
  const auto imp = optimize::improve(m, io);
  EXPECT_EQ(imp.after.hex.inverted, 0);
  EXPECT_GT(imp.after.hex.sj_min, 0.2);
  EXPECT_NEAR(imp.after.total_volume, test::enclosed_volume(s), 0.01 * test::enclosed_volume(s));
}

TEST(Autopolycube, ProgressKeepsTheLabelsAndThePolycubeWhenItFails) {
  // One +X triangle in the middle of each face: islands, but no relabelling allowed.
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  for (int f = 0; f < s.F.rows(); f += 7) s.patch(f) = s.patch(f) == 1 ? 3 : 1;
  auto o = cell_options(0.5, 1);
  o.max_relabels = 0;
  autopolycube::AutoPolycube progress;
  try {
    autopolycube::autopolycube(s, o, &progress);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("chart"), std::string::npos) << e.what();
  }
  EXPECT_EQ(progress.labels.F.rows(), s.F.rows());
}

// The first repair depends on the labels and the size only: a run at another level handed the first
// run's repair relabels nothing again and builds the same polycube as a run that repairs by itself.
TEST(Autopolycube, ARepairHandedDownIsNotDoneAgain) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 4);
  for (int f = 0; f < s.F.rows(); f += 7) s.patch(f) = s.patch(f) == 1 ? 3 : 1;  // islands to relabel
  auto o = cell_options(0.5, 1);
  int relabels = 0;
  o.log = [&](int, const std::string& m) { relabels += m.rfind("relabelling", 0) == 0; };
  const auto first = autopolycube::autopolycube(s, o);
  ASSERT_GT(relabels, 0);
  EXPECT_GT(first.repaired.relabelled, 0);
  EXPECT_LE(first.repaired.relabelled, first.relabelled);
  EXPECT_EQ(first.repaired.labels.F.rows(), first.labels.F.rows());

  auto fine = o;
  fine.level = 0;
  fine.size = o.size;  // the same element size, a grid of half the spacing
  relabels = 0;
  const auto alone = autopolycube::autopolycube(s, fine);
  EXPECT_GT(relabels, 0);
  relabels = 0;
  fine.repaired = &first.repaired;
  const auto handed = autopolycube::autopolycube(s, fine);
  EXPECT_EQ(relabels, 0);
  EXPECT_EQ(handed.relabelled, alone.relabelled);
  EXPECT_EQ(handed.blocks, alone.blocks);
  EXPECT_EQ(handed.squares, alone.squares);
  ASSERT_EQ(handed.structure.num_nodes(), alone.structure.num_nodes());
  EXPECT_LT((handed.structure.V - alone.structure.V).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE((handed.labels.patch.array() == alone.labels.patch.array()).all());

  // A repaired labelling with fewer triangles than the labels cannot be theirs.
  autopolycube::RepairedLabels small{test::cell_surface({{0, 0, 0}}, 1), 0, 0, {}};
  fine.repaired = &small;
  EXPECT_THROW(autopolycube::autopolycube(s, fine), GeometryError);
}

TEST(Autopolycube, BadArgumentsAreGeometryErrors) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  auto o = cell_options(0.5, 1);
  o.level = 7;
  EXPECT_THROW(autopolycube::autopolycube(s, o), GeometryError);
  o.level = 1;
  o.size = -1;
  EXPECT_THROW(autopolycube::autopolycube(s, o), GeometryError);
  s.patch(0) = 0;
  EXPECT_THROW(autopolycube::autopolycube(s, cell_options(0.5, 1)), GeometryError);
}

// A passed time budget stops the automatic polycube with TimeoutError naming the step, in the
// polycube itself and in its label repair and chart maps; the same calls without it succeed.
TEST(Autopolycube, APassedDeadlineThrowsTimeoutErrorNamingTheStep) {
  auto s = test::cylinder_surface(1.0, 2.0, 48, 12, 6);
  auto o = cell_options(0.25, 1);
  ASSERT_NO_THROW(autopolycube::autopolycube(s, o));
  o.deadline = Deadline::in(1e-6);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  try {
    autopolycube::autopolycube(s, o);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("autopolycube", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("stopped after the time budget of 1e-06 s"), std::string::npos) << e.what();
  }

  // The label repair, on labels with islands to repair.
  auto islands = test::cell_surface({{0, 0, 0}}, 4);
  for (int f = 0; f < islands.F.rows(); f += 7) islands.patch(f) = islands.patch(f) == 1 ? 3 : 1;
  autopolycube::RepairOptions ro;
  ASSERT_GT(autopolycube::repair_labels(islands, ro).relabelled, 0);
  ro.deadline = o.deadline;
  try {
    autopolycube::repair_labels(islands, ro);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_EQ(e.where(), "autopolycube (label repair)");
  }

  // The chart maps.
  const auto g = autopolycube::chart_graph(s);
  const auto pg = autopolycube::plane_groups(s, g);
  autopolycube::PolycubeMapOptions mo;
  mo.cell = 0.25;
  ASSERT_NO_THROW(autopolycube::polycube_map(s, g, pg, mo));
  mo.deadline = o.deadline;
  try {
    autopolycube::polycube_map(s, g, pg, mo);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_EQ(e.where(), "autopolycube (chart maps)");
  }
}

// The paper's raw surfaces that the automatic path meshes with its defaults.
class AutopolycubePaper : public ::testing::TestWithParam<std::string> {};

TEST_P(AutopolycubePaper, SegmentAutopolycubeGenerateImproveHasNoInvertedCell) {
  const std::string path = test::data_path("hexdom/" + GetParam() + "/" + GetParam() + ".k");
  HEXDOM_REQUIRE_DATA(path);
  auto s = io::read_surface(path);
  s.patch = segmentation::segment_cvt(s).label;
  auto r = autopolycube::autopolycube(s);
  EXPECT_EQ(r.inverted_blocks, 0);
  generation::GenerateOptions go;
  go.level = 1;
  const mesh::Mesh m = generation::generate(r.patches, r.structure, go);
  optimize::ImproveOptions io;
  io.surface = r.patches;
  const auto imp = optimize::improve(m, io);
  EXPECT_EQ(imp.after.hex.inverted + imp.after.prism.inverted + imp.after.tet.inverted, 0);
}

INSTANTIATE_TEST_SUITE_P(Models, AutopolycubePaper, ::testing::Values("hepta"));
