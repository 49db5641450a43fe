// The overlay path's buffer layer: one hexahedron over every boundary quad of the core, its outer
// face on the surface, and the outer nodes put on the surface's regions, curves and corners.
#pragma once

#include <vector>

#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/node_kinds.h"
#include "hexdom/overlay/features.h"

namespace hexdom::overlay {

/// What each node of the meshed part was put on: kind Interior (core nodes), Surface (`a` the
/// region; -1: the nearest point of the whole surface, for a node let off its region), Curve (the curve between regions `a` < `b`) or Corner (`a` the feature corner's index
/// in SurfaceFeatures::corners()).
struct Placement {
  std::vector<optimize::NodeKind> kind;
  std::vector<int> a, b;
  int surface = 0, curve = 0, corner = 0;
  int demoted = 0;     ///< curve nodes let off their curve where a quad would have three on it
  int corners_missed = 0;  ///< feature corners no outer node came near
  /// Per outer quad (place_outer_nodes' `outer`, in its order): the region it took.
  std::vector<int> quad_region;
  /// Per outer quad and edge i (its nodes i, i + 1): the other quad on it (-1: none), as
  /// place_outer_nodes found them; pillow_curves, which adds quads, clears them.
  std::vector<std::array<int, 4>> quad_neighbours;
};

/// The core (hexahedra, boundary a 2-manifold) with one more hexahedron on each boundary quad: its
/// inner face the quad, its outer face a copy of it whose nodes are new. `outer` receives the outer
/// quads (outward, as mesh::boundary_faces orients them, their nodes the new ones); `copy`, when
/// given, each core node's outer copy (-1 for nodes inside the core).
mesh::Mesh add_buffer_layer(const mesh::Mesh& core, std::vector<std::array<int, 4>>* outer,
                            std::vector<int>* copy = nullptr);

/// Moves each core node that has an outer copy (`copy`, from add_buffer_layer, after the outer
/// nodes were put on the surface) along the outer quads' mean normal n at its copy, so that it
/// lies at least its `depth` (per node of m; a single value for all when depth has one entry)
/// inside its copy: x -= (depth - (x_copy - x).n) n when that is positive.
/// Where the solid is thinner (the point 1.5 depth inside the copy is nearer the surface's other
/// side, whose normal faces against n), the depth is halved, at most 4 times, so that the two
/// sides' layers leave a third of the thickness between them. Returns the number of nodes moved.
int pull_inner_nodes(mesh::Mesh& m, const std::vector<std::array<int, 4>>& outer, const std::vector<int>& copy,
                     const SurfaceFeatures& features, const std::vector<double>& depth);

/// Puts the outer nodes of `m` (those of `outer`) on the surface. Each outer quad takes the region
/// nearest its centroid, or, when the surface there faces more than 60 degrees away from the quad
/// (a core cell jutting past the face beside the one it faces), the region its normal line meets
/// first (either way, within 1.5 quad diagonals or twice the closest point's distance, whichever is
/// more) where that one faces within 60 degrees of it (then a quad whose
/// neighbours mostly took another region takes theirs); a
/// node on quads of one region goes onto that region, on two regions that share a curve onto the
/// curve, and each feature corner gets the nearest node among those on two of its regions (within
/// `reach`). Where a quad would have three consecutive nodes on one curve (a staircase of the grid
/// along a curve, which flattens the quad's corner), the middle one leaves the curve for the region
/// across it, so the quad follows the curve along its diagonal; not with `staircases` false (for
/// pillow_curves, which takes every curve node off the regions' quads).
Placement place_outer_nodes(mesh::Mesh& m, const std::vector<std::array<int, 4>>& outer, const SurfaceFeatures& features,
                            double reach, bool staircases = true);

/// What pillow_curves added.
struct CurvePillow {
  int prisms = 0;  ///< wedges, two per outer edge between two regions
  int copies = 0;  ///< nodes added: one per region sector of each outer node where regions meet
};

/// Sheets of prisms along the region boundaries of the buffer layer, so that no outer quad of a
/// region keeps a node on a curve (a grid's staircase along a curve otherwise flattens the quad
/// at each of its turns, on one side or the other). At each outer node where quads of different
/// regions (p.quad_region) meet, each sector (the quads around it of one region, consecutive)
/// takes a copy of the node, its buffer hexes the copy; each outer edge between two regions gets
/// a wedge on either side, between the hex's old wall and its new one, the core nodes under the
/// edge shared. The old nodes keep their placement (curve or corner) and lie on the wedges only;
/// each copy goes onto its sector's region (placement Surface), `offset` of the way from the old
/// node to the mean centroid of the sector's quads. The wedges' outer quads are appended to
/// `outer` and p.quad_region (their side's region); each wedge is valid where its hex's corners at
/// the edge are. Requires m's last outer.size() cells to be add_buffer_layer's hexes in outer's
/// order (std::logic_error otherwise).
CurvePillow pillow_curves(mesh::Mesh& m, std::vector<std::array<int, 4>>& outer, Placement& p,
                          const SurfaceFeatures& features, double offset);

/// Laplacian passes over the outer nodes with an outer edge shorter than `crowded` (the closest
/// points crowd them onto a reflex curve): each moves to the mean of its neighbours on its region
/// or curve and back onto it; corners stay.
void spread(mesh::Mesh& m, const std::vector<std::array<int, 4>>& outer, const Placement& p, const SurfaceFeatures& features,
            int passes, double crowded);

/// Per node: its neighbours along the outer quads' edges that lie on the same curve (curve nodes of
/// the same pair of regions, corners on both); empty for other nodes.
std::vector<std::vector<int>> curve_neighbours(const Placement& p, const std::vector<std::array<int, 4>>& outer,
                                               const SurfaceFeatures& features);

/// Lets `nodes` (in any order, repeated or not) off one level of feature: a node on a region goes
/// anywhere on the surface (its nearest point), a node on a curve onto the first of its two regions,
/// a corner onto one of its curves (the first pair of its regions that shares one). For cells the
/// optimiser could not make valid with their nodes held on sharp features or on one face. Returns
/// the number of nodes let off.
int loosen_nodes(Placement& p, std::vector<int> nodes, const SurfaceFeatures& features);

/// Where node v of a placement goes for a candidate position x (its region, curve or corner).
/// `hint`, when given: the node's last triangle, a first bound for the closest point, updated
/// (any triangle index, even of another region, gives the same answer; SurfaceFeatures::project_region).
Eigen::Vector3d place(const Placement& p, const SurfaceFeatures& features, int v, const Eigen::Vector3d& x,
                      int* hint = nullptr);

}  // namespace hexdom::overlay
