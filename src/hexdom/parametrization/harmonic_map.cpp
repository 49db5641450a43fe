#include "hexdom/parametrization/harmonic_map.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cmath>

#include "hexdom/common/error.h"

namespace hexdom::parametrization {

Eigen::SparseMatrix<double> cotmatrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(F.rows() * 12);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      int i = F(f, k), j = F(f, (k + 1) % 3), o = F(f, (k + 2) % 3);
      Eigen::Vector3d a = V.row(i) - V.row(o), b = V.row(j) - V.row(o);
      double c = a.dot(b) / std::max(a.cross(b).norm(), 1e-300);  // cot of the angle at o
      t.emplace_back(i, j, 0.5 * c);
      t.emplace_back(j, i, 0.5 * c);
      t.emplace_back(i, i, -0.5 * c);
      t.emplace_back(j, j, -0.5 * c);
    }
  }
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

namespace {

// Mean-value weights w_ij = (tan(a1/2) + tan(a2/2)) / |v_i - v_j| (Floater), as a Laplacian whose
// diagonal is minus the row sum. Not symmetric.
Eigen::SparseMatrix<double> mean_value_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(F.rows() * 12);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      int i = F(f, k), j = F(f, (k + 1) % 3), o = F(f, (k + 2) % 3);
      Eigen::Vector3d eij = V.row(j) - V.row(i), eio = V.row(o) - V.row(i);
      double lij = eij.norm(), lio = eio.norm();
      double ang = std::atan2(eij.cross(eio).norm(), eij.dot(eio));  // angle at i
      double tn = std::tan(0.5 * ang);
      // The angle at i between edges (i,j) and (i,o) contributes to w_ij and w_io.
      t.emplace_back(i, j, tn / std::max(lij, 1e-300));
      t.emplace_back(i, o, tn / std::max(lio, 1e-300));
      t.emplace_back(i, i, -tn / std::max(lij, 1e-300) - tn / std::max(lio, 1e-300));
    }
  }
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

double signed_area(const Eigen::MatrixXd& uv, int a, int b, int c) {
  return 0.5 * ((uv(b, 0) - uv(a, 0)) * (uv(c, 1) - uv(a, 1)) - (uv(c, 0) - uv(a, 0)) * (uv(b, 1) - uv(a, 1)));
}

}  // namespace

HarmonicMapResult harmonic_map(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const std::vector<int>& b, const Eigen::MatrixXd& bc) {
  const int n = static_cast<int>(V.rows());
  std::vector<int> slot(n, -1);  // -2 boundary, >=0 interior unknown, -1 unused
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) slot[F(f, k)] = 0;
  for (int v : b) slot[v] = -2;
  std::vector<int> interior;
  for (int v = 0; v < n; ++v)
    if (slot[v] == 0) { slot[v] = static_cast<int>(interior.size()); interior.push_back(v); }
  HarmonicMapResult r;
  r.uv = Eigen::MatrixXd::Zero(n, 2);
  for (size_t i = 0; i < b.size(); ++i) r.uv.row(b[i]) = bc.row(i);
  // Orientation of the boundary polygon: the sign every parametric triangle must share.
  double poly = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    const auto& p = bc.row(i);
    const auto& q = bc.row((i + 1) % b.size());
    poly += p(0) * q(1) - q(0) * p(1);
  }
  const double sign = poly >= 0 ? 1.0 : -1.0;

  for (Weights w : {Weights::Cotangent, Weights::MeanValue}) {
    r.weights = w;
    if (!interior.empty()) {
      Eigen::SparseMatrix<double> L = w == Weights::Cotangent ? cotmatrix(V, F) : mean_value_matrix(V, F);
      const int m = static_cast<int>(interior.size());
      std::vector<Eigen::Triplet<double>> t;
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
      for (int k = 0; k < L.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
          int i = static_cast<int>(it.row()), j = static_cast<int>(it.col());
          if (slot[i] < 0) continue;
          if (slot[j] >= 0) t.emplace_back(slot[i], slot[j], -it.value());
          else if (slot[j] == -2) rhs.row(slot[i]) += it.value() * r.uv.row(j);
        }
      Eigen::SparseMatrix<double> A(m, m);
      A.setFromTriplets(t.begin(), t.end());
      Eigen::MatrixXd x;
      if (w == Weights::Cotangent) {
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
        if (solver.info() != Eigen::Success) continue;  // not positive definite: try mean value
        x = solver.solve(rhs);
      } else {
        Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
        solver.analyzePattern(A);
        solver.factorize(A);
        if (solver.info() != Eigen::Success) throw MeshingError("harmonic map: the mean-value system is singular");
        x = solver.solve(rhs);
      }
      if (!x.allFinite()) continue;
      for (int i = 0; i < m; ++i) r.uv.row(interior[i]) = x.row(i);
    }
    r.flipped = 0;
    for (int f = 0; f < F.rows(); ++f)
      if (sign * signed_area(r.uv, F(f, 0), F(f, 1), F(f, 2)) < 0) ++r.flipped;  // 0: an ear on one side
    if (r.flipped == 0) return r;
  }
  return r;
}

}  // namespace hexdom::parametrization
