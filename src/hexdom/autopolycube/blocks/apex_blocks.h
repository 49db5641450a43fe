// Tet and prism blocks at an apex (issue 9, "prism / tet blocks where a chart is triangular").
//
// At the tip of a cone or a pyramid only side charts meet (+-X and +-Y around a tip pointing up),
// which no polycube has: the label repair merged them all into one chart and gave up. Two steps:
//  - add_apex_caps gives the triangles around such a vertex (its 1-ring) the missing axis' label
//    (the sign of their mean normal), so the labelling becomes that of a frustum, which the polycube
//    path meshes (a cap chart of one plane, the side charts' top edges on it);
//  - collapse_apexes then collapses the cap's squares to the apex: a block under the cap has its
//    cap face at one point (a pyramid) and becomes 2 tets, split along a diagonal of its other face;
//    the blocks of the column below become 2 prisms each along the same diagonal, so faces stay
//    conforming (tet faces triangles, hex faces quads, prisms between), down to the boundary square
//    that ends the column, whose triangles are cut along the diagonal into two triangular patches. The
//    cap's triangles are replaced by a fan from the apex over the cap's boundary (the same plane as
//    the 1-ring triangles they came from), each fan triangle joining the side square beside it.
// A hex corner at the apex is bounded by the tip's angle (three edges: two generatrices and the
// axis; about 0.28 at a half-angle of 32 degrees), tets there have the tip's solid angle shared
// among fewer cells.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "hexdom/autopolycube/blocks/grid_polycube.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

struct ApexCapOptions {
  /// A vertex is an apex when the labels of its triangles are three or more of two axes only and
  /// the mean unit normal of its triangles has at least this component along the third axis.
  double min_normal = 0.05;
  /// ... and every triangle's unit normal has at least this component along it (the ends of the thin
  /// wedge's knife edge, whose end faces are at right angles to the missing axis, are no tips).
  double min_lean = 0.01;
  /// ... and the angles of its triangles at it sum to at most this share of a full turn (a vertex on a
  /// crease where labels of two axes meet turns a full turn: no tip).
  double max_angle = 0.8;
  /// The cap: the triangles within this distance of the apex, cut at that sphere (the input's
  /// geometry kept); 0: the apex's 1-ring.
  double radius = 0;
  LogCallback log;
};

/// Gives a cap around every apex vertex of `labels` (patch = label 1..6) the label of the missing
/// axis (triangles cut at the cap's sphere: new vertices appended, old ones keep their indices);
/// returns the apex vertices (indices into labels.V).
std::vector<int> add_apex_caps(mesh::SurfaceMesh& labels, const ApexCapOptions& options = {});

struct CollapseApexes {
  int apexes = 0;      ///< apex vertices given
  int collapsed = 0;   ///< of them, collapsed to tet / prism blocks
  int tets = 0, prisms = 0;
  int split_squares = 0;  ///< boundary squares split into two triangular patches
  double min_quality_before = 0, min_quality_after = 0;  ///< worst scaled Jacobian of the blocks changed
};

/// Collapses the cap charts around `apexes` (vertices of `polycube.patches`, whose patch = 1 + square
/// index of `polycube.grid`; all blocks of `polycube.structure` hexes over the grid cells; see
/// GridPolycube). An apex is collapsed
/// only when its 1-ring lies on the squares of one chart, every block touching those squares'
/// corners is a block under them, each column below ends at a boundary square (its triangles are
/// cut along the chosen diagonal, as cut_along_grid cuts along grid lines), every boundary face of the result matches one patch by its
/// corners and no block is inverted; otherwise it is left as it is (hex blocks under a cap) and the
/// reason logged. Patch ids are renumbered 1..n when something collapsed; unused patch vertices
/// and structure vertices are dropped.
CollapseApexes collapse_apexes(GridPolycube& polycube, const std::vector<int>& apexes, LogCallback log = {});

}  // namespace hexdom::autopolycube
