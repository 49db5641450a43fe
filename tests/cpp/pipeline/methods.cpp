// The two meshing paths behind one pipeline: the overlay grid alone on CAD parts the polycube finds
// hard (a torus, a sphere, a cone's apex), and the automatic choice between the paths.
#ifdef HEXDOM_WITH_CAD
#include <gtest/gtest.h>

#include "cad/cad_test_util.h"
#include "hexdom/pipeline/mesh_cad.h"

using namespace hexdom;

namespace {

int inverted(const quality::QualityReport& q) { return q.hex.inverted + q.prism.inverted + q.tet.inverted; }

pipeline::MeshCadRun mesh_part(const TopoDS_Shape& part, const std::string& name, pipeline::Method method) {
  pipeline::MeshCadOptions o;
  o.mesh.method = method;
  return pipeline::mesh_cad_part(cad::read_shape(test::write_part(part, name)), o);
}

}  // namespace

// The overlay path alone on a torus, a sphere, a cone's apex, a 10 degree wedge and a box with
// cylinders tangent to its faces: no inverted cell, the boundary nodes on the B-rep, the volume within 1%;
// the cone's within 2%: its base rim gets a node only where the grid's staircase meets it (36
// nodes on a rim of 54 cells' length, measured -1.42%; the finer grids tried keep inverted cells).
TEST(OverlayPath, MeshesCurvedAcuteAndTangentPartsOnTheirBrep) {
  const std::pair<const char*, TopoDS_Shape> parts[] = {
      {"overlay_torus", test::make_torus()},   {"overlay_sphere", test::make_sphere()},
      {"overlay_cone", test::make_cone()},     {"overlay_wedge10", test::make_wedge(10.0)},
      {"overlay_stadium", test::make_stadium()}};
  for (const auto& [name, shape] : parts) {
    const pipeline::MeshCadRun r = mesh_part(shape, name, pipeline::Method::Overlay);
    EXPECT_EQ(r.run.method, pipeline::Method::Overlay) << name;
    EXPECT_EQ(inverted(r.run.quality), 0) << name;
    ASSERT_TRUE(r.snapped) << name;
    EXPECT_LE(r.snap.report.max_after, 1e-7 * r.snap.report.diagonal) << name;
    const double tolerance = std::string(name) == "overlay_cone" ? 0.02 : 0.01;
    EXPECT_NEAR(r.run.quality.total_volume, r.stats.brep_volume, tolerance * r.stats.brep_volume) << name;
    EXPECT_EQ(r.tessellations, 1) << name;  // the overlay grid does not depend on the triangles
    EXPECT_NE(pipeline::choice_text(r.run).find("overlay grid"), std::string::npos) << pipeline::choice_text(r.run);
  }
}

// A box: the polycube meets every target, so the automatic choice keeps it without trying the grid.
TEST(AutomaticChoice, KeepsThePolycubeWhenItMeetsTheTargets) {
  const pipeline::MeshCadRun r = mesh_part(test::make_box(), "auto_box", pipeline::Method::Auto);
  EXPECT_EQ(r.run.method, pipeline::Method::Polycube);
  EXPECT_TRUE(r.run.polycube_note.empty()) << r.run.polycube_note;
  EXPECT_EQ(inverted(r.run.quality), 0);
}

// A torus: the polycube's mesh misses a target, so the grid is meshed too, and the run kept is the
// better of the two by the pipeline's order (measured before the snap, as mesh_surface compares).
TEST(AutomaticChoice, MeshesTheGridTooWhenThePolycubeMissesATarget) {
  const mesh::SurfaceMesh s = cad::tessellate(cad::read_shape(test::write_part(test::make_torus(), "auto_torus")));
  pipeline::MeshSurfaceOptions o;
  std::string log;
  o.log = [&](int, const std::string& m) { log += m + "\n"; };
  const pipeline::MeshSurfaceRun automatic = pipeline::mesh_surface(s, o);
  o.method = pipeline::Method::Polycube;
  const pipeline::MeshSurfaceRun polycube = pipeline::mesh_surface(s, o);
  o.method = pipeline::Method::Overlay;
  const pipeline::MeshSurfaceRun overlay = pipeline::mesh_surface(s, o);
  const double volume = mesh::enclosed_volume(s.V, s.F);
  ASSERT_FALSE(automatic.polycube_note.empty()) << log;
  EXPECT_NE(log.find("meshing with the overlay grid too"), std::string::npos) << log;
  const pipeline::MeshSurfaceRun& better = pipeline::better_run(overlay, polycube, volume, o) ? overlay : polycube;
  EXPECT_EQ(automatic.method, better.method);
  EXPECT_EQ(automatic.mesh.num_cells(), better.mesh.num_cells());
}

TEST(AutomaticChoice, MethodsAreNamed) {
  for (auto m : {pipeline::Method::Auto, pipeline::Method::Polycube, pipeline::Method::Overlay})
    EXPECT_EQ(pipeline::method_from_name(pipeline::method_name(m)), m);
  EXPECT_THROW(pipeline::method_from_name("octree"), InputError);
}

#endif  // HEXDOM_WITH_CAD
