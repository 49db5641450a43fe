#include "hexdom/autopolycube/repair/split_oblique_faces.h"

#include <set>

#include "auto_test_util.h"
#include "hexdom/autopolycube/autopolycube.h"
#include "hexdom/generation/generate.h"
#include "hexdom/optimize/improve.h"
#include "hexdom/quality/metrics.h"
#include "hexdom/segmentation/axis_labels.h"
#include "test_common.h"

using namespace hexdom;

namespace {

// The tetrahedron (0,0,0), (a,0,0), (0,a,0), (0,0,a): three faces at right angles (-X, -Y, -Z) and a
// slanted one of normal (1,1,1)/sqrt 3, which labels_from_normals (a tie) gives one label; every face
// split into n x n triangles.
mesh::SurfaceMesh tetrahedron(double a, int n) {
  const Eigen::RowVector3d o(0, 0, 0), x(a, 0, 0), y(0, a, 0), z(0, 0, a);
  return test::subdivided_triangles({{o, y, x}, {o, x, z}, {o, z, y}, {x, y, z}}, n);
}

double area(const mesh::SurfaceMesh& s) {
  double A = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    A += (b - a).cross(c - a).norm() / 2;
  }
  return A;
}

bool on_slanted_face(const mesh::SurfaceMesh& s, int f, double a) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(s.V.row(s.F(f, k)).sum() - a) > 1e-9) return false;
  return true;
}

}  // namespace

TEST(SplitObliqueFaces, ATetrahedronsSlantedFaceBecomesThreeQuadsLabelledFromItsCorners) {
  const double a = 4.0;
  mesh::SurfaceMesh s = tetrahedron(a, 8);
  const mesh::SurfaceMesh before = s;
  // Today's labelling: the slanted face is one chart, beside the face of its opposite label.
  std::set<int> slanted_before;
  for (int f = 0; f < s.F.rows(); ++f)
    if (on_slanted_face(s, f, a)) slanted_before.insert(s.patch(f));
  ASSERT_EQ(slanted_before.size(), 1u);

  const auto faces = autopolycube::split_oblique_faces(s);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_TRUE(faces[0].normal.isApprox(Eigen::Vector3d(1, 1, 1).normalized(), 1e-9));
  // The quad at the corner on axis k takes +k (the axis of the opposite side's neighbour, the sign of the normal).
  for (int k = 0; k < 3; ++k) {
    int on = -1;
    faces[0].corners[k].maxCoeff(&on);
    EXPECT_NEAR(faces[0].corners[k][on], a, 1e-12);
    EXPECT_EQ(faces[0].labels[k], 1 + 2 * on) << "corner " << k;
  }
  // The geometry is unchanged: old vertices in place, the same area and volume, still closed.
  ASSERT_GE(s.V.rows(), before.V.rows());
  EXPECT_TRUE(s.V.topRows(before.V.rows()).isApprox(before.V));
  EXPECT_NEAR(area(s), area(before), 1e-9 * area(before));
  EXPECT_NEAR(test::enclosed_volume(s), a * a * a / 6, 1e-9);
  EXPECT_NO_THROW(segmentation::check_surface(s));
  // On the slanted face, each triangle has the label of the axis of its centre's largest coordinate
  // (the medians cut the face along x = y, y = z, z = x); the other faces keep their labels.
  int slanted = 0;
  std::set<int> quads;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = (s.V.row(s.F(f, 0)) + s.V.row(s.F(f, 1)) + s.V.row(s.F(f, 2))).transpose() / 3;
    if (!on_slanted_face(s, f, a)) {
      const Eigen::Vector3d p = s.V.row(s.F(f, 0)), q = s.V.row(s.F(f, 1)), r = s.V.row(s.F(f, 2));
      EXPECT_EQ(s.patch(f), segmentation::nearest_label((q - p).cross(r - p)));
      continue;
    }
    ++slanted;
    int k = 0;
    c.maxCoeff(&k);
    EXPECT_EQ(s.patch(f), 1 + 2 * k) << "triangle " << f << " centre " << c.transpose();
    quads.insert(s.patch(f));
  }
  EXPECT_GT(slanted, static_cast<int>(slanted_before.size()));
  EXPECT_EQ(quads, (std::set<int>{1, 3, 5}));
  // The cuts are straight: a vertex where two quads meet lies on their median (within the snap of
  // cut_triangles, 1% of a barycentric coordinate).
  for (int f = 0; f < s.F.rows(); ++f) {
    if (!on_slanted_face(s, f, a)) continue;
    for (int g = 0; g < s.F.rows(); ++g) {
      if (g == f || !on_slanted_face(s, g, a) || s.patch(g) <= s.patch(f)) continue;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (s.F(f, i) == s.F(g, j)) {
            const int p = (s.patch(f) - 1) / 2, q = (s.patch(g) - 1) / 2;
            EXPECT_NEAR(s.V(s.F(f, i), p), s.V(s.F(f, i), q), 0.02 * a) << "vertex " << s.F(f, i);
          }
    }
  }
}

TEST(SplitObliqueFaces, FacesNearAnAxisOrLeaningBetweenTwoAxesAreLeftAlone) {
  mesh::SurfaceMesh cube = test::cell_surface({{0, 0, 0}}, 4);
  EXPECT_TRUE(autopolycube::split_oblique_faces(cube).empty());
  // A pyramid's sides lean between two axes only (a component 0).
  mesh::SurfaceMesh pyr = test::pyramid_surface(4.0, 3.0, 8);
  const mesh::SurfaceMesh pyr0 = pyr;
  EXPECT_TRUE(autopolycube::split_oblique_faces(pyr).empty());
  EXPECT_EQ(pyr.patch, pyr0.patch);
}

TEST(SplitObliqueFaces, TheTetrahedronHasAPolycubeOnlyWithTheSplit) {
  const mesh::SurfaceMesh s = tetrahedron(4.0, 16);
  autopolycube::AutoPolycubeOptions o;
  o.level = 1;
  o.size = 0.25;
  o.oblique_faces = false;
  EXPECT_THROW(autopolycube::autopolycube(s, o), GeometryError);
  o.oblique_faces = true;
  const auto r = autopolycube::autopolycube(s, o);
  EXPECT_EQ(r.oblique_faces, 1);
  EXPECT_EQ(r.relabelled, 0);
  EXPECT_EQ(r.charts, 6);  // a cube: three faces at right angles and three quads
  EXPECT_EQ(r.structure.count(mesh::CellType::Hex), r.structure.num_cells());
  // No block is inverted; the blocks at the face's centre and at the edges' midpoints have a corner
  // whose three edges lie in one plane (three quads at 120 degrees; two edges along one straight
  // edge), scaled Jacobian 0 there, which the improvement's pillow layer takes away.
  EXPECT_GT(r.min_block_quality, -1e-9);
  generation::GenerateOptions go;
  go.level = 1;
  const mesh::Mesh generated = generation::generate(r.patches, r.structure, go);
  optimize::ImproveOptions io;
  io.surface = r.patches;
  const optimize::ImproveResult ir = optimize::improve(generated, io);
  EXPECT_GT(ir.pillow_cells, 0);
  EXPECT_EQ(ir.after.hex.inverted, 0);
  EXPECT_GT(ir.after.hex.sj_min, 0.15);
  // The blocks fill the tetrahedron: their volume is the tetrahedron's up to the boundary squares'
  // chords (the slanted face is flat, so none).
  double volume = 0;
  for (int b = 0; b < r.structure.num_cells(); ++b) volume += quality::volume(r.structure.type(b), quality::cell_points(r.structure, b));
  EXPECT_NEAR(volume, 64.0 / 6, 1e-6 * 64.0);
}
