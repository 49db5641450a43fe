#include "hexdom/autopolycube/repair/repair_labels.h"

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

// Found by AddressSanitizer (session 18): the turning of a chart's loops was computed along the
// axis "3 - a - b" of each curve's two labels, which for opposite labels (one axis) is 3 or -1,
// and read and wrote past the arrays. Such a chart is reported as OppositeNeighbours only.
TEST(ChartProblems, AChartBesideItsOppositeIsNotJudgedByItsTurning) {
  auto s = test::cell_surface({{0, 0, 0}}, 4);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(1.0, 0.5, 0.9), Eigen::Vector3d(0.5, 0.5, 1.0)}) {
    auto opposite = s;
    for (int f : near(s, p, 0.12)) opposite.patch(f) = opposite.patch(f) % 2 ? opposite.patch(f) + 1 : opposite.patch(f) - 1;
    const auto ps = problems_of(opposite);
    EXPECT_TRUE(has(ps, autopolycube::ProblemKind::OppositeNeighbours));
    for (const auto& pr : ps)
      if (pr.kind == autopolycube::ProblemKind::BadTurning)
        for (int c : pr.charts) EXPECT_GE(c, 0) << pr.message;
  }
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
  for (int ci : g.region_curves[top])
    if (g.label[g.curves[ci].left] == 1 || g.label[g.curves[ci].right] == 1) curve = ci;
  ASSERT_GE(curve, 0);
  const Eigen::VectorXi l = autopolycube::relabel_band(s, g, top, g.curves[curve].vertices, 0.3);
  int changed = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    const bool in_band = g.region(f) == top && c.x() > 0.75;  // the column of squares along x = 1
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

namespace {
// A body [0,4] x [1,3] x [0,6] and a plate [0,1] x [0,3] x [1,7] in front of it (-Y) and above it;
// the plate's underside in front of the body (z = 1, y < 1) labelled -Y. The -Y chart then wraps
// around the lower end of the +X step at x = 1, a tip 1 wide and 5 long: their curve is convex
// along the plate (y = 0, and z = 1 under the step) and concave along the body (y = 1, z 1..6), as
// at a cusp where two tangent surfaces part (i11o_s1: the R65 round and the tube, the tip a crescent
// narrower than a cell).
mesh::SurfaceMesh step_wrapped_by_one_chart() {
  std::vector<std::array<int, 3>> cells;
  for (int x = 0; x < 4; ++x)
    for (int y = 1; y < 3; ++y)
      for (int z = 0; z < 6; ++z) cells.push_back({x, y, z});
  for (int y = 0; y < 3; ++y)
    for (int z = 1; z < 7; ++z)
      if (y == 0 || z == 6) cells.push_back({0, y, z});  // the rest is in the body
  auto s = test::cell_surface(cells, 2);
  for (int f : near(s, {0.5, 0.5, 1.0}, 0.5))
    if (s.patch(f) == 6) s.patch(f) = 4;
  return s;
}
// Lengths of the sharp edges (normals more than 45 degrees apart) between a triangle labelled a and
// one labelled b: [0] convex, [1] concave.
std::array<double, 2> sharp_lengths(const mesh::SurfaceMesh& s, int a, int b) {
  std::map<std::pair<int, int>, std::vector<int>> edge;
  for (int f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      edge[{std::min(u, v), std::max(u, v)}].push_back(f);
    }
  std::array<double, 2> out{0, 0};
  for (const auto& [e, fs] : edge) {
    if (fs.size() != 2) continue;
    int fa = fs[0], fb = fs[1];
    if (s.patch(fa) != a) std::swap(fa, fb);
    if (s.patch(fa) != a || s.patch(fb) != b) continue;
    auto normal = [&](int f) {
      const Eigen::Vector3d p = s.V.row(s.F(f, 0)), q = s.V.row(s.F(f, 1)), r = s.V.row(s.F(f, 2));
      return Eigen::Vector3d((q - p).cross(r - p).normalized());
    };
    const Eigen::Vector3d na = normal(fa), nb = normal(fb);
    if (na.dot(nb) > std::cos(M_PI / 4)) continue;
    const Eigen::Vector3d cb = (s.V.row(s.F(fb, 0)) + s.V.row(s.F(fb, 1)) + s.V.row(s.F(fb, 2))) / 3.0;
    const bool convex = na.dot(cb - Eigen::Vector3d(s.V.row(e.first))) < 0;
    out[convex ? 0 : 1] += (s.V.row(e.first) - s.V.row(e.second)).norm();
  }
  return out;
}
}  // namespace

TEST(MixedConvexityProblems, ACurveConvexInPartAndConcaveInPartIsFound) {
  const auto s = step_wrapped_by_one_chart();
  const auto l = sharp_lengths(s, 1, 4);
  ASSERT_NEAR(l[0], 13.0, 1e-9);  // convex: y = 0 (z 1..7), z = 1 (y 0..1) and the body's x = 4, y = 1
  ASSERT_NEAR(l[1], 5.0, 1e-9);   // concave: y = 1 (z 1..6)
  // Nothing else is wrong with the labelling: chart_problems finds nothing, the mixed curve is found.
  EXPECT_TRUE(problems_of(s).empty());
  const auto ps = autopolycube::mixed_convexity_problems(s, autopolycube::chart_graph(s));
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0].kind, autopolycube::ProblemKind::MixedConvexity);
  EXPECT_NE(ps[0].message.find("(+X"), std::string::npos) << ps[0].message;
  EXPECT_NE(ps[0].message.find("(-Y"), std::string::npos) << ps[0].message;
  EXPECT_NE(ps[0].message.find("7 convex, 5 concave of 12"), std::string::npos) << ps[0].message;  // x = 4: another curve
  // Parts shorter than the minimum length (here the concave one, 5) do not count.
  EXPECT_EQ(autopolycube::mixed_convexity_problems(s, autopolycube::chart_graph(s), 4.9).size(), 1u);
  EXPECT_TRUE(autopolycube::mixed_convexity_problems(s, autopolycube::chart_graph(s), 5.1).empty());
  // A polycube labelling of the same solid (the underside -Z) has no such curve.
  auto plain = s;
  plain.patch = test::labels_from_normals(s);
  EXPECT_TRUE(autopolycube::mixed_convexity_problems(plain, autopolycube::chart_graph(plain)).empty());
}

TEST(RepairLabels, MixedCurveLosesTheTipOfTheChartWrappedAround) {
  // The repair gives the -Y label to the +X step's part in front of the body (y < 1, z < 6), the
  // tip that the -Y chart wraps around (narrower than the band, as i11o_s1's crescent is narrower
  // than a cell), and to nothing else far from it: afterwards the +X / -Y edges are convex only.
  const auto s = step_wrapped_by_one_chart();
  autopolycube::RepairOptions opt;
  opt.band_width = 3.0;
  const auto r = autopolycube::repair_labels(s, opt);
  EXPECT_TRUE(r.remaining.empty());
  EXPECT_GE(r.banded, 1);
  auto t = s;
  t.patch = r.label;
  EXPECT_TRUE(autopolycube::mixed_convexity_problems(t, autopolycube::chart_graph(t)).empty());
  const auto l = sharp_lengths(t, 1, 4);
  EXPECT_EQ(l[1], 0.0) << "concave +X / -Y edges left";
  EXPECT_GE(l[0], 7.0);  // x = 4, and y = 0 above the tip
  int tip = 0, tip_relabelled = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))) / 3.0;
    const bool in_tip = std::abs(c.x() - 1.0) < 1e-9 && c.y() < 1.0 && c.z() < 6.0;
    tip += in_tip;
    if (in_tip) tip_relabelled += r.label(f) == 4;
    if (r.label(f) != s.patch(f)) {
      EXPECT_EQ(s.patch(f), 1) << "triangle " << f;
      EXPECT_EQ(r.label(f), 4) << "triangle " << f;
      EXPECT_LT(c.z(), 6.5) << "triangle " << f << " is far from the tip";
    }
  }
  EXPECT_EQ(tip_relabelled, tip);
}
