// Cutting triangles of a surface along the zero level of a vertex field, without changing the
// geometry (apex caps, halves of boundary squares, oblique faces split from their corners).
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <map>
#include <vector>

namespace hexdom::autopolycube {

/// Cuts the triangles `tris` of F along the zero level of the vertex field f (linear along edges;
/// values of magnitude below eps are taken as 0, and f is changed so), as cut_along_grid cuts along
/// grid lines: a new vertex where an edge crosses, at the position of the same barycentric
/// coordinates (appended to `extra`, numbered from nv; pos gives any vertex's position, f gets 0 at
/// it), so the geometry does not change. An edge is cut once even when two of `tris` share it.
/// Returns the pieces (three vertices, the triangle of F they came from) in the triangles'
/// orientation. f must hold a value for every vertex of `tris`.
/// \note Triangles that share a cut edge but are not in `tris` are not cut: the caller keeps the
/// surface conforming (the edge lies inside the set, or its crossing was split before).
std::vector<std::array<int, 4>> cut_triangles(const Eigen::MatrixXi& F, const std::vector<int>& tris, std::map<int, double>& f,
                                              double eps, int nv, std::vector<Eigen::RowVector3d>& extra,
                                              const std::function<Eigen::RowVector3d(int)>& pos);

}  // namespace hexdom::autopolycube
