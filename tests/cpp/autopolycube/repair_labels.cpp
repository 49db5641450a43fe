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
