#include "hexdom/autopolycube/blocks/collapse_slivers.h"

#include <map>
#include <set>

#include "auto_test_util.h"
#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/generation/generate.h"
#include "hexdom/polycube/patch_layout.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/quality/report.h"
#include "test_common.h"

using namespace hexdom;

namespace {

// A 14 degree wedge: cross-section (0,0) (4,0) (0,1) extruded 2 along z. The bottom is -Y, the
// back -X, the slanted face +Y but for a strip `w` wide along the knife edge at x = 4, labelled +X:
// the strip the label repair puts between two nearly opposite charts.
mesh::SurfaceMesh knife_edge_wedge(double w) {
  const Eigen::Vector2d tip(4, 0), top(0, 1);
  const Eigen::Vector2d cut = tip + w * (top - tip).normalized();
  return test::extruded_polygon({{0, 0}, tip, cut, top}, {4, 1, 3, 2}, 2.0, 0.05);
}

autopolycube::AutoPolycubeOptions options(double sliver_ratio) {
  autopolycube::AutoPolycubeOptions o;
  o.level = 1;
  o.size = 0.25;  // cells of 0.5
  o.sliver_ratio = sliver_ratio;
  return o;
}


}  // namespace

TEST(CollapseSlivers, KnifeEdgeStripGivesPrismBlocksAndTriangularPatches) {
  const auto s = knife_edge_wedge(0.08);
  const auto r = autopolycube::autopolycube(s, options(0.35));
  ASSERT_GT(r.prism_blocks, 0);
  EXPECT_GE(r.slivers, 1);
  EXPECT_EQ(r.structure.count(mesh::CellType::Wedge), r.prism_blocks);
  EXPECT_EQ(r.structure.num_cells(), r.blocks);
  EXPECT_EQ(r.inverted_blocks, 0);
  for (int b = 0; b < r.structure.num_cells(); ++b) {
    const auto P = quality::cell_points(r.structure, b);
    EXPECT_GT(quality::volume(r.structure.type(b), P), 0) << "block " << b + 1;
    EXPECT_GT(quality::scaled_jacobian(r.structure.type(b), P), 0) << "block " << b + 1;
    if (r.structure.type(b) == mesh::CellType::Wedge) {
      std::set<int> distinct;
      for (int i = 0; i < 6; ++i) distinct.insert(r.structure.cells(b, i));
      EXPECT_EQ(distinct.size(), 6u);
    }
  }
  // Every boundary face of the structure is one patch of the patch surface, the prisms' end
  // triangles included, and the geometry is the input's.
  const auto layout = polycube::patch_layout(r.patches);
  int boundary = 0, triangles = 0;
  for (const auto& [vs, n] : test::cell_faces(r.structure)) {
    EXPECT_LE(n, 2);
    boundary += n == 1;
    triangles += n == 1 && vs.size() == 3;
  }
  EXPECT_EQ(static_cast<int>(layout.patches.size()), boundary);
  int three = 0;
  for (const auto& p : layout.patches) {
    EXPECT_EQ(p.num_loops, 1);
    EXPECT_TRUE(p.corners.size() == 3 || p.corners.size() == 4) << p.corners.size();
    three += p.corners.size() == 3;
  }
  EXPECT_GT(triangles, 0);
  EXPECT_EQ(three, triangles);
  EXPECT_NEAR(test::enclosed_volume(r.patches), test::enclosed_volume(s), 1e-9);

  // generate takes the pair: prisms in the mesh, conforming (no face used by three cells, the
  // boundary faces closed), valid after improvement, the volume kept.
  generation::GenerateOptions go;
  go.level = 1;
  const mesh::Mesh m = generation::generate(r.patches, r.structure, go);
  EXPECT_EQ(m.count(mesh::CellType::Wedge), 8 * r.prism_blocks);
  EXPECT_EQ(m.count(mesh::CellType::Hex), 8 * (r.blocks - r.prism_blocks));
  std::map<std::vector<int>, std::vector<int>> ordered;
  std::map<std::pair<int, int>, int> boundary_edges;
  int mesh_triangles = 0;
  for (const auto& [vs, n] : test::cell_faces(m, &ordered)) {
    ASSERT_LE(n, 2);
    if (n == 2) continue;
    const auto& f = ordered.at(vs);
    mesh_triangles += f.size() == 3;
    for (size_t i = 0; i < f.size(); ++i)
      ++boundary_edges[{std::min(f[i], f[(i + 1) % f.size()]), std::max(f[i], f[(i + 1) % f.size()])}];
  }
  for (const auto& [e, n] : boundary_edges) ASSERT_EQ(n, 2) << "boundary edge " << e.first << " " << e.second;
  EXPECT_GT(mesh_triangles, 0);  // the prisms' end triangles on the surface
  optimize::ImproveOptions io;
  io.surface = r.patches;
  const auto imp = optimize::improve(m, io);
  EXPECT_EQ(imp.after.hex.inverted + imp.after.prism.inverted, 0);
  EXPECT_GT(imp.after.prism.sj_min, 0);
  EXPECT_NEAR(imp.after.total_volume, test::enclosed_volume(s), 0.01 * test::enclosed_volume(s));
}

TEST(CollapseSlivers, PrismsOnlyWhereTheyDoNotLowerTheWorstBlock) {
  const auto s = knife_edge_wedge(0.08);
  const auto hexes = autopolycube::autopolycube(s, options(0));
  EXPECT_EQ(hexes.prism_blocks, 0);
  EXPECT_EQ(hexes.structure.count(mesh::CellType::Hex), hexes.blocks);
  const auto prisms = autopolycube::autopolycube(s, options(0.35));
  EXPECT_EQ(prisms.blocks, hexes.blocks);
  EXPECT_GE(prisms.min_block_quality, hexes.min_block_quality - 1e-12);
}

TEST(CollapseSlivers, ABandInThePlaneOfItsSideCollapsesWhateverItsWidth) {
  // The strip 1.2 wide (as wide as its squares are long) but in the plane of the slanted side: the
  // hex blocks under it have a straight angle where it meets that side (scaled Jacobian 0), as the
  // label repair's band along a knife edge has; the prisms keep the blocks' volume.
  const auto r = autopolycube::autopolycube(knife_edge_wedge(1.2), options(0.35));
  EXPECT_GT(r.prism_blocks, 0);
  EXPECT_GT(r.min_block_quality, 0.1);
  EXPECT_EQ(r.inverted_blocks, 0);
}

TEST(CollapseSlivers, AFaceOfItsOwnStaysHexBlocks) {
  // The wedge cut square at the tip: the +X face at x = 4 is 0.6 high, at right angles to the
  // bottom, not a sliver and not in the plane of a side; its blocks stay hexes.
  const auto s = test::extruded_polygon({{0, 0}, {4, 0}, {4, 0.6}, {0, 1}}, {4, 1, 3, 2}, 2.0, 0.05);
  const auto r = autopolycube::autopolycube(s, options(0.35));
  EXPECT_EQ(r.prism_blocks, 0);
  EXPECT_EQ(r.structure.count(mesh::CellType::Hex), r.blocks);
  EXPECT_EQ(r.inverted_blocks, 0);
}
