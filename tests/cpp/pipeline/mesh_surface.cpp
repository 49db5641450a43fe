#include "hexdom/pipeline/mesh_surface.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "autopolycube/auto_test_util.h"
#include "hexdom/generation/generate.h"
#include "test_common.h"

using namespace hexdom;

namespace {
double volume_error(const pipeline::MeshSurfaceRun& r, double reference) {
  return std::abs(r.quality.total_volume - reference) / reference;
}

// The kept candidate rebuilt stage by stage from the options the run reports, as the workbench's
// objects do it (Segmentation EdgeWeight, Polycube KeepWidths / TetApexes / Level, Mesh Level):
// no repair handed down, no candidate choice.
mesh::Mesh rebuild(const mesh::SurfaceMesh& s, const pipeline::MeshSurfaceOptions& o, const pipeline::MeshSurfaceRun& r) {
  segmentation::CvtOptions so = o.segment;
  so.edge_weight = r.edge_weight;
  mesh::SurfaceMesh labels = s;
  labels.patch = segmentation::segment_cvt(s, so).label;
  autopolycube::AutoPolycubeOptions ao = o.polycube;
  ao.size = o.size;
  ao.level = r.level;
  ao.keep_widths = r.keep_widths;
  ao.collapse_apexes = r.collapse_apexes;
  const auto p = autopolycube::autopolycube(labels, ao);
  generation::GenerateOptions go;
  go.level = r.level;
  go.relax_sweeps = o.relax_sweeps;
  optimize::ImproveOptions io = o.improvement;
  io.surface = p.patches;
  io.max_edge_ratio = o.target_edge_ratio;  // as the pipeline's improvement stage
  return optimize::improve(generation::generate(p.patches, p.structure, go), io).mesh;
}

// The bar with a hole tilted by 40 degrees most tests here mesh, and its options: element size 1,
// level 1, in the model's axes (the bar is tilted whole: in its own frame its hole would not be).
mesh::SurfaceMesh tilted_hole_bar() { return test::holed_bar_surface(4.0, 2.0, 12.0, 8, 24, 4, 40.0 * M_PI / 180.0); }
pipeline::MeshSurfaceOptions tilted_hole_options() {
  pipeline::MeshSurfaceOptions o;
  o.align = false;
  o.size = 1.0;
  o.level = 1;
  return o;
}

void expect_same_mesh(const mesh::Mesh& a, const mesh::Mesh& b) {
  for (auto t : {mesh::CellType::Hex, mesh::CellType::Wedge, mesh::CellType::Tet}) EXPECT_EQ(a.count(t), b.count(t));
  ASSERT_EQ(a.V.rows(), b.V.rows());
  EXPECT_LT((a.V - b.V).cwiseAbs().maxCoeff(), 1e-9);
}
}  // namespace

// A bar with a hole tilted by 40 degrees (diameter 4, cells of 2 at level 1): with the widths of the
// hole kept, the tunnel is 2 x 2 blocks and the volume error less than half of what it is with the
// least-squares offsets alone (a tunnel of 1 x 1 block, the hole carried by 8 nodes around). The
// polycube path alone: under auto the overlay grid may mesh the second run.
TEST(MeshSurface, ATiltedHoleKeepsItsWidthAndTheVolume) {
  const auto s = tilted_hole_bar();
  const double reference = test::enclosed_volume(s);
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.method = pipeline::Method::Polycube;
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_EQ(r.quality.hex.inverted, 0);
  EXPECT_LT(volume_error(r, reference), 0.015) << r.quality.total_volume << " vs " << reference;

  pipeline::MeshSurfaceOptions old = o;
  old.polycube.keep_widths = false;
  old.try_without_widths = false;
  const auto q = pipeline::mesh_surface(s, old);
  // 2.8% without the widths (60 blocks, the tunnel 1 x 1), 1.0% with them (55 blocks, 2 x 2): a
  // 16-gon for the hole instead of an 8-gon.
  EXPECT_LT(volume_error(r, reference), 0.5 * volume_error(q, reference))
      << r.quality.total_volume << " vs " << q.quality.total_volume << " (surface " << reference << ")";
}

// When the first candidate misses a target, the second is meshed and the better kept, and the run
// says which: with an unreachable worst-SJ target both are measured.
TEST(MeshSurface, ASecondCandidateIsMeasuredWhenTheFirstMissesATarget) {
  const auto s = tilted_hole_bar();
  const double reference = test::enclosed_volume(s);
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.target_sj = 2.0;  // no mesh meets it
  o.method = pipeline::Method::Polycube;  // the polycube's own candidates, without the overlay grid
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_NE(log.find("again without keeping the widths of holes"), std::string::npos) << log;
  // Neither meets the SJ target, nor the volume one (1.0% and 2.8%), so the higher worst SJ decides:
  // 0.94 with the widths, 0.88 without.
  EXPECT_NE(log.find("kept the polycube with the widths of holes"), std::string::npos) << log;
  EXPECT_LT(volume_error(r, reference), 0.015);
}

// Once the time budget has passed after the first candidate, no further candidate is tried: the run
// so far is kept and the log says so. (The log line of the first candidate's improvement waits until
// the deadline has passed; the test above shows the second candidate tried without a budget.)
TEST(MeshSurface, NoFurtherCandidateOnceTheTimeBudgetHasPassed) {
  const auto s = tilted_hole_bar();
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.target_sj = 2.0;  // no mesh meets it: without the budget the second candidate is meshed
  o.method = pipeline::Method::Polycube;
  const Deadline deadline = Deadline::in(4.0);  // time for the first candidate (about 0.5 s)
  o.deadline = deadline;
  std::string log;
  o.log = [&](int, const std::string& m) {
    log += m + "\n";
    if (m.rfind("improve:", 0) == 0)
      while (!deadline.passed()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  };
  const auto r = pipeline::mesh_surface(s, o);
  ASSERT_EQ(log.find("stopped"), std::string::npos) << "the first candidate did not finish in time:\n" << log;
  EXPECT_NE(log.find("time budget passed: keeping level 1: worst SJ"), std::string::npos) << log;
  EXPECT_EQ(log.find("again without keeping the widths of holes"), std::string::npos) << log;
  EXPECT_TRUE(r.budget_passed);
  EXPECT_EQ(r.segmentations, 1);
  EXPECT_TRUE(r.keep_widths);
  EXPECT_EQ(r.quality.hex.inverted, 0);
}

// Without a hole keep_widths changes nothing, so the polycube without the widths would be the same
// one again: it is not meshed, even when the first misses a target. (A box of 4 x 4 x 2 cells.)
TEST(MeshSurface, NoSecondCandidateWhenKeepingTheWidthsChangedNothing) {
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 2; ++k) cells.push_back({i, j, k});
  const auto s = test::cell_surface(cells, 2);
  pipeline::MeshSurfaceOptions o;
  o.align = false;  // the bar is tilted whole: in its own frame its hole would not be tilted
  o.size = 0.5;
  o.level = 1;
  o.target_sj = 2.0;  // no mesh meets it
  o.method = pipeline::Method::Polycube;  // the polycube's own candidates, without the overlay grid
  o.refine_when_inverted = false;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_EQ(r.polycube.widened, 0);
  EXPECT_EQ(log.find("without keeping the widths of holes"), std::string::npos) << log;
  EXPECT_EQ(r.segmentations, 1);

  // The tilted hole's walls are kept apart: there the second candidate is meshed (test above).
  const auto h = tilted_hole_bar();
  o.size = 1.0;
  EXPECT_GT(pipeline::mesh_surface(h, o).polycube.widened, 0);
}

// The second candidate (without the widths of holes) and a finer level take the first candidate's
// label repair instead of repairing the same labelling again.
TEST(MeshSurface, TheLabelRepairRunsOncePerRun) {
  auto s = tilted_hole_bar();
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.target_sj = 2.0;  // no mesh meets it: both candidates are meshed
  o.method = pipeline::Method::Polycube;  // the polycube's own candidates, without the overlay grid
  o.verbose = true;
  std::string log;
  int repairs = 0, handed = 0;
  o.log = [&](int, const std::string& m) {
    log += m + "\n";
    handed += m.rfind("labels: the repair of an earlier run", 0) == 0;
    repairs += m.rfind("autopolycube:", 0) == 0;
  };
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_EQ(repairs, 2) << log;  // two candidates
  EXPECT_EQ(handed, 1) << log;   // the second one took the first one's repair
  EXPECT_EQ(r.quality.hex.inverted, 0);
}

// Auto's further candidates start from its first run (MeshSurfaceOptions::first_run): that one is
// not segmented, repaired nor meshed again, and the result is the one the whole chain gives.
TEST(MeshSurface, TheCandidatesStartFromTheFirstRunGiven) {
  const auto s = tilted_hole_bar();
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.target_sj = 2.0;  // no mesh meets it: the second candidate is meshed
  o.method = pipeline::Method::Polycube;
  o.refine_when_inverted = false;
  int segmentations = 0;
  o.log = [&](int, const std::string& m) { segmentations += m.rfind("segment:", 0) == 0; };
  const auto whole = pipeline::mesh_surface(s, o);
  EXPECT_EQ(segmentations, 2);  // the first candidate and the one without the widths
  pipeline::MeshSurfaceOptions first = o;
  first.try_without_widths = false;
  const auto one = pipeline::mesh_surface(s, first);
  segmentations = 0;
  o.first_run = &one;
  const auto rest = pipeline::mesh_surface(s, o);
  EXPECT_EQ(segmentations, 1);  // the one without the widths only
  EXPECT_EQ(rest.keep_widths, whole.keep_widths);
  expect_same_mesh(rest.mesh, whole.mesh);
}

// The run reports the options of the candidate it kept (level, lambda, widths of holes, tet or hex
// blocks at apexes), and they rebuild that very mesh without the choice: what Mesh Part sets on
// its objects. Tilted hole: with an unreachable SJ target both width candidates are measured and
// the one with the widths kept; with keep_widths off from the start, it says so.
TEST(MeshSurface, TheKeptCandidatesOptionsAreReportedAndRebuildItsMesh) {
  const auto s = tilted_hole_bar();
  pipeline::MeshSurfaceOptions o = tilted_hole_options();
  o.target_sj = 2.0;  // no mesh meets it: both candidates are measured
  o.method = pipeline::Method::Polycube;  // the polycube's own candidates, without the overlay grid
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_NE(log.find("kept the polycube with the widths of holes"), std::string::npos) << log;
  EXPECT_TRUE(r.keep_widths);
  EXPECT_TRUE(r.collapse_apexes);  // the default; no apex here
  EXPECT_EQ(r.edge_weight, 0.1);
  EXPECT_NE(pipeline::choice_text(r).find("level " + std::to_string(r.level) + ", lambda 0.1"), std::string::npos) << pipeline::choice_text(r);
  EXPECT_NE(pipeline::choice_text(r).find("widths of holes kept"), std::string::npos);
  EXPECT_NE(pipeline::to_text(r).find("kept          level"), std::string::npos) << pipeline::to_text(r);
  expect_same_mesh(rebuild(s, o, r), r.mesh);

  pipeline::MeshSurfaceOptions old = o;
  old.polycube.keep_widths = false;
  old.refine_when_inverted = false;
  const auto q = pipeline::mesh_surface(s, old);
  EXPECT_FALSE(q.keep_widths);
  EXPECT_EQ(q.level, 1);
  EXPECT_NE(pipeline::choice_text(q).find("level 1, lambda 0.1, least-squares plane offsets"), std::string::npos)
      << pipeline::choice_text(q);
  expect_same_mesh(rebuild(s, old, q), q.mesh);
}

// A pyramid's tip: tet blocks first; when their mesh misses the targets the hex blocks under the cap
// are measured too. The run says which it kept, its mesh has tets exactly when it kept the tet
// blocks, and the reported options rebuild it. One level only, so that the log's choice is the
// kept mesh's (a second level makes the choice again).
TEST(MeshSurface, TheKeptApexBlocksAreReportedAndRebuildTheMesh) {
  const auto s = test::pyramid_surface(4.0, 3.0, 16);
  pipeline::MeshSurfaceOptions o;
  o.size = 0.25;
  o.level = 1;
  o.refine_when_inverted = false;
  o.refine_below_sj = 0;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_EQ(r.polycube.apexes, 1);
  const bool tets = log.find("kept the tet blocks at the apexes") != std::string::npos ||
                    log.find("with tet blocks at the apexes: again") == std::string::npos;
  EXPECT_EQ(r.collapse_apexes, tets) << log;
  EXPECT_EQ(r.mesh.count(mesh::CellType::Tet) > 0, r.collapse_apexes) << log;
  EXPECT_NE(pipeline::choice_text(r).find(r.collapse_apexes ? "tet blocks at apexes" : "hex blocks under the caps"),
            std::string::npos)
      << pipeline::choice_text(r);
  expect_same_mesh(rebuild(s, o, r), r.mesh);

  pipeline::MeshSurfaceOptions hex = o;  // the hex blocks asked for: reported as such
  hex.polycube.collapse_apexes = false;
  const auto h = pipeline::mesh_surface(s, hex);
  EXPECT_FALSE(h.collapse_apexes);
  EXPECT_EQ(h.mesh.count(mesh::CellType::Tet), 0);
}

// A part lying at an angle is segmented and given its polycube in the frame its faces fit: turned
// 30 degrees about (1, 2, 3), an L of boxes gives the mesh it gives square to the axes (the same
// cells, the worst SJ within what the improvement's axis-bound searches make of the turn), in the
// turned part's own coordinates; in the model's axes (align off) its faces lean between labels and
// the labelling needs repairs.
TEST(MeshSurface, APartLyingAtAnAngleIsMeshedInTheFrameItsFacesFit) {
  const auto square = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {2, 0, 1}}, 3);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const auto turned = segmentation::rotated(square, R);
  pipeline::MeshSurfaceOptions o;
  o.size = 0.25;
  const auto a = pipeline::mesh_surface(square, o);
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto b = pipeline::mesh_surface(turned, o);
  EXPECT_FALSE(a.frame.turned());
  ASSERT_TRUE(b.frame.turned());
  EXPECT_NE(log.find("frame: the faces fit the axes turned by 30.0 degrees"), std::string::npos) << log;
  EXPECT_NE(pipeline::choice_text(b).find("frame: the axes turned by 30.0 degrees"), std::string::npos);
  for (auto t : {mesh::CellType::Hex, mesh::CellType::Wedge, mesh::CellType::Tet}) EXPECT_EQ(a.mesh.count(t), b.mesh.count(t));
  EXPECT_EQ(b.polycube.relabelled, 0);
  EXPECT_EQ(b.quality.hex.inverted, 0);
  EXPECT_NEAR(b.quality.hex.sj_min, a.quality.hex.sj_min, 0.05);
  EXPECT_NEAR(b.quality.total_volume, a.quality.total_volume, 1e-6 * a.quality.total_volume);
  // Everything is in the turned part's coordinates, and the polycube is square to the frame: its
  // faces' normals, turned back by R, lie along the axes.
  auto square_share = [&](const mesh::SurfaceMesh& p) {
    double on = 0, all = 0;
    for (int f = 0; f < p.F.rows(); ++f) {
      const Eigen::RowVector3d x0 = p.V.row(p.F(f, 0)), x1 = p.V.row(p.F(f, 1)), x2 = p.V.row(p.F(f, 2));
      const Eigen::RowVector3d n = (x1 - x0).cross(x2 - x0) * R;
      all += n.norm();
      if (n.norm() > 0 && n.cwiseAbs().maxCoeff() > 0.999 * n.norm()) on += n.norm();
    }
    return all > 0 ? on / all : 0.0;
  };
  EXPECT_GT(square_share(b.polycube.polycube), 0.999);
  const Eigen::RowVector3d lo = turned.V.colwise().minCoeff(), hi = turned.V.colwise().maxCoeff();
  for (int v = 0; v < b.mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(b.mesh.V(v, k), lo(k) - 1e-6);
      EXPECT_LE(b.mesh.V(v, k), hi(k) + 1e-6);
    }
  // In the model's axes the polycube is square to those instead.
  o.align = false;
  o.log = nullptr;
  const auto c = pipeline::mesh_surface(turned, o);
  EXPECT_FALSE(c.frame.turned());
  EXPECT_LT(square_share(c.polycube.polycube), 0.5);
}

TEST(MeshSurface, SeparateSolidsAreMeshedEachAsARegion) {
  // An L of three unit cells and, apart from it, a bar of two, scaled by 10.
  const auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 0, 0}, {3, 0, 1}}, 3, 10.0);
  pipeline::MeshSurfaceOptions o;
  o.size = 2.5;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const auto r = pipeline::mesh_surface(s, o);
  ASSERT_EQ(r.solids.size(), 2u);
  EXPECT_NE(log.find("solid 2 of 2"), std::string::npos) << log;
  EXPECT_EQ(r.mesh.num_cells(), r.solids[0].mesh.num_cells() + r.solids[1].mesh.num_cells());
  EXPECT_EQ(r.mesh.num_nodes(), r.solids[0].mesh.num_nodes() + r.solids[1].mesh.num_nodes());
  EXPECT_EQ(quality::inverted_cells(r.quality), 0);
  int cells[2] = {0, 0};
  const auto q = quality::quality_report(r.mesh);
  EXPECT_NEAR(q.total_volume, 5000.0, 1e-6);
  for (int c = 0; c < r.mesh.num_cells(); ++c) {
    const int k = r.mesh.region(c) - 1;
    ASSERT_TRUE(k == 0 || k == 1) << r.mesh.region(c);
    for (int j = 0; j < mesh::node_count(r.mesh.type(c)); ++j)  // solid 1 lies in x <= 20, solid 2 in x >= 30
      EXPECT_TRUE(k == 0 ? r.mesh.V(r.mesh.cells(c, j), 0) <= 20 + 1e-9 : r.mesh.V(r.mesh.cells(c, j), 0) >= 30 - 1e-9);
    ++cells[k];
  }
  EXPECT_EQ(cells[0], r.solids[0].mesh.num_cells());
  EXPECT_EQ(cells[1], r.solids[1].mesh.num_cells());
  EXPECT_NEAR(r.solids[0].quality.total_volume, 3000.0, 1e-6);
  EXPECT_NEAR(r.solids[1].quality.total_volume, 2000.0, 1e-6);
  EXPECT_EQ(r.labels.F.rows(), s.F.rows());
  EXPECT_NE(pipeline::choice_text(r).find("2 solids; solid 1: "), std::string::npos) << pipeline::choice_text(r);
}

TEST(MeshSurface, APlateAndARodGetCellsAcrossWithoutNeedles) {
  // 100 x 100 x 0.5 and 1000 x 1 x 1 boxes: the default size (diagonal / 30) is 4.7 and 33, many times
  // their thickness. Cubic cells would give two layers of needles (edge ratio 18 and 66).
  for (const Eigen::Vector3d dims : {Eigen::Vector3d(100, 100, 0.5), Eigen::Vector3d(1000, 1, 1)}) {
    auto s = test::cell_surface({{0, 0, 0}}, 1);  // two triangles per face, as STL exports write a box
    s.V = s.V * dims.asDiagonal();
    pipeline::MeshSurfaceOptions o;
    o.method = pipeline::Method::Polycube;
    std::string log;
    o.log = [&](int, const std::string& m) { log += m + "\n"; };
    const auto r = pipeline::mesh_surface(s, o);
    EXPECT_NE(log.find("thin part: cells of"), std::string::npos) << log;
    EXPECT_EQ(quality::inverted_cells(r.quality), 0);
    EXPECT_GT(r.quality.hex.sj_min, 0.99) << log;
    EXPECT_NEAR(r.mesh.num_cells(), dims(2) < 1 ? 80 * 80 * 2 : 400 * 2 * 2, 0);
    EXPECT_LE(quality::max_edge_ratio(r.quality), 5.0 + 1e-6) << dims.transpose();
    EXPECT_NEAR(r.quality.total_volume, dims.prod(), 1e-6 * dims.prod());
    // At least two cells across each thin axis: three distinct node coordinates along it.
    for (int a = 0; a < 3; ++a) {
      if (dims(a) > 1) continue;
      std::vector<double> c(r.mesh.V.col(a).data(), r.mesh.V.col(a).data() + r.mesh.V.rows());
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end(), [](double x, double y) { return std::abs(x - y) < 1e-9; }), c.end());
      EXPECT_GE(c.size(), 3u) << "axis " << a;
    }
    // The labels and the polycube's patches are in the model's coordinates, as for any part.
    EXPECT_NEAR(r.labels.V.col(0).maxCoeff(), dims(0), 1e-9);
    EXPECT_NEAR(r.polycube.patches.V.col(2).maxCoeff(), dims(2), 1e-9);
  }
}

// The bounds on the element size: a default size above the max size is brought down to it (and a
// given one too), one below the min size up; a min size above the max size is refused.
TEST(MeshSurface, TheElementSizeIsKeptWithinTheMinAndMaxSize) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.V = s.V * Eigen::Vector3d(60, 30, 15).asDiagonal();  // diagonal 73.5: default size 2.45
  pipeline::MeshSurfaceOptions o;
  EXPECT_NEAR(pipeline::element_size(s, o), std::sqrt(60.0 * 60 + 30 * 30 + 15 * 15) / 30, 1e-12);
  o.max_size = 1.5;
  EXPECT_EQ(pipeline::element_size(s, o), 1.5);
  o.size = 4;
  EXPECT_EQ(pipeline::element_size(s, o), 1.5);
  o = {};
  o.min_size = 3;
  EXPECT_EQ(pipeline::element_size(s, o), 3);
  o.max_size = 2;
  EXPECT_THROW(pipeline::element_size(s, o), InputError);
  o = {};
  o.min_size = -1;
  EXPECT_THROW(pipeline::bounded_size(1, o), InputError);
}

// The max size reaches both paths: the box's cells are about that long (the polycube rounds each
// block count to the nearest whole number, up to 1.25 x at level 1; the overlay's buffer cells
// reach the surface),
// well below the default size, and there are several times the default's cells.
TEST(MeshSurface, TheMaxSizeBoundsTheCellsOfBothPaths) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.V = s.V * Eigen::Vector3d(20, 2, 2).asDiagonal();  // default size 0.67
  for (auto method : {pipeline::Method::Polycube, pipeline::Method::Overlay}) {
    pipeline::MeshSurfaceOptions o;
    o.method = method;
    o.max_size = 0.4;
    const auto r = pipeline::mesh_surface(s, o);
    o.max_size = 0;
    const int default_cells = pipeline::mesh_surface(s, o).mesh.num_cells();
    EXPECT_EQ(quality::inverted_cells(r.quality), 0);
    EXPECT_NEAR(r.quality.total_volume, 80, 1e-6 * 80);
    std::vector<double> lengths;
    static const int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                      {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    ASSERT_EQ(r.mesh.count(mesh::CellType::Hex), r.mesh.num_cells());
    for (int c = 0; c < r.mesh.num_cells(); ++c)
      for (const auto& e : kEdges)
        lengths.push_back((r.mesh.V.row(r.mesh.cells(c, e[0])) - r.mesh.V.row(r.mesh.cells(c, e[1]))).norm());
    std::sort(lengths.begin(), lengths.end());
    const double p95 = lengths[lengths.size() * 95 / 100];
    // (the polycube: 2 / 0.8 = 2.5 blocks across rounded to 2, cells of 0.5 there, 0.4 along)
    EXPECT_LE(lengths[lengths.size() / 2], method == pipeline::Method::Overlay ? 0.4 * 1.01 : 0.5 * 1.01);
    EXPECT_LE(p95, 0.4 * 1.3) << pipeline::method_name(method);
    EXPECT_GT(r.mesh.num_cells(), 3 * default_cells) << pipeline::method_name(method);
  }
}

// A min size keeps the plate's cells from getting thinner than it: one cell across instead of two
// (80 x 80 x 2 without it), and still no needles.
TEST(MeshSurface, AMinSizeGivesAThinPlateFewerCellsAcross) {
  auto s = test::cell_surface({{0, 0, 0}}, 1);
  s.V = s.V * Eigen::Vector3d(100, 100, 0.5).asDiagonal();
  pipeline::MeshSurfaceOptions o;
  o.method = pipeline::Method::Polycube;
  o.min_size = 0.5;
  const auto r = pipeline::mesh_surface(s, o);
  EXPECT_EQ(r.mesh.num_cells(), 40 * 40 * 1);
  EXPECT_LE(quality::max_edge_ratio(r.quality), 5.0 + 1e-6);
  EXPECT_GT(r.quality.hex.sj_min, 0.99);
  o.min_size = 0;
  o.across_thin = 4;  // cells across: four, the other sides at most 5 times as long
  const auto r4 = pipeline::mesh_surface(s, o);
  EXPECT_EQ(r4.mesh.num_cells(), 160 * 160 * 4);
  EXPECT_LE(quality::max_edge_ratio(r4.quality), 5.0 + 1e-6);
}
