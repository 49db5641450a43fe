#include <Eigen/Geometry>
#include <cmath>

#include "hexdom/parametrization/harmonic_map.h"
#include "test_common.h"

using namespace hexdom::parametrization;

namespace {
// A wavy grid over [0,1]^2 (z = bumps), k x k cells, two triangles per cell.
void wavy_grid(int k, Eigen::MatrixXd& V, Eigen::MatrixXi& F, std::vector<int>& b) {
  V.resize((k + 1) * (k + 1), 3);
  F.resize(2 * k * k, 3);
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i <= k; ++i) {
      double x = double(i) / k, y = double(j) / k;
      // Irregular in-plane spacing, so that cotangent weights are not uniform.
      V.row(j * (k + 1) + i) << x + 0.03 * std::sin(7 * y), y + 0.03 * std::sin(5 * x), 0.2 * std::sin(3 * x) * std::cos(2 * y);
    }
  int f = 0;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      int a = j * (k + 1) + i;
      F.row(f++) << a, a + 1, a + k + 2;
      F.row(f++) << a, a + k + 2, a + k + 1;
    }
  for (int i = 0; i < k; ++i) b.push_back(i);
  for (int j = 0; j < k; ++j) b.push_back(j * (k + 1) + k);
  for (int i = k; i > 0; --i) b.push_back(k * (k + 1) + i);
  for (int j = k; j > 0; --j) b.push_back(j * (k + 1));
}
}  // namespace

TEST(Cotmatrix, RowsSumToZero) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<int> b;
  wavy_grid(6, V, F, b);
  Eigen::SparseMatrix<double> L = cotmatrix(V, F);
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(V.rows());
  EXPECT_LT((L * ones).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(L) - Eigen::MatrixXd(L).transpose()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(HarmonicMap, ReproducesALinearFunctionOfAPlanarMesh) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<int> b;
  wavy_grid(8, V, F, b);
  V.col(2).setZero();  // planar: the identity (x, y) is harmonic for cotangent weights
  Eigen::MatrixXd bc(b.size(), 2);
  for (size_t i = 0; i < b.size(); ++i) bc.row(i) = V.row(b[i]).head<2>();
  auto r = harmonic_map(V, F, b, bc);
  EXPECT_EQ(r.weights, Weights::Cotangent);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_LT((r.uv - V.leftCols(2)).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(HarmonicMap, CurvedPatchOntoSquareFlipsNothing) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<int> b;
  wavy_grid(10, V, F, b);
  Eigen::MatrixXd bc(b.size(), 2);
  const int k = 10;
  for (size_t i = 0; i < b.size(); ++i) {
    int s = static_cast<int>(i) / k, t = static_cast<int>(i) % k;
    double u = double(t) / k;
    Eigen::Vector2d p = s == 0 ? Eigen::Vector2d(u, 0) : s == 1 ? Eigen::Vector2d(1, u) : s == 2 ? Eigen::Vector2d(1 - u, 1) : Eigen::Vector2d(0, 1 - u);
    bc.row(i) = p.transpose();
  }
  auto r = harmonic_map(V, F, b, bc);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_GE(r.uv.minCoeff(), -1e-12);
  EXPECT_LE(r.uv.maxCoeff(), 1 + 1e-12);
}
