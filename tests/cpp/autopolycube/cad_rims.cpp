// The polycube map of a round plate with a bolt hole close to its rim (the HexMe part i01o_m1, issue 9):
// the plate is tessellated by the CAD stage (test_autopolycube links it, and OpenCASCADE when the
// build has it).
#ifdef HEXDOM_WITH_CAD
#include "cad/cad_test_util.h"
#include "hexdom/autopolycube/repair/chart_graph.h"
#include "hexdom/autopolycube/repair/plane_groups.h"
#include "hexdom/autopolycube/map/polycube_map.h"
#include "hexdom/autopolycube/repair/repair_labels.h"
#include "hexdom/autopolycube/repair/split_chords.h"
#include "hexdom/segmentation/axis_labels.h"

using namespace hexdom;

namespace {
// Label 1..6 of the axis nearest to each triangle's normal.
Eigen::VectorXi labels_from_normals(const mesh::SurfaceMesh& s) {
  Eigen::VectorXi l(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    l(f) = segmentation::nearest_label((b - a).cross(c - a));
  }
  return l;
}
}  // namespace

// Disc of radius 30 and thickness 10 with a hole of radius 2.5 whose centre is 25 from the axis, on
// the +X quarter's middle: the hole is 2.5 from the rim. Flattened, the rim's +X quarter has the mean
// x of its curves, 0.90 R = 27.0, and the hole's outer (-X) wall 27.3: ordering the two by those means
// put the rim's plane inside the hole, and the plate's +Z and -Z charts folded (i01o_m1: 155
// triangles at every lambda and level). Where the two curves lie side by side (|y| <= 2.5) the rim is
// at x >= 29.9, outside the hole: that is the order the planes must keep.
TEST(PolycubeMap, ARoundRimStaysOutsideABoltHoleNearIt) {
  const TopoDS_Shape disc = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 30.0, 10.0).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(25, 0, -1), gp_Dir(0, 0, 1)), 2.5, 12.0).Shape();
  const cad::Shape shape = cad::read_shape(test::write_part(BRepAlgoAPI_Cut(disc, hole).Shape(), "rim_bolt_hole"));
  cad::TessellateOptions to;
  to.size = 2.0;
  mesh::SurfaceMesh s = cad::tessellate(shape, to);
  s.patch = labels_from_normals(s);
  autopolycube::RepairOptions ro;
  ro.band_width = 2.0;
  const autopolycube::RepairResult rep = autopolycube::repair_labels(s, ro);
  ASSERT_TRUE(rep.remaining.empty()) << rep.remaining.front().message;
  s.patch = rep.label;
  s = autopolycube::split_chords(s, autopolycube::chart_graph(s));
  const auto g = autopolycube::chart_graph(s);
  const auto pg = autopolycube::plane_groups(s, g);
  autopolycube::PolycubeMapOptions mo;
  mo.cell = 5.0;
  const auto m = autopolycube::polycube_map(s, g, pg, mo);
  int flipped = 0;
  for (int n : m.flipped) flipped += n;
  EXPECT_EQ(flipped, 0);
  // The plane of the rim's +X chart lies at least a cell beyond the plane of the hole's -X wall.
  int rim = -1, wall = -1;
  for (int c = 0; c < g.num_charts(); ++c) {
    if (g.label[c] != 1 && g.label[c] != 2) continue;
    double out = 0, off = 0;  // largest distance of its vertices from the disc's axis and from the hole's
    for (int f = 0; f < s.F.rows(); ++f)
      if (g.region(f) == c)
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector3d p = s.V.row(s.F(f, k));
          out = std::max(out, std::hypot(p(0), p(1)));
          off = std::max(off, std::hypot(p(0) - 25, p(1)));
        }
    if (g.label[c] == 1 && out > 29.9) rim = pg.of_chart[c];
    if (g.label[c] == 2 && off < 2.6) wall = pg.of_chart[c];
  }
  ASSERT_GE(rim, 0);
  ASSERT_GE(wall, 0);
  EXPECT_GE(m.plane(rim) - m.plane(wall), 1);
}
#endif
