// Every solid of a CAD source meshed as one part (pipeline::mesh_cad_solids): the part's faces,
// edges and vertices numbered as in the source (FreeCAD's numbering of a compound), local sizes
// given in those numbers reaching the solid that has the face.
#ifdef HEXDOM_WITH_CAD
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <TopExp.hxx>

#include "cad/cad_test_util.h"
#include "hexdom/pipeline/mesh_cad.h"

using namespace hexdom;

namespace {

// A 10 x 8 x 6 box and, 20 to its right, a cylinder of radius 5: 6 + 3 faces.
TopoDS_Shape box_and_cylinder() {
  gp_Trsf move;
  move.SetTranslation(gp_Vec(20, 0, 0));
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, test::make_box());
  b.Add(c, BRepBuilderAPI_Transform(test::make_cylinder(), move, true).Shape());
  return c;
}

double distance(const TopoDS_Shape& s, const Eigen::Vector3d& p) {
  BRepExtrema_DistShapeShape d(s, BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex());
  return d.IsDone() ? d.Value() : 1e30;
}

}  // namespace

// Each solid keeps the compound's numbers of its faces, edges and vertices; a solid read alone is
// numbered 1..n.
TEST(Solids, KeepTheNumbersOfTheirSource) {
  const TopoDS_Shape c = box_and_cylinder();
  const std::vector<cad::Shape> solids = cad::read_solids(test::write_part(c, "solids_numbers"));
  ASSERT_EQ(solids.size(), 2u);
  TopTools_IndexedMapOfShape faces, edges, vertices;
  TopExp::MapShapes(c, TopAbs_FACE, faces);
  TopExp::MapShapes(c, TopAbs_EDGE, edges);
  TopExp::MapShapes(c, TopAbs_VERTEX, vertices);
  ASSERT_EQ(faces.Extent(), 9);
  EXPECT_EQ(cad::source_numbers(solids[0], 2), (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(cad::source_numbers(solids[1], 2), (std::vector<int>{7, 8, 9}));
  EXPECT_EQ(cad::source_numbers(solids[1], 1).size() + 12, static_cast<size_t>(edges.Extent()));
  EXPECT_EQ(cad::source_numbers(solids[1], 1).front(), 13);
  EXPECT_EQ(cad::source_numbers(solids[1], 0).front(), 9);
  EXPECT_EQ(cad::source_numbers(solids[1], 0).size() + 8, static_cast<size_t>(vertices.Extent()));
  const cad::Shape alone = cad::read_shape(test::write_part(test::make_cylinder(), "solids_alone"));
  EXPECT_EQ(cad::source_numbers(alone, 2), (std::vector<int>{1, 2, 3}));
  EXPECT_THROW(cad::source_numbers(alone, 3), std::invalid_argument);
}

// The part's mesh: solid k's cells in region k, the volume the two B-reps', every tessellation
// triangle's patch the compound's face its corners lie on, every snapped node's entity a face
// of its own solid in the compound's numbers; the runs' figures summed.
TEST(Solids, AreMeshedAsOnePartInTheSourcesNumbers) {
  const TopoDS_Shape c = box_and_cylinder();
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(c, TopAbs_FACE, faces);
  const std::vector<cad::Shape> solids = cad::read_solids(test::write_part(c, "solids_part"));
  const pipeline::MeshSolidsRun r = pipeline::mesh_cad_solids(solids);
  ASSERT_EQ(r.solids.size(), 2u);
  EXPECT_TRUE(r.touching.empty());
  const pipeline::MeshCadRun& p = r.part;
  const mesh::Mesh& m = p.run.mesh;
  EXPECT_EQ(m.num_cells(), r.solids[0].run.mesh.num_cells() + r.solids[1].run.mesh.num_cells());
  for (int k = 0; k < m.num_cells(); ++k) {
    const int region = m.region(k) == 1 ? 0 : 1;
    ASSERT_TRUE(m.region(k) == 1 || m.region(k) == 2) << m.region(k);
    EXPECT_EQ(m.V(m.cells(k, 0), 0) > 14.0, region == 1) << "cell " << k;
  }
  const double brep = test::brep_volume(c);
  EXPECT_NEAR(p.stats.brep_volume, brep, 1e-6 * brep);
  EXPECT_NEAR(p.run.quality.total_volume, brep, 0.01 * brep);
  EXPECT_EQ(p.stats.triangles, r.solids[0].stats.triangles + r.solids[1].stats.triangles);
  EXPECT_EQ(p.tessellations, r.solids[0].tessellations + r.solids[1].tessellations);
  // Triangles: the patches 1..9, corners on the face of that number.
  ASSERT_EQ(p.surface.F.rows(), p.stats.triangles);
  std::set<int> patches;
  for (int t = 0; t < p.surface.F.rows(); t += 7) {
    const int f = p.surface.patch(t);
    ASSERT_TRUE(f >= 1 && f <= 9) << f;
    patches.insert(f);
    for (int j = 0; j < 3; ++j) EXPECT_LT(distance(faces(f), p.surface.V.row(p.surface.F(t, j))), 1e-6) << "patch " << f;
  }
  EXPECT_EQ(patches.size(), 9u);
  // Snap: one kind per node; face nodes on their face in the compound's numbers.
  ASSERT_TRUE(p.snapped);
  ASSERT_EQ(p.snap.kind.size(), static_cast<size_t>(m.num_nodes()));
  EXPECT_EQ(p.snap.report.boundary_nodes, r.solids[0].snap.report.boundary_nodes + r.solids[1].snap.report.boundary_nodes);
  EXPECT_LE(p.snap.report.max_after, 1e-7 * p.snap.report.diagonal);
  int checked = 0;
  for (int v = 0; v < m.num_nodes(); v += 5) {
    if (p.snap.kind[v] != cad::SnapKind::Face) continue;
    const int f = p.snap.entity[v];
    ASSERT_TRUE(f >= 1 && f <= 9) << f;
    EXPECT_EQ(f >= 7, m.V(v, 0) > 14.0) << "node " << v << " on Face" << f;
    EXPECT_LT(distance(faces(f), m.V.row(v)), 1e-6) << "node " << v << " on Face" << f;
    checked++;
  }
  EXPECT_GT(checked, 20);
}

// A size on the cylinder's side (Face7 of the compound, Face1 of the cylinder) refines the
// cylinder only; a face no solid has is refused by its number.
TEST(Solids, TakeLocalSizesInTheSourcesNumbers) {
  const std::vector<cad::Shape> solids = cad::read_solids(test::write_part(box_and_cylinder(), "solids_sizes"));
  pipeline::MeshCadOptions o;
  o.mesh.method = pipeline::Method::Overlay;
  const pipeline::MeshSolidsRun plain = pipeline::mesh_cad_solids(solids, o);
  overlay::LocalSize l;
  l.patch = 7;
  l.size = 0.25;  // the cylinder's default size is about 0.6 (its diagonal / 30)
  o.mesh.overlay.local_sizes.push_back(l);
  const pipeline::MeshSolidsRun sized = pipeline::mesh_cad_solids(solids, o);
  EXPECT_EQ(sized.solids[0].run.mesh.num_cells(), plain.solids[0].run.mesh.num_cells());
  EXPECT_GT(sized.solids[1].run.mesh.num_cells(), 2 * plain.solids[1].run.mesh.num_cells());
  o.mesh.overlay.local_sizes[0].patch = 10;
  try {
    pipeline::mesh_cad_solids(solids, o);
    ADD_FAILURE() << "Face10 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Face10"), std::string::npos) << e.what();
  }
}
// One solid chosen from the compound (read_solids with options.solid) is meshed in the compound's
// numbers as well: its tessellation's patches and a size on its Face7; a face of the other solid is
// refused naming the solid's faces.
TEST(Solids, OneChosenSolidKeepsTheSourcesNumbers) {
  cad::ReadOptions ro;
  ro.solid = 2;
  const std::vector<cad::Shape> one = cad::read_solids(test::write_part(box_and_cylinder(), "solids_chosen"), ro);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(cad::source_numbers(one[0], 2), (std::vector<int>{7, 8, 9}));
  pipeline::MeshCadOptions o;
  o.mesh.method = pipeline::Method::Overlay;
  overlay::LocalSize l;
  l.patch = 7;
  l.size = 0.5;
  o.mesh.overlay.local_sizes.push_back(l);
  const pipeline::MeshCadRun r = pipeline::mesh_cad_part(one[0], o);
  std::set<int> patches(r.surface.patch.data(), r.surface.patch.data() + r.surface.patch.size());
  EXPECT_EQ(patches, (std::set<int>{7, 8, 9}));
  ASSERT_TRUE(r.snapped);
  for (size_t v = 0; v < r.snap.kind.size(); ++v)
    if (r.snap.kind[v] == cad::SnapKind::Face) ASSERT_TRUE(r.snap.entity[v] >= 7 && r.snap.entity[v] <= 9) << r.snap.entity[v];
  o.mesh.overlay.local_sizes[0].patch = 1;
  try {
    pipeline::mesh_cad_part(one[0], o);
    ADD_FAILURE() << "Face1 of the box accepted for the cylinder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Face1, which is not a face of the solid meshed (Face7, Face8, Face9)"),
              std::string::npos) << e.what();
  }
}
#endif
