// mesh::join_surfaces: surfaces side by side, vertex ids shifted, patches kept (0 where missing).
#include <gtest/gtest.h>

#include "hexdom/mesh/mesh.h"

using namespace hexdom;

TEST(JoinSurfaces, ShiftsTheSecondSurfacesVerticesAndKeepsPatches) {
  mesh::SurfaceMesh a, b;
  a.V = Eigen::MatrixXd::Identity(3, 3);
  a.F.resize(1, 3);
  a.F << 0, 1, 2;
  a.patch.resize(1);
  a.patch << 4;
  b.V = 2 * Eigen::MatrixXd::Identity(4, 3);
  b.F.resize(2, 3);
  b.F << 0, 1, 2, 0, 2, 3;  // no patch ids
  const mesh::SurfaceMesh j = mesh::join_surfaces({&a, &b});
  ASSERT_EQ(j.V.rows(), 7);
  ASSERT_EQ(j.F.rows(), 3);
  EXPECT_EQ(j.F.row(1), Eigen::RowVector3i(3, 4, 5));
  EXPECT_EQ(j.F.row(2), Eigen::RowVector3i(3, 5, 6));
  EXPECT_EQ(j.V.row(4), b.V.row(1));
  EXPECT_EQ(j.patch, Eigen::Vector3i(4, 0, 0));
  EXPECT_EQ(mesh::join_surfaces({}).F.rows(), 0);
}
