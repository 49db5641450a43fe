// Node kinds of a volume mesh for the optimiser: which nodes may move, and where to.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include "hexdom/mesh/adjacency.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::optimize {

/// How a node may move, from most to least constrained: not at all (where three or more feature
/// curves meet, or a node held fixed), along its feature curve, on the boundary surface, or freely
/// inside the volume. The values of Curve and Surface are the numbers of parameters a node of that
/// kind moves in on the surface (NodeFreedom).
enum NodeKind : signed char { Corner = 0, Curve = 1, Surface = 2, Interior = 3 };

/// The boundary structure of a volume mesh the optimiser works with.
struct NodeKinds {
  mesh::NodeCells node_cells;                ///< per node: its cells, in increasing order
  std::vector<std::vector<int>> node_faces;  ///< per node: its boundary faces (indices into `faces`)
  std::vector<mesh::BoundaryFace> faces;     ///< mesh::boundary_faces, in its order
  std::vector<NodeKind> kind;                ///< per node
  std::vector<std::vector<int>> curve_nbrs;  ///< per node: its neighbours along sharp boundary edges
  std::vector<std::vector<int>> edge_nbrs;   ///< per node: its mesh-edge neighbours, sorted
  std::vector<int> region;  ///< per boundary face: its smooth region (faces joined across edges not sharp)
  std::vector<std::pair<int, int>> across_sharp;  ///< the two faces of each sharp edge that has two
};

/// Classifies the nodes of a volume mesh. A boundary edge is sharp when `sharp` (#V flags) is given
/// and flags both its nodes, or, without it, when its faces' normals differ by more than
/// `feature_angle` degrees or it has other than two faces. A boundary node on no sharp edge is a
/// Surface node, on two a Curve node, otherwise a Corner. Throws GeometryError for a mesh that is
/// not conforming (mesh::boundary_faces).
NodeKinds node_kinds(const mesh::Mesh& mesh, double feature_angle, const std::vector<char>* sharp);

/// Geometry the boundary nodes must keep: the surface, and the feature curves as degenerate
/// triangles (one per sharp edge).
struct BoundaryConstraints {
  mesh::TriangleProjector surface, curves;
  /// Where set, replaces both projections for Surface and Curve nodes (ImproveOptions::project).
  std::function<Eigen::Vector3d(int, const Eigen::Vector3d&)> project;
  /// Whether `project` may be called from several threads at once (for different nodes).
  bool project_concurrent = false;
};

/// The constraints of `mesh` classified as `kinds`: the surface is `given` when it has triangles,
/// else the mesh's own boundary faces (quads split at their first node); the curves are the sharp
/// edges at the mesh's positions.
BoundaryConstraints boundary_constraints(const mesh::Mesh& mesh, const NodeKinds& kinds, const mesh::SurfaceMesh& given);

}  // namespace hexdom::optimize
