// cad::snap_to_brep: classification of boundary nodes by CAD face / edge / vertex and exact
// projection, on a box and a cylinder made with OCCT here and meshed with structured hexes that
// sit slightly inside the solid (as a mesh on a tessellation's chords does).
#ifdef HEXDOM_WITH_CAD
#include <cmath>
#include <cstdio>
#include <string>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>

#include "cad_test_util.h"
#include "hexdom/cad/snap.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/report.h"

using namespace hexdom;
using hexdom::test::write_part;

namespace {

/// Structured (nx x ny x nz) hex grid over [0,1]^3, points mapped by `f`.
template <class Map>
mesh::Mesh grid(int nx, int ny, int nz, Map f) {
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  Eigen::MatrixXd V((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) V.row(id(i, j, k)) = f(double(i) / nx, double(j) / ny, double(k) / nz).transpose();
  mesh::MeshBuilder b;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int h[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                    id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        b.add(mesh::CellType::Hex, h, 1);
      }
  return b.finish(V);
}

int count(const cad::SnapResult& r, cad::SnapKind k) {
  return static_cast<int>(std::count(r.kind.begin(), r.kind.end(), k));
}

}  // namespace

TEST(SnapToBrep, BoxNodesGoOntoFacesEdgesAndCorners) {
  const cad::Shape shape = cad::read_shape(write_part(BRepPrimAPI_MakeBox(10.0, 8.0, 6.0).Shape(), "snap_box"));
  const mesh::SurfaceMesh tess = cad::tessellate(shape, {});
  const int nx = 5, ny = 4, nz = 3;
  // 0.2% smaller than the box and shifted a little: every boundary node is off the B-rep.
  const mesh::Mesh m = grid(nx, ny, nz, [](double u, double v, double w) {
    return Eigen::Vector3d(0.01 + 9.98 * u, 0.01 + 7.98 * v, 0.005 + 5.99 * w);
  });
  const cad::SnapResult r = cad::snap_to_brep(shape, m, tess);
  const int boundary = m.num_nodes() - (nx - 1) * (ny - 1) * (nz - 1);
  EXPECT_EQ(r.report.boundary_nodes, boundary);
  EXPECT_EQ(count(r, cad::SnapKind::Vertex), 8);
  EXPECT_EQ(count(r, cad::SnapKind::Edge), 4 * ((nx - 1) + (ny - 1) + (nz - 1)));
  EXPECT_EQ(count(r, cad::SnapKind::Face), boundary - 8 - 4 * ((nx - 1) + (ny - 1) + (nz - 1)));
  EXPECT_EQ(r.report.vertex_nodes, 8);
  EXPECT_GT(r.report.max_before, 0.004);
  EXPECT_LT(r.report.max_after, 1e-12);
  const cad::ShapeInfo info = cad::shape_info(shape);
  const Eigen::Vector3d size(10, 8, 6);
  for (int v = 0; v < m.num_nodes(); ++v) {
    const Eigen::Vector3d p = r.mesh.V.row(v);
    int on = 0;  // coordinates on a face plane
    for (int a = 0; a < 3; ++a) on += std::abs(p(a)) < 1e-12 || std::abs(p(a) - size(a)) < 1e-12;
    // The CAD faces it lies on (the box's Face1..Face6: x = 0, x = 10, y = 0, ..., z = 6): one per
    // plane it is on.
    ASSERT_EQ(static_cast<int>(r.faces[v].size()), on) << v;
    for (int f : r.faces[v]) EXPECT_LT(std::abs(p((f - 1) / 2) - ((f - 1) % 2) * size((f - 1) / 2)), 1e-12) << v << " Face" << f;
    switch (r.kind[v]) {
      case cad::SnapKind::Interior: EXPECT_EQ(on, 0) << v; break;
      case cad::SnapKind::Face: EXPECT_EQ(on, 1) << v; break;
      case cad::SnapKind::Edge: EXPECT_EQ(on, 2) << v; break;
      case cad::SnapKind::Vertex:
        EXPECT_EQ(on, 3) << v;
        EXPECT_LT((p - Eigen::Vector3d(info.vertex_points.row(r.entity[v] - 1))).norm(), 1e-12) << v;
        break;
    }
  }
  EXPECT_EQ(r.report.inverted, 0);
  EXPECT_NEAR(r.quality.total_volume, 480.0, 1e-9);
}

// SnapOptions::face_only: the nodes marked go onto a CAD face only, however near an edge or a
// vertex; the others as before. A list of the wrong length is refused.
TEST(SnapToBrep, FaceOnlyNodesStayOffTheEdgesAndVertices) {
  const cad::Shape shape = cad::read_shape(write_part(BRepPrimAPI_MakeBox(10.0, 8.0, 6.0).Shape(), "snap_box_face_only"));
  const mesh::SurfaceMesh tess = cad::tessellate(shape, {});
  const mesh::Mesh m = grid(5, 4, 3, [](double u, double v, double w) {
    return Eigen::Vector3d(0.01 + 9.98 * u, 0.01 + 7.98 * v, 0.005 + 5.99 * w);
  });
  const Eigen::Vector3d size(10, 8, 6);
  cad::SnapOptions o;
  o.face_only.assign(m.num_nodes(), 0);
  int marked = 0;
  for (int v = 0; v < m.num_nodes(); ++v)  // the nodes of the x = 0 side
    if (m.V(v, 0) < 0.02) o.face_only[v] = 1, ++marked;
  ASSERT_EQ(marked, 5 * 4);
  const cad::SnapResult r = cad::snap_to_brep(shape, m, tess, o);
  int unmarked_edges = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    const Eigen::Vector3d p = r.mesh.V.row(v);
    if (o.face_only[v]) {  // onto the nearest of its faces, on exactly one face plane: off the edges
      int on = 0;
      for (int a = 0; a < 3; ++a) on += std::abs(p(a)) < 1e-12 || std::abs(p(a) - size(a)) < 1e-12;
      EXPECT_EQ(r.kind[v], cad::SnapKind::Face) << v;
      EXPECT_EQ(on, 1) << v;
    } else {
      unmarked_edges += r.kind[v] == cad::SnapKind::Edge;
    }
  }
  EXPECT_EQ(count(r, cad::SnapKind::Vertex), 4);                        // the four at x = 10
  EXPECT_EQ(unmarked_edges, 4 * 4 + 2 * 3 + 2 * 2);  // the x edges' inner nodes, the x = 10 side's y and z edges
  EXPECT_LT(r.report.max_after, 1e-12);
  EXPECT_EQ(r.report.inverted, 0);
  o.face_only.pop_back();
  EXPECT_THROW(cad::snap_to_brep(shape, m, tess, o), InputError);
}

TEST(SnapToBrep, CylinderRimNodesGoOntoTheCircles) {
  const double R = 5, H = 12;
  const cad::Shape shape = cad::read_shape(write_part(BRepPrimAPI_MakeCylinder(R, H).Shape(), "snap_cyl"));
  cad::TessellateOptions to;
  to.size = 1.5;
  const mesh::SurfaceMesh tess = cad::tessellate(shape, to);
  const int n = 8, nz = 6;
  // Square grid on the disk (elliptical map), radius 1% short, caps 1% inside.
  const mesh::Mesh m = grid(n, n, nz, [&](double u, double v, double w) {
    const double x = 2 * u - 1, y = 2 * v - 1;
    return Eigen::Vector3d(0.99 * R * x * std::sqrt(1 - y * y / 2), 0.99 * R * y * std::sqrt(1 - x * x / 2),
                           0.01 * H + 0.98 * H * w);
  });
  cad::SnapOptions opt;
  opt.edge_tolerance = 0.3;
  const cad::SnapResult r = cad::snap_to_brep(shape, m, tess, opt);
  EXPECT_EQ(count(r, cad::SnapKind::Vertex), 0);  // the cylinder's vertices are on its seam, not corners
  EXPECT_EQ(count(r, cad::SnapKind::Edge), 2 * 4 * n);  // the two rims
  EXPECT_LT(r.report.max_after, 1e-9);
  EXPECT_GT(r.report.max_before, 0.04);
  for (int v = 0; v < m.num_nodes(); ++v) {
    const Eigen::Vector3d p = r.mesh.V.row(v);
    const double rho = std::hypot(p(0), p(1));
    const bool cap = std::abs(p(2)) < 1e-9 || std::abs(p(2) - H) < 1e-9, side = std::abs(rho - R) < 1e-9;
    if (r.kind[v] == cad::SnapKind::Edge) {
      EXPECT_TRUE(cap && side) << v << ": " << p.transpose();
    } else if (r.kind[v] == cad::SnapKind::Face) {
      EXPECT_TRUE(cap != side) << v << ": " << p.transpose();
    } else {
      EXPECT_TRUE(!cap && rho < R) << v;
    }
  }
  EXPECT_EQ(r.report.inverted, 0);
  // The snapped mesh's volume is that of the inscribed polygonal prism: within 2% of pi R^2 H.
  EXPECT_NEAR(r.quality.total_volume, M_PI * R * R * H, 0.02 * M_PI * R * R * H);
}

// The progressive snap (SnapOptions::steps) is a second whole restoration: made only where the
// direct one leaves inverted cells or ends below both the worst SJ before and `keep`. A grid of
// perfect cubes turned 4 degrees about the box's axis: the snap shears its outer cells.
TEST(SnapToBrep, TheProgressiveSnapOnlyWhereTheDirectOneEndsBelowTheBar) {
  const cad::Shape shape = cad::read_shape(write_part(BRepPrimAPI_MakeBox(10.0, 10.0, 10.0).Shape(), "snap_turned"));
  const mesh::SurfaceMesh tess = cad::tessellate(shape, {});
  const double a = 4 * M_PI / 180;
  const mesh::Mesh m = grid(5, 5, 5, [&](double u, double v, double w) {
    const double x = 10 * u - 5, y = 10 * v - 5;
    return Eigen::Vector3d(5 + std::cos(a) * x - std::sin(a) * y, 5 + std::sin(a) * x + std::cos(a) * y, 10 * w);
  });
  auto progressive = [&](double keep, double* before, double* after) {
    cad::SnapOptions opt;
    opt.keep = keep;
    std::string log;
    opt.log = [&](int, const std::string& l) { log += l + "\n"; };
    const cad::SnapResult r = cad::snap_to_brep(shape, m, tess, opt);
    *before = r.report.worst_sj_before;
    *after = r.report.worst_sj;
    EXPECT_EQ(r.report.inverted, 0);
    EXPECT_LT(r.report.max_after, 1e-9);
    return log.find("in 2 steps") != std::string::npos;
  };
  double before = 0, after = 0;
  const bool at_default = progressive(0.3, &before, &after);
  std::printf("worst SJ before the snap %.4f, after %.4f\n", before, after);
  ASSERT_GT(before, 0.999);
  ASSERT_GE(after, 0.3);
  EXPECT_FALSE(at_default) << "above the bar: no second restoration";
  // With keep 1 the bar is the worst before the snap, which the direct snap does not keep.
  ASSERT_LT(after, before - 1e-3);
  EXPECT_TRUE(progressive(1.0, &before, &after));
}

TEST(SnapToBrep, TessellationNamingAMissingFaceIsAnInputError) {
  const cad::Shape shape = cad::read_shape(write_part(BRepPrimAPI_MakeBox(1.0, 1.0, 1.0).Shape(), "snap_bad"));
  mesh::SurfaceMesh tess = cad::tessellate(shape, {});
  tess.patch(3) = 7;
  const mesh::Mesh m = grid(1, 1, 1, [](double u, double v, double w) { return Eigen::Vector3d(u, v, w); });
  try {
    cad::snap_to_brep(shape, m, tess);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Face7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("snap_bad.brep"), std::string::npos) << e.what();
  }
}

TEST(ImproveFixedNodes, FixedNodesNeverMove) {
  // A distorted grid: optimisation moves nodes, but none of the fixed ones.
  const mesh::Mesh m = grid(3, 3, 3, [](double u, double v, double w) {
    return Eigen::Vector3d(u + 0.15 * std::sin(7 * v + 3 * w), v + 0.1 * std::cos(5 * u), w + 0.1 * u * v);
  });
  optimize::ImproveOptions io;
  io.smooth = 2;
  io.optimize = 5;
  for (int v = 0; v < m.num_nodes(); v += 2) io.fixed_nodes.push_back(v);
  const optimize::ImproveResult r = optimize::improve(m, io);
  for (int v : io.fixed_nodes) EXPECT_EQ(r.mesh.V.row(v), m.V.row(v)) << v;
  EXPECT_GT((r.mesh.V - m.V).norm(), 0);  // the others did move
  io.fixed_nodes = {m.num_nodes()};
  EXPECT_THROW(optimize::improve(m, io), GeometryError);
}

TEST(ImproveProjectHook, DecidesWhereMovingBoundaryNodesGo) {
  // A hook that sends every boundary node back to where it was: only interior nodes move.
  const mesh::Mesh m = grid(3, 3, 3, [](double u, double v, double w) {
    return Eigen::Vector3d(u + 0.15 * std::sin(7 * v + 3 * w), v + 0.1 * std::cos(5 * u), w + 0.1 * u * v);
  });
  optimize::ImproveOptions io;
  io.smooth = 2;
  io.optimize = 5;
  int calls = 0;
  io.project = [&](int v, const Eigen::Vector3d&) -> Eigen::Vector3d {
    ++calls;
    return m.V.row(v).transpose();
  };
  const optimize::ImproveResult r = optimize::improve(m, io);
  EXPECT_GT(calls, 0);
  for (int v = 0; v < m.num_nodes(); ++v) {
    const int i = v % 4, j = (v / 4) % 4, k = v / 16;
    const bool inside = i > 0 && i < 3 && j > 0 && j < 3 && k > 0 && k < 3;
    if (!inside) {
      EXPECT_EQ(r.mesh.V.row(v), m.V.row(v)) << v;
    }
  }
}

#endif
