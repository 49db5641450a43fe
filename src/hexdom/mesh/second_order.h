// Second-order meshes from first-order ones: a node in the middle of every cell edge.
#pragma once

#include <array>
#include <vector>

#include "hexdom/mesh/mesh.h"

namespace hexdom::mesh {

/// `linear` (volume cells only, first order) made second order: one new node per mesh edge, at
/// its midpoint, shared by every cell around the edge. The corner nodes keep their numbers; the
/// mid-edge nodes follow them (rows num_nodes() of `linear` on), in the order the cells first use
/// their edges. Throws GeometryError naming a 2D cell, InputError for a second-order input.
Mesh add_mid_edge_nodes(const Mesh& linear);

/// The two corner nodes of every mid-edge node of a second-order mesh: #V entries, {-1, -1} for
/// the corner nodes. Throws GeometryError when two cells give one mid-edge node different ends.
std::vector<std::array<int, 2>> mid_edge_ends(const Mesh& mesh);

/// Node coordinates of cell c of a second-order mesh in VTK's quadratic order (corners, then
/// the mid-edge nodes): node_count + edge_count rows (20, 15, 10) of `p`. Returns that number.
int second_order_points(const Mesh& mesh, int c, double (*p)[3]);

/// Most nodes a second-order cell has (the 20-node hex's).
constexpr int kMaxSecondOrderNodes = 20;

}  // namespace hexdom::mesh
