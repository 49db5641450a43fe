// Puts the boundary nodes of a volume mesh exactly on the B-rep it was made from, so that FEM
// constraints on CAD faces (which look for nodes within 1e-7 of a face) find them.
//
// Method: every boundary face of the mesh takes the CAD face of the tessellation triangle nearest its
// centroid; a boundary node gathers the CAD faces of its boundary faces (and of the triangle nearest
// itself). A node among three or more CAD faces that meet at a CAD vertex, and near it, goes onto the
// vertex (one node per vertex); a node among two or more CAD faces that share a CAD edge, and near it,
// goes onto the edge; every other boundary node goes onto the nearest of its CAD faces (trimmed).
// "Near" is `edge_tolerance` times the node's shortest boundary edge, so a mesh that does not follow
// a CAD edge (a smooth blend crossed by the polycube) is not pulled onto it. Then the interior nodes
// are untangled and optimised (optimize::improve), the boundary nodes sliding along their own CAD face
// or edge (`slide`, exact projections) or held fixed, the vertex nodes always fixed.
//
// Unlike the rest of hexdom_cad this uses the quality stage of hexdom_core, for the last step.
#pragma once

#include <vector>

#include "hexdom/cad/shape.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/quality/report.h"

namespace hexdom::cad {

struct SnapOptions {
  /// A node goes onto a CAD edge (vertex) of its faces when it lies within this fraction of its
  /// shortest boundary edge from it.
  double edge_tolerance = 0.25;
  /// Quality restoration of the interior nodes afterwards: smoothing passes and optimisation rounds
  /// (optimize::improve with the boundary nodes fixed); both 0 skips it.
  int smooth = 3;
  int optimize = 20;
  /// Edge-ratio target of the final restoration (optimize::ImproveOptions::max_edge_ratio); 0: none.
  double max_edge_ratio = 0;
  /// During the restoration, boundary nodes may slide along their own CAD face or edge (vertex
  /// nodes stay); false holds every boundary node where the projection put it.
  bool slide = true;
  /// The restoration keeps every cell at or above min(keep, worst SJ before the snap) there, even
  /// while the cells the projection inverted are untangled (optimize::ImproveOptions::floor):
  /// without it, untangling a thin layer cell lets cells the snap never touched drop to the level of
  /// the worst. When that leaves cells inverted, the restoration is run again without it and the
  /// better kept. Negative: no floor.
  double keep = 0.3;
  /// When the direct snap (all boundary nodes at once, then the restoration) ends with inverted
  /// cells or below both the worst SJ before it and `keep`, the snap is made again in this many
  /// equal steps, the interior restored with the boundary held after each but the last, so that
  /// the thin cells along the boundary (a pillow layer) follow instead of inverting; the better
  /// result is kept (fewer inverted cells, then the better worst cell). 1: direct only.
  int steps = 2;
  /// Empty, or #V of the mesh: nodes marked non-zero go onto the nearest of their CAD faces only,
  /// never onto a CAD edge or vertex (the overlay path's nodes on a smooth region, some of which it
  /// let off a sharp curve on purpose so that a cell does not flatten along it).
  std::vector<char> face_only;
  /// Threads of the restoration (optimize::ImproveOptions::threads; 0: one per core). The boundary
  /// nodes sliding on their CAD faces move on the calling thread; the mesh does not depend on it.
  int threads = 0;
  LogCallback log;
};

/// What a boundary node was put on.
enum class SnapKind : int { Interior = 0, Face = 1, Edge = 2, Vertex = 3 };

struct SnapReport {
  int boundary_nodes = 0;
  int face_nodes = 0, edge_nodes = 0, vertex_nodes = 0;  ///< boundary nodes moved onto each kind
  /// Distances of the boundary nodes to the B-rep, before and after: each node's distance to the
  /// point of its CAD face, edge or vertex it is put on, and after the restoration to that face, edge
  /// or vertex (OCCT projections); each at least the node's distance to the whole B-rep.
  double max_before = 0, mean_before = 0, max_after = 0, mean_after = 0;
  double max_move = 0;   ///< largest displacement of a boundary node
  double diagonal = 0;   ///< bounding-box diagonal of the mesh, for relative figures
  int inverted_snapped = 0;  ///< inverted cells right after the projection
  int inverted = 0;          ///< inverted cells after the restoration
  double worst_sj_before = 0, worst_sj_snapped = 0, worst_sj = 0;  ///< worst cell SJ (all types)
  double seconds_project = 0, seconds_restore = 0;
};

struct SnapResult {
  mesh::Mesh mesh;
  SnapReport report;
  quality::QualityReport quality;   ///< of `mesh`
  std::vector<SnapKind> kind;       ///< #V: what each node was put on
  std::vector<int> entity;          ///< #V: 1-based face, edge or vertex id (FreeCAD numbering); 0 inside
  /// #V: the CAD faces (1-based, increasing) each node lies on: its face's; an edge's or a vertex's
  /// faces for a node put on one; empty inside. The FEM face sets take a node into Face<k> by it.
  std::vector<std::vector<int>> faces;
};

/// Projects the boundary nodes of `mesh` (hex / prism / tet, conforming) onto the B-rep of `shape`,
/// classified by the CAD face ids of `tessellation` (a tessellation of `shape`: patch(t) is the
/// 1-based CAD face of triangle t, as cad::tessellate gives), then restores the interior. Inverted
/// cells that remain are counted in the report and the quality, not thrown. Throws InputError when
/// the tessellation names a face the shape does not have, GeometryError for a non-conforming mesh.
SnapResult snap_to_brep(const Shape& shape, const mesh::Mesh& mesh, const mesh::SurfaceMesh& tessellation,
                        const SnapOptions& options = {});

}  // namespace hexdom::cad
