// How a mesh meets local sizes (local_size_fit), and the automatic choice's place for it: after
// the quality targets, before the edge ratio and the worst SJ.
#include <gtest/gtest.h>

#include "hex_grid.h"
#include "hexdom/pipeline/local_refinement.h"
#include "segmentation/seg_test_util.h"

using namespace hexdom;

namespace {

// A 6 x 6 x 6 cube of unit cells and its surface: patches 1-4 the sides (1: y = 0), 5 the top
// (z = 6), 6 the bottom.
struct Cube {
  mesh::Mesh mesh = test::jittered_cube_grid(6, 0.0, 1);
  mesh::SurfaceMesh surface = test::extruded_polygon(
      {{{0, 0}, {6, 0}}, {{6, 0}, {6, 6}}, {{6, 6}, {0, 6}}, {{0, 6}, {0, 0}}}, 6.0, 3);
};

overlay::LocalSize on_face(int patch, double size) { return overlay::LocalSize{patch, size, {}}; }

overlay::LocalSize along(const Eigen::MatrixXd& polyline, double size) {
  overlay::LocalSize l;
  l.size = size;
  l.polyline = polyline;
  return l;
}

pipeline::MeshSurfaceRun run_meeting(int met, int asked) {
  pipeline::MeshSurfaceRun r;
  r.quality.hex.count = 10;
  r.quality.total_volume = 1.0;
  r.quality.hex.sj_min = 0.5;
  r.quality.hex.edge_ratio_max = 2;
  r.local_fit.ratio.assign(asked, 1.0);
  r.local_fit.met = met;
  return r;
}

}  // namespace

TEST(LocalSizeFit, MeasuresTheCellsOnTheFacesAndAlongTheLinesAsked) {
  const Cube c;
  Eigen::MatrixXd rim(3, 3), inside(2, 3);
  rim << 0, 0, 6, 3, 0, 6, 6, 0, 6;  // the top's edge over the side y = 0
  inside << 3, 3, 1, 3, 3, 5;        // through the inside: no boundary edge along it
  const pipeline::LocalSizeFit fit = pipeline::local_size_fit(
      c.mesh, c.surface, {on_face(5, 1.0), on_face(1, 1.15), on_face(6, 2.0), along(rim, 1.0), along(inside, 1.0)});
  ASSERT_EQ(fit.ratio.size(), 5u);
  EXPECT_NEAR(fit.ratio[0], 1.0, 1e-12);
  EXPECT_NEAR(fit.ratio[1], 1 / 1.15, 1e-12);
  EXPECT_NEAR(fit.ratio[2], 0.5, 1e-12);  // cells half the size asked: not met
  EXPECT_NEAR(fit.ratio[3], 1.0, 1e-12);
  EXPECT_EQ(fit.ratio[4], 0.0);
  EXPECT_EQ(fit.met, 3);
  EXPECT_FALSE(fit.all_met());
  EXPECT_TRUE(pipeline::local_size_fit(c.mesh, c.surface, {}).ratio.empty());
  EXPECT_EQ(pipeline::local_fit_text(fit, {on_face(5, 1.0), on_face(1, 1.15), on_face(6, 2.0), along(rim, 1.0),
                                           along(inside, 1.0)}),
            "local sizes: cells 1.00 of the size on Face5, 0.87 of the size on Face1, 0.50 of the size on Face6, "
            "1.00 of the size along an edge, 0.00 of the size along an edge (3 of 5 within 20%)");
}

// More local sizes met comes after the volume target and before the edge ratio and the worst SJ;
// a mesh that misses one is not kept by auto without the other path.
TEST(LocalSizeFit, TheChoiceWeighsItAfterTheQualityTargets) {
  const pipeline::MeshSurfaceOptions o;
  pipeline::MeshSurfaceRun met = run_meeting(1, 1), missed = run_meeting(0, 1);
  missed.quality.hex.sj_min = 0.9;
  EXPECT_TRUE(pipeline::better_run(met, missed, 1.0, o));
  EXPECT_FALSE(pipeline::better_run(missed, met, 1.0, o));
  EXPECT_TRUE(pipeline::meets_path_targets(met, 1.0, o));
  EXPECT_FALSE(pipeline::meets_path_targets(missed, 1.0, o));
  EXPECT_TRUE(pipeline::meets_targets(missed, 1.0, o));
  met.quality.hex.sj_min = 0.2;  // below the SJ target: the SJ decides first
  EXPECT_TRUE(pipeline::better_run(missed, met, 1.0, o));
  met.quality.hex.sj_min = 0.5;
  met.quality.total_volume = 1.5;  // volume off: so does the volume
  EXPECT_TRUE(pipeline::better_run(missed, met, 1.0, o));
}
