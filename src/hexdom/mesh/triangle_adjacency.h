// Edge neighbours of the triangles of a closed manifold surface.
#pragma once

#include <Eigen/Core>

namespace hexdom::mesh {

/// #F by 3: TT(f, k) is the triangle across edge (F(f, k), F(f, (k + 1) % 3)), -1 on an open edge.
/// Expects a manifold surface (see check_surface); with more than two triangles on an edge the
/// result pairs the two lowest (f, k) half-edges on it.
Eigen::MatrixXi triangle_adjacency(const Eigen::MatrixXi& F);

}  // namespace hexdom::mesh
