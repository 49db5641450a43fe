// Node moves that raise the worst cells of a volume mesh without changing its connectivity: the
// relaxation of nodes next to poor cells and the untangling of inverted cells, surface nodes
// sliding within the surface. Quality is the scaled Jacobian (quality/metrics.h) and its samples
// (quality/jacobian_samples.h).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "hexdom/mesh/adjacency.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/node_kinds.h"

namespace hexdom::optimize {

/// How each node may move (its NodeKind): freely (Interior), in the parameter plane of its patch
/// (Surface), along its boundary curve (Curve; both keep it on the surface that `place`
/// evaluates), or not at all (Corner). A Curve node uses only the first parameter.
struct NodeFreedom {
  std::vector<signed char> kind;             ///< per node, a NodeKind
  std::vector<std::array<double, 2>> param;  ///< per node: the parameters where it was made
  std::vector<std::array<double, 2>> now;    ///< per node: the parameters of its current position
  /// 3D position x of surface node v at parameters q.
  std::function<void(int v, const double* q, double* x)> place;
  /// Clamps parameters q of surface node v into its domain.
  std::function<void(int v, double* q)> clamp;
};

/// Moves nodes of kind Interior (`kind`: a NodeKind per node) that belong to a cell whose
/// scaled Jacobian (quality::scaled_jacobian, -1 for inverted cells) is at most `poor` towards the
/// centroid of their edge neighbours (steps 1, 1/2, 1/4 of the way), keeping a move only when the
/// worst scaled Jacobian of the node's cells rises by more than 1e-12. Sweeps over those nodes in
/// increasing order, skipping a node until a node of one of its cells has moved since its last
/// failed try, until a sweep moves none or after `sweeps` sweeps.
/// Inputs: `cells` = mesh::node_cells(M); the search for poor cells runs on `threads` threads (the
/// result does not depend on their number).
/// Guarantees: only Interior nodes move; no cell of a moved node falls below the worst of that
/// node's cells before the move, so the mesh's worst cell never gets worse; deterministic.
/// When `left` is given it receives, in increasing order, every cell some of whose Jacobian samples
/// are at most `left_threshold` (< poor) afterwards.
/// Returns a one-line summary for the log.
std::string relax_poor(mesh::Mesh& M, const mesh::NodeCells& cells, const std::vector<signed char>& kind, int sweeps,
                       double poor, int threads, std::vector<int>* left = nullptr, double left_threshold = 0);

/// Untangles and raises poor cells: the cells with a Jacobian sample at most `trigger` (only those
/// in `candidates` when given: a superset of them in increasing order) are poor; their nodes are
/// visited, nodes not Corner, surface nodes only next to poor cells whose worst sample is at most
/// `poor_surface`. A visited node inside the volume first tries the centroid of its edge
/// neighbours (steps 1, 1/2, 1/4); a node whose worst sample is below poor / 2 then descends a
/// penalty on its samples below `poor` by finite differences (surface nodes in their curve or
/// patch parameters, each parameter within `box` of where the node was made). Inverted cells have
/// negative samples, so the descent untangles them. A move is kept only when it raises the worst
/// Jacobian sample depending on the node by more than 1e-12 and leaves every edge of the node at
/// least min(a tenth of their mean length, its shortest edge). Nodes of cells still at most
/// `trigger` next to a node that gained 1e-4 or more are visited in the next round, up to `sweeps`
/// rounds.
/// Inputs: `cells` = mesh::node_cells(M); F.now holds the current parameters of surface nodes (and
/// is updated with the moves), F.place and F.clamp evaluate and bound them.
/// Guarantees: no sample that depends on a moved node falls below the worst such sample before the
/// move, so the mesh's worst cell never gets worse; surface nodes stay where F.place puts them;
/// connectivity unchanged; deterministic. When `left` is given it receives, in increasing order,
/// the cells with a sample at most `trigger` afterwards.
/// Returns a one-line summary for the log.
std::string untangle_nodes(mesh::Mesh& M, const mesh::NodeCells& cells, NodeFreedom& F, int sweeps, double trigger,
                           double poor, double poor_surface, double box, const std::vector<int>* candidates = nullptr,
                           std::vector<int>* left = nullptr);

}  // namespace hexdom::optimize
