// The automatic path (tessellate -> mesh_surface -> snap) on a shared CAD part, where a mechanism
// of the improvement shows on the figures it reaches. Parts built with OpenCASCADE (test_pipeline
// links it when the build has it).
#ifdef HEXDOM_WITH_CAD
#include <Eigen/Core>

#include "cad/cad_test_util.h"
#include "hexdom/pipeline/mesh_surface.h"
#include "hexdom/cad/snap.h"
#include "hexdom/quality/metrics.h"

using namespace hexdom;

// i11o_s1 at the default size (diagonal / 30, level 1): where the R65 round's -Y / +Z label boundary
// meets the plate's faces, cells have two faces on the round. With the tessellation of 2026-11 the
// run without a layer capped there (0.270, 0.267 after the snap) and the layer over the smooth
// regions, checked after its edge nodes went back onto the surface and optimised with the pattern
// search below the bar, gave 0.320 (0.301 after the snap). The remesher's graded split sizes
// (2026-12) give a tessellation on which the candidate without the widths of holes, unpillowed,
// reaches 0.329 (0.322 after the snap). Which candidate wins depends on the triangles; the worst SJ
// of 0.3 before and after the snap is what this part must keep.
TEST(ImproveOnSharedPart, PolycubeMeshOfAPlateWithARoundKeepsTheWorstSJAboveTheBar) {
  const std::string path = test::data_path("cad/i11o_s1.step");
  HEXDOM_REQUIRE_DATA(path);
  const cad::Shape shape = cad::read_shape(path);
  const mesh::SurfaceMesh surface = cad::tessellate(shape, cad::TessellateOptions{});
  pipeline::MeshSurfaceOptions o;
  o.method = pipeline::Method::Polycube;  // auto keeps the overlay mesh here (the polycube's edge ratio is 48)
  const pipeline::MeshSurfaceRun run = pipeline::mesh_surface(surface, o);
  ASSERT_EQ(run.level, 1);
  const Eigen::VectorXd sj = quality::compute_metrics(run.mesh).scaled_jacobian;
  EXPECT_GE(sj.minCoeff(), 0.3);
  const cad::SnapResult snapped = cad::snap_to_brep(shape, run.mesh, surface, cad::SnapOptions{});
  const Eigen::VectorXd sj2 = quality::compute_metrics(snapped.mesh).scaled_jacobian;
  EXPECT_GE(sj2.minCoeff(), 0.3);
  EXPECT_EQ(snapped.quality.hex.inverted, 0);
}

// A cone R25 x 40 at the default size (diagonal / 30): its polycube is a box whose side planes the
// least squares put between the base and the tip, 3 cells of 5.4 across the base of diameter 50, so
// 24 nodes went around the base rim and every ring up the side, and the chords between them cut
// (2 pi / 24)^2 / 6 = 1.14% of the volume away (measured -1.16%, the boundary nodes on the B-rep).
// The rim's quarter arcs now keep cells of their length (PolycubeMapOptions::keep_lengths): 32 nodes.
TEST(AutoPathOnACadPart, AConesRimKeepsEnoughNodesForItsVolume) {
  const cad::Shape shape = cad::read_shape(test::write_part(BRepPrimAPI_MakeCone(25.0, 0.0, 40.0).Shape(), "cone_r25"));
  const mesh::SurfaceMesh surface = cad::tessellate(shape, cad::TessellateOptions{});
  const pipeline::MeshSurfaceRun run = pipeline::mesh_surface(surface);
  const cad::SnapResult snapped = cad::snap_to_brep(shape, run.mesh, surface, cad::SnapOptions{});
  const double volume = M_PI * 25.0 * 25.0 * 40.0 / 3.0;
  EXPECT_NEAR(snapped.quality.total_volume, volume, 0.01 * volume);
  EXPECT_EQ(snapped.quality.hex.inverted + snapped.quality.prism.inverted + snapped.quality.tet.inverted, 0);
  EXPECT_GE(quality::compute_metrics(snapped.mesh).scaled_jacobian.minCoeff(), 0.3);
  EXPECT_LE(snapped.report.max_after, 1e-7 * snapped.report.diagonal);
}

#endif  // HEXDOM_WITH_CAD
