// The automatic path (tessellate -> mesh_surface -> snap) on a shared CAD part, where a mechanism
// of the improvement shows on the figures it reaches.
#include <Eigen/Core>

#include "cad_test_util.h"
#include "hexdom/autopolycube/mesh_surface.h"
#include "hexdom/cad/snap.h"
#include "hexdom/quality/metrics.h"

using namespace hexdom;

// i11o_s1 at the default size (diagonal / 30, level 1): where the R65 round's -Y / +Z label boundary
// meets the plate's faces, the run without a pillow layer is kept, and its worst hexes have two
// faces on the round whose corners tie in pairs. The gradient of the minimum stalls there (0.220);
// the pattern search of the run without a layer climbs on (0.270, 0.267 after the snap).
TEST(ImproveOnSharedPart, RunWithoutLayerClimbsPastTiedCornersOnARound) {
  const std::string path = test::data_path("cad/i11o_s1.step");
  HEXDOM_REQUIRE_DATA(path);
  const cad::Shape shape = cad::read_shape(path);
  const mesh::SurfaceMesh surface = cad::tessellate(shape, cad::TessellateOptions{});
  const autopolycube::MeshSurfaceRun run = autopolycube::mesh_surface(surface);
  ASSERT_EQ(run.level, 1);
  EXPECT_EQ(run.mesh.num_cells(), run.generated.num_cells());  // the run without a layer was kept
  const Eigen::VectorXd sj = quality::compute_metrics(run.mesh).scaled_jacobian;
  EXPECT_GE(sj.minCoeff(), 0.26);
  const cad::SnapResult snapped = cad::snap_to_brep(shape, run.mesh, surface, cad::SnapOptions{});
  const Eigen::VectorXd sj2 = quality::compute_metrics(snapped.mesh).scaled_jacobian;
  EXPECT_GE(sj2.minCoeff(), 0.26);
  EXPECT_EQ(snapped.quality.hex.inverted, 0);
}
