// Second-order meshes of CAD parts and surfaces through the pipeline (MeshSurfaceOptions::order).
#include <set>

#include "hexdom/common/error.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/second_order.h"
#include "hexdom/pipeline/mesh_cad.h"
#include "test_common.h"

#ifdef HEXDOM_WITH_CAD
#include <BRepPrimAPI_MakeCylinder.hxx>

#include "cad/cad_test_util.h"
#include "hexdom/cad/project.h"
#endif

using namespace hexdom;

namespace {

/// The mid-edge nodes of the boundary edges of a second-order mesh.
std::vector<int> boundary_mid_nodes(const mesh::Mesh& m) {
  mesh::Mesh corners = m;
  corners.mid.resize(0, 12);
  std::set<mesh::EdgeKey> boundary;
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(corners))
    for (int i = 0; i < f.n; ++i) boundary.insert(mesh::undirected_edge(f.v[i], f.v[(i + 1) % f.n]));
  std::vector<int> r;
  const auto ends = mesh::mid_edge_ends(m);
  for (int v = 0; v < m.num_nodes(); ++v)
    if (ends[v][0] >= 0 && boundary.count(mesh::undirected_edge(ends[v][0], ends[v][1]))) r.push_back(v);
  return r;
}

}  // namespace

TEST(SecondOrderPipeline, OrdersOtherThanOneAndTwoAreRefused) {
  pipeline::MeshSurfaceOptions o;
  o.order = 3;
  EXPECT_THROW(pipeline::mesh_surface(mesh::SurfaceMesh{}, o), InputError);
}

#ifdef HEXDOM_WITH_CAD
// A cylinder of radius 10, meshed by the polycube path: its first-order mesh's chords cut the round
// face; the second order puts the boundary's mid-edge nodes on the B-rep, and the curved cells
// enclose the volume to a small fraction of the chords' deficit. The corners are the first-order
// mesh's.
TEST(SecondOrderPipeline, ACylinderSecondOrderHasItsMidEdgeNodesOnTheBrepAndItsVolume) {
  const cad::Shape shape = cad::read_shape(test::write_part(BRepPrimAPI_MakeCylinder(10.0, 20.0).Shape(), "cyl_r10"));
  pipeline::MeshCadOptions o;
  o.mesh.threads = 1;
  o.mesh.method = pipeline::Method::Polycube;  // (auto's choice can depend on the machine's speed)
  const pipeline::MeshCadRun first = pipeline::mesh_cad_part(shape, o);
  o.mesh.order = 2;
  const pipeline::MeshCadRun second = pipeline::mesh_cad_part(shape, o);
  const mesh::Mesh& m = second.run.mesh;
  ASSERT_TRUE(m.second_order());
  EXPECT_FALSE(first.run.mesh.second_order());
  ASSERT_EQ(m.num_cells(), first.run.mesh.num_cells());
  EXPECT_TRUE(m.V.topRows(first.run.mesh.num_nodes()) == first.run.mesh.V);
  EXPECT_EQ(second.run.quality.hex20.count, first.run.quality.hex.count);
  EXPECT_EQ(quality::inverted_cells(second.run.quality), 0);
  const std::vector<int> mids = boundary_mid_nodes(m);
  EXPECT_EQ(static_cast<int>(mids.size()), second.run.second_order.boundary_mid_nodes);
  EXPECT_EQ(second.run.second_order.curve.placed, second.run.second_order.boundary_mid_nodes);
  Eigen::MatrixXd P(mids.size(), 3);
  for (size_t k = 0; k < mids.size(); ++k) P.row(k) = m.V.row(mids[k]);
  const cad::Projection d = cad::project_to_shape(shape, P);
  EXPECT_LE(d.distance.maxCoeff(), 1e-7 * second.run.second_order.diagonal);
  const double volume = M_PI * 100 * 20;
  const double e1 = std::abs(first.run.quality.total_volume - volume), e2 = std::abs(second.run.quality.total_volume - volume);
  EXPECT_GT(e1, 1e-3 * volume);  // the chords' deficit
  EXPECT_LT(e2, 0.02 * e1);
}
#endif
