#include "hexdom/common/error.h"
#include "hexdom/io/mesh_io.h"
#include "hexdom/polycube/patch_layout.h"
#include "test_common.h"

using namespace hexdom;

namespace {
std::string example(const std::string& name) { return std::string(HEXDOM_SOURCE_DIR) + "/examples/data/" + name; }
}  // namespace

TEST(PatchLayout, LBracketHasOnePatchPerBoundaryFace) {
  auto s = io::read_surface(example("lbracket_patches.k"));
  auto layout = polycube::patch_layout(s);
  EXPECT_EQ(layout.patches.size(), 17u);
  // Every vertex of the polycube is a corner: 18 structure vertices minus none inside.
  EXPECT_EQ(layout.corners.size(), 18u);
  for (const auto& p : layout.patches) {
    EXPECT_EQ(p.num_loops, 1);
    EXPECT_TRUE(p.corners.size() == 3 || p.corners.size() == 4) << p.corners.size();
  }
}

TEST(CheckClosedManifold, OpenSurfaceNamesItsEdge) {
  auto s = io::read_surface(example("lbracket_patches.k"));
  s.F.conservativeResize(s.F.rows() - 1, 3);
  try {
    polycube::check_closed_manifold(s);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("open surface"), std::string::npos) << e.what();
  }
}

TEST(CheckClosedManifold, FlippedTriangleIsReported) {
  auto s = io::read_surface(example("lbracket_patches.k"));
  std::swap(s.F(5, 0), s.F(5, 1));
  EXPECT_THROW(polycube::check_closed_manifold(s), GeometryError);
}
