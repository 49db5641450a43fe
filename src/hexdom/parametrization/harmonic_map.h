// Harmonic maps of disk-like triangle patches onto a convex polygon (a polycube face).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace hexdom::parametrization {

/// Cotangent Laplacian of a triangle mesh: L(i,j) = (cot a + cot b) / 2 for an edge (i,j),
/// L(i,i) = -sum of the row. \note L is negative semi-definite; constant vectors lie in its kernel.
Eigen::SparseMatrix<double> cotmatrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

enum class Weights { Cotangent, MeanValue };

struct HarmonicMapResult {
  Eigen::MatrixXd uv;   ///< #V by 2 parametric positions (rows of vertices not in F are untouched)
  Weights weights;      ///< weights used in the end
  int flipped = 0;      ///< parametric triangles with the wrong orientation (0 when bijective;
                        ///< triangles with all corners on one straight side have zero area)
};

/// Maps the triangles F (a topological disk over V) with boundary vertices `b` fixed at `bc` (#b by 2)
/// by a harmonic map: cotangent weights solved by sparse Cholesky; if any parametric triangle flips
/// (cotangent weights can be negative), it falls back to mean-value weights, which are positive and
/// give a bijection onto a convex boundary polygon (Floater). Orientation is judged against the
/// boundary polygon's own orientation. Throws MeshingError when the linear solve fails.
HarmonicMapResult harmonic_map(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                               const std::vector<int>& b, const Eigen::MatrixXd& bc);

}  // namespace hexdom::parametrization
