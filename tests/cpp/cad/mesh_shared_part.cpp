// The automatic path (tessellate -> mesh_surface -> snap) on a shared CAD part, where a mechanism
// of the improvement shows on the figures it reaches.
#include <Eigen/Core>

#include "cad_test_util.h"
#include "hexdom/autopolycube/mesh_surface.h"
#include "hexdom/cad/snap.h"
#include "hexdom/quality/metrics.h"

using namespace hexdom;

// i11o_s1 at the default size (diagonal / 30, level 1): where the R65 round's -Y / +Z label boundary
// meets the plate's faces, cells have two faces on the round. The run without a layer caps there
// (0.270, 0.267 after the snap). The layer over the smooth regions was inverted at the arm's R11
// hole rim (-0.084) once its edge nodes went back onto the surface, and, made valid, its gradient
// rounds stalled at the x = 16 crescent (0.158), where a layer cell's face has two edges on the R65
// arc. Now the layer is checked after that projection and the run goes on with the pattern search
// below the bar: 0.320, and 0.301 after the snap (its restoration keeps 0.3).
TEST(ImproveOnSharedPart, LayerOverTheSmoothRegionsOpensTheCrescentCornerOnARound) {
  const std::string path = test::data_path("cad/i11o_s1.step");
  HEXDOM_REQUIRE_DATA(path);
  const cad::Shape shape = cad::read_shape(path);
  const mesh::SurfaceMesh surface = cad::tessellate(shape, cad::TessellateOptions{});
  const autopolycube::MeshSurfaceRun run = autopolycube::mesh_surface(surface);
  ASSERT_EQ(run.level, 1);
  EXPECT_GT(run.mesh.num_cells(), run.generated.num_cells());  // a pillowed run was kept
  const Eigen::VectorXd sj = quality::compute_metrics(run.mesh).scaled_jacobian;
  EXPECT_GE(sj.minCoeff(), 0.3);
  const cad::SnapResult snapped = cad::snap_to_brep(shape, run.mesh, surface, cad::SnapOptions{});
  const Eigen::VectorXd sj2 = quality::compute_metrics(snapped.mesh).scaled_jacobian;
  EXPECT_GE(sj2.minCoeff(), 0.3);
  EXPECT_EQ(snapped.quality.hex.inverted, 0);
}
