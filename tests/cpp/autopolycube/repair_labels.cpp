#include "hexdom/autopolycube/repair_labels.h"

#include "auto_test_util.h"
#include "test_common.h"

using namespace hexdom;

namespace {
std::vector<autopolycube::ChartProblem> problems_of(const mesh::SurfaceMesh& s) {
  auto g = autopolycube::chart_graph(s);
  return autopolycube::chart_problems(s, g, autopolycube::plane_groups(s, g));
}
bool has(const std::vector<autopolycube::ChartProblem>& ps, autopolycube::ProblemKind k) {
  for (const auto& p : ps)
    if (p.kind == k) return true;
  return false;
}
// Triangles whose centroid lies within `r` of point p in every coordinate (a box around p).
std::vector<int> near(const mesh::SurfaceMesh& s, const Eigen::Vector3d& p, double r) {
  std::vector<int> out;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    if ((c - p).cwiseAbs().maxCoeff() < r) out.push_back(f);
  }
  return out;
}
}  // namespace

TEST(ChartProblems, PolycubeLabellingsHaveNone) {
  EXPECT_TRUE(problems_of(test::cell_surface({{0, 0, 0}}, 2)).empty());
  EXPECT_TRUE(problems_of(test::cell_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2)).empty());
  // A ring of 8 cells: charts with holes.
  EXPECT_TRUE(problems_of(test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}}, 2)).empty());
}

TEST(ChartProblems, EachKindIsFoundAndNamed) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  // An island: +X triangles inside the +Z face.
  auto island = s;
  for (int f : near(s, {0.5, 0.5, 1.0}, 0.25)) island.patch(f) = 1;
  auto ps = problems_of(island);
  ASSERT_TRUE(has(ps, autopolycube::ProblemKind::ClosedCurve));
  EXPECT_NE(ps.front().message.find("loop without corners"), std::string::npos) << ps.front().message;
  // Opposite labels side by side: a strip of -X triangles along the top of the +X face.
  auto opposite = s;
  for (int f : near(s, {1.0, 0.5, 0.9}, 0.12)) opposite.patch(f) = 2;
  EXPECT_TRUE(has(problems_of(opposite), autopolycube::ProblemKind::OppositeNeighbours));
  // A chart with only two corners: a lens of +Y triangles across the edge between +X and +Z.
  auto lens = s;
  for (int f : near(s, {1.0, 0.5, 1.0}, 0.12)) lens.patch(f) = 3;
  EXPECT_FALSE(problems_of(lens).empty());
}

TEST(RepairLabels, IslandJoinsItsSurroundings) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  auto bad = s;
  for (int f : near(s, {0.5, 0.5, 1.0}, 0.25)) bad.patch(f) = 1;
  ASSERT_NE(bad.patch, s.patch);
  auto r = autopolycube::repair_labels(bad);
  EXPECT_TRUE(r.remaining.empty());
  EXPECT_EQ(r.relabelled, 1);
  EXPECT_EQ(r.label, s.patch);
}

TEST(RepairLabels, OppositeSliverIsRelabelledAway) {
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 4);
  auto bad = s;
  for (int f : near(s, {2.0, 0.5, 0.9}, 0.12)) bad.patch(f) = 2;
  auto r = autopolycube::repair_labels(bad);
  EXPECT_TRUE(r.remaining.empty());
  EXPECT_GE(r.relabelled, 1);
  bad.patch = r.label;
  EXPECT_TRUE(problems_of(bad).empty());
}

TEST(RepairLabels, RemainingProblemsAreReturnedNotThrown) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  for (int f : near(s, {0.5, 0.5, 1.0}, 0.25)) s.patch(f) = 1;
  autopolycube::RepairOptions opt;
  opt.max_relabels = 0;
  auto r = autopolycube::repair_labels(s, opt);
  EXPECT_FALSE(r.remaining.empty());
  EXPECT_EQ(r.relabelled, 0);
}

TEST(RepairLabels, BandTakesOnlyTheTrianglesNearTheCurveAndAnotherAxis) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  auto g = autopolycube::chart_graph(s);
  // The +Z chart and its curve with the +X chart (the edge x = 1, z = 1).
  int top = -1, curve = -1;
  for (int c = 0; c < g.num_charts(); ++c)
    if (g.label[c] == 5) top = c;
  ASSERT_GE(top, 0);
  for (int ci : g.chart_curves[top])
    if (g.label[g.curves[ci].left] == 1 || g.label[g.curves[ci].right] == 1) curve = ci;
  ASSERT_GE(curve, 0);
  const Eigen::VectorXi l = autopolycube::relabel_band(s, g, top, g.curves[curve].vertices, 0.3);
  int changed = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    const bool in_band = g.chart(f) == top && c.x() > 0.75;  // the column of squares along x = 1
    if (!in_band) {
      EXPECT_EQ(l(f), s.patch(f)) << "triangle " << f;
      continue;
    }
    ++changed;
    EXPECT_NE((l(f) - 1) / 2, 2) << "triangle " << f << " keeps the axis Z";
  }
  EXPECT_EQ(changed, 8);
}

TEST(RepairLabels, OppositeChartsAreRepairedAndTheRestKeepsItsLabels) {
  // Two cells side by side along X; the +Z face of the right cell labelled -Z, next to the +Z face
  // of the left cell (opposite labels along one curve). The repair must leave no problem, and the
  // left cell's +Z face keeps its label.
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}}, 4);
  auto bad = s;
  for (int f : near(s, {1.5, 0.5, 1.0}, 0.5)) bad.patch(f) = 6;
  ASSERT_TRUE(has(problems_of(bad), autopolycube::ProblemKind::OppositeNeighbours));
  auto r = autopolycube::repair_labels(bad);
  EXPECT_TRUE(r.remaining.empty());
  EXPECT_GE(r.banded, 1);  // a bend, not only whole charts
  bad.patch = r.label;
  EXPECT_TRUE(problems_of(bad).empty());
  for (int f : near(s, {0.5, 0.5, 1.0}, 0.4)) EXPECT_EQ(r.label(f), 5) << "triangle " << f;
}

TEST(RepairLabels, ARepairThatCyclesStopsWithTheProblemsLeft) {
  // Whatever the repair does, it ends: either no problem is left or the problems are returned.
  auto s = test::cell_surface({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 4);
  for (int f : near(s, {1.5, 0.5, 1.0}, 0.5)) s.patch(f) = 6;
  for (int f : near(s, {1.5, 0.5, 0.0}, 0.5)) s.patch(f) = 5;
  autopolycube::RepairOptions opt;
  opt.max_relabels = 1000;
  auto r = autopolycube::repair_labels(s, opt);
  EXPECT_LT(r.relabelled, 1000);
  auto t = s;
  t.patch = r.label;
  EXPECT_EQ(problems_of(t).size(), r.remaining.size());
}
