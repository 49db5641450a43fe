// The two meshing paths behind one pipeline: the overlay grid alone on CAD parts the polycube finds
// hard (a torus, a sphere, a cone's apex), and the automatic choice between the paths.
#ifdef HEXDOM_WITH_CAD
#include <gtest/gtest.h>

#include "cad/cad_test_util.h"
#include "hexdom/pipeline/mesh_cad.h"

using namespace hexdom;

namespace {

int inverted(const quality::QualityReport& q) { return q.hex.inverted + q.prism.inverted + q.tet.inverted; }

/// With `untimed`, auto's polycube path has no time budget and is not stopped when the overlay's
/// mesh meets the targets, so that what it finds does not depend on the machine's speed.
pipeline::MeshCadRun mesh_part(const TopoDS_Shape& part, const std::string& name, pipeline::Method method,
                               bool untimed = false) {
  pipeline::MeshCadOptions o;
  o.mesh.method = method;
  if (untimed) o.mesh.polycube_seconds = o.mesh.polycube_seconds_overlay_met = 0;
  return pipeline::mesh_cad_part(cad::read_shape(test::write_part(part, name)), o);
}

// A run of 10 hexes of volume 1 with this worst SJ and largest edge ratio, for the choice's order.
pipeline::MeshSurfaceRun hex_run(double sj_min, double edge_ratio_max) {
  pipeline::MeshSurfaceRun r;
  r.quality.hex.count = 10;
  r.quality.total_volume = 1.0;
  r.quality.hex.sj_min = sj_min;
  r.quality.hex.edge_ratio_max = edge_ratio_max;
  return r;
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

// A 60 x 60 x 20 box with a 30 x 30 step 0.35 high on top: the polycube gives the step a layer of
// cells 0.35 thick under cells of about 3 (edge ratio above 10); auto meshes the grid too and keeps
// the mesh within the edge-ratio target, the other targets being met by both. Untimed: under the
// sanitizers the polycube path was stopped at the overlay's cut before it said why it missed.
TEST(AutomaticChoice, AThinLayerOfCellsHasTheGridMeshedTooAndTheMeshWithoutItKept) {
  const TopoDS_Shape part = BRepAlgoAPI_Fuse(BRepPrimAPI_MakeBox(60.0, 60.0, 20.0).Shape(),
                                             BRepPrimAPI_MakeBox(gp_Pnt(15, 15, 20), 30.0, 30.0, 0.35).Shape())
                                .Shape();
  const pipeline::MeshCadRun polycube = mesh_part(part, "auto_thin_step", pipeline::Method::Polycube);
  const pipeline::MeshCadRun automatic = mesh_part(part, "auto_thin_step", pipeline::Method::Auto, true);
  const double target = pipeline::MeshSurfaceOptions{}.target_edge_ratio;
  EXPECT_GT(quality::max_edge_ratio(polycube.run.quality), target);
  EXPECT_EQ(automatic.run.method, pipeline::Method::Overlay) << automatic.run.polycube_note;
  EXPECT_NE(automatic.run.polycube_note.find("max edge ratio"), std::string::npos) << automatic.run.polycube_note;
  EXPECT_LE(quality::max_edge_ratio(automatic.run.quality), target);
  EXPECT_EQ(inverted(automatic.run.quality), 0);
  EXPECT_NEAR(automatic.run.quality.total_volume, automatic.stats.brep_volume, 0.01 * automatic.stats.brep_volume);
}

// The order of two meshes equal on the other targets: the one within the edge-ratio target first,
// whatever its worst SJ; with the target off (0) the higher worst SJ.
TEST(AutomaticChoice, TheEdgeRatioTargetComesBeforeTheWorstSJ) {
  const pipeline::MeshSurfaceRun needle = hex_run(0.9, 40), blunt = hex_run(0.5, 3);
  pipeline::MeshSurfaceOptions o;
  EXPECT_TRUE(pipeline::better_run(blunt, needle, 1.0, o));
  EXPECT_FALSE(pipeline::better_run(needle, blunt, 1.0, o));
  EXPECT_FALSE(pipeline::meets_path_targets(needle, 1.0, o));
  EXPECT_TRUE(pipeline::meets_targets(needle, 1.0, o));
  o.target_edge_ratio = 0;
  EXPECT_TRUE(pipeline::better_run(needle, blunt, 1.0, o));
  EXPECT_TRUE(pipeline::meets_path_targets(needle, 1.0, o));
}

// Both beyond the edge-ratio target, both above the SJ target: the smaller edge ratio first (a cell
// 17 times longer than wide serves FEM better than one 77 times), whatever the worst SJ; below the
// SJ target the worst SJ decides.
TEST(AutomaticChoice, BeyondTheEdgeRatioTargetTheSmallerEdgeRatioComesFirst) {
  pipeline::MeshSurfaceRun thin = hex_run(0.447, 17.1), thinner = hex_run(0.455, 77.3);
  const pipeline::MeshSurfaceOptions o;
  EXPECT_TRUE(pipeline::better_run(thin, thinner, 1.0, o));
  EXPECT_FALSE(pipeline::better_run(thinner, thin, 1.0, o));
  thin.quality.hex.sj_min = 0.2;
  thinner.quality.hex.sj_min = 0.25;
  EXPECT_TRUE(pipeline::better_run(thinner, thin, 1.0, o));
}

// A time budget too small for anything: auto meshes the box (whose polycube mesh it keeps without a
// budget, test above) with the overlay grid, and polycube_note says that the budget stopped the
// polycube path; for mesh_cad_part one budget stops every tessellation's polycube.
TEST(TimeBudget, AutoWithATinyBudgetKeepsTheOverlayMeshAndNamesTheBudget) {
  pipeline::MeshCadOptions o;
  o.mesh.polycube_seconds = 1e-6;
  std::string log;
  o.log = o.mesh.log = [&](int, const std::string& m) { log += m + "\n"; };
  const pipeline::MeshCadRun r = pipeline::mesh_cad_part(cad::read_shape(test::write_part(test::make_box(), "budget_box")), o);
  EXPECT_EQ(r.run.method, pipeline::Method::Overlay) << log;
  EXPECT_NE(r.run.polycube_note.find("the polycube path stopped after its time budget of 1e-06 s at stage"), std::string::npos)
      << r.run.polycube_note;
  EXPECT_EQ(inverted(r.run.quality), 0);
  EXPECT_EQ(r.tessellations, 1) << log;

  // mesh_surface alone, on the box's tessellation.
  pipeline::MeshSurfaceOptions so;
  so.polycube_seconds = 1e-6;
  const pipeline::MeshSurfaceRun sr = pipeline::mesh_surface(r.surface, so);
  EXPECT_EQ(sr.method, pipeline::Method::Overlay);
  EXPECT_NE(sr.polycube_note.find("time budget of 1e-06 s"), std::string::npos) << sr.polycube_note;
  EXPECT_EQ(inverted(sr.quality), 0);
  so.polycube_seconds = 0;  // no limit: the polycube mesh again
  EXPECT_EQ(pipeline::mesh_surface(r.surface, so).method, pipeline::Method::Polycube);
}

// Method::Polycube runs to its end unless it is given a deadline; with one that passes before there
// is a mesh it throws TimeoutError (mesh_surface and mesh_cad_part alike).
TEST(TimeBudget, PolycubeWithATinyDeadlineThrowsTimeoutError) {
  const cad::Shape shape = cad::read_shape(test::write_part(test::make_box(), "budget_box_polycube"));
  const mesh::SurfaceMesh s = cad::tessellate(shape);
  pipeline::MeshSurfaceOptions o;
  o.method = pipeline::Method::Polycube;
  o.polycube_seconds = 1e-6;  // not the polycube method's budget: no deadline, no limit
  EXPECT_EQ(pipeline::mesh_surface(s, o).method, pipeline::Method::Polycube);
  o.deadline = Deadline::in(1e-6);
  EXPECT_THROW(pipeline::mesh_surface(s, o), TimeoutError);
  pipeline::MeshCadOptions co;
  co.mesh = o;
  co.mesh.deadline = Deadline::in(1e-6);
  try {
    pipeline::mesh_cad_part(shape, co);
    FAIL() << "no TimeoutError";
  } catch (const TimeoutError& e) {
    EXPECT_NE(std::string(e.what()).find("stopped after the time budget of 1e-06 s"), std::string::npos) << e.what();
  }
}

TEST(AutomaticChoice, MethodsAreNamed) {
  for (auto m : {pipeline::Method::Auto, pipeline::Method::Polycube, pipeline::Method::Overlay})
    EXPECT_EQ(pipeline::method_from_name(pipeline::method_name(m)), m);
  EXPECT_THROW(pipeline::method_from_name("octree"), InputError);
}

#endif  // HEXDOM_WITH_CAD
