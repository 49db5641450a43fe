// Automatic polycube structure from a labelled surface (issue 9): the polycube map of the charts,
// its planes on a grid of spacing h, one hex block per grid cell inside, and the surface re-split
// along the grid lines so that `hexdom generate` takes the pair unchanged.
//
// Method: charts (connected regions of one label) are flattened by a least-squares deformation
// that keeps the surface's gradients (one sparse solve per axis, plane offsets free), the planes are
// put on the grid so that every chart boundary curve keeps its direction and a length of at least
// one cell, curves are straightened between their corners and chart interiors mapped harmonically
// into their plane polygons. The cells that polygons enclose are the blocks; the polycube's surface
// is cut along the grid lines (cut vertices take the input position at the same barycentric
// coordinates), and block vertices on the surface sit at those grid points' input positions.
// Labellings that cannot be a polycube (opposite labels side by side, islands, pinches, faces with
// fewer than 4 corners, zero-length edges, folds of the map) are repaired by joining the smallest
// offending chart to a neighbour. Where the repair left a thin strip chart along a wedge-like
// feature (a knife edge), the blocks under the strip become prisms: the strip's short edges collapse
// and its squares join the neighbouring patches (collapse_slivers.h). At an apex where only side
// charts meet (the tip of a cone or a pyramid) the 1-ring becomes a cap chart of the missing axis
// and the blocks under the cap collapse to the apex: tets at the tip, prisms in the columns below
// (apex_blocks.h). A flat triangular face whose normal is far from every axis (a tetrahedron's
// slanted face) is cut into three quads from its corners first (split_oblique_faces.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"

namespace hexdom::autopolycube {

/// The labelling after the label repair and the chord split that autopolycube does first, and what
/// that took. It depends only on the input labels, the element size and max_relabels (not on the
/// level nor on keep_widths), so a caller that builds several polycubes of one labelling (mesh_surface's
/// candidates) repairs once.
struct RepairedLabels {
  mesh::SurfaceMesh labels;  ///< chords split, no chart problem left
  int relabelled = 0, chords = 0;
  std::vector<Eigen::Vector3d> apexes;  ///< apex vertices given a cap (add_apex_caps), by position
  int oblique_faces = 0;                ///< oblique triangular faces split from their corners
};

struct AutoPolycubeOptions {
  /// Target element size H (model units); 0: the bounding-box diagonal / 30.
  double size = 0;
  /// Subdivision level s that `generate` will use: blocks are grid cells of spacing h = H * 2^s.
  int level = 1;
  int max_relabels = 200;  ///< charts the label repair may relabel
  int max_attempts = 20;   ///< relabel-and-retry rounds when the map folds or the cells do not match
  /// Rounds in a row that may end in the very same problem (the same charts, of the same sizes,
  /// failing the same way) before autopolycube gives up: relabelling other charts is then not
  /// converging (the label repair takes back most of each relabelling).
  int max_same_problem = 3;
  /// A chart blamed for a fold or a mismatch is relabelled only when its area is at most this share
  /// of the surface's; otherwise autopolycube gives up and names it.
  double max_relabel_area = 0.03;
  int untangle_rounds = 50;  ///< rounds of local moves of interior block vertices
  /// Walls of a hole or a slot (charts of opposite labels facing each other across a void) get planes
  /// as many cells apart as they are in the input, not just one (PolycubeMapOptions::keep_widths).
  bool keep_widths = true;
  /// Strip charts (1 or 2 squares wide) whose real width across is at most this share of their
  /// squares' length along, or whose hex blocks are poor, become prism blocks where that does not
  /// lower the worst block (see collapse_slivers.h); 0: hex blocks only.
  double sliver_ratio = 0.35;
  /// Apexes where only side charts meet get a cap chart, and the blocks under it collapse to tets
  /// and prisms (apex_blocks.h); false: labels as given (the label repair then merges the charts
  /// around the apex).
  bool apex_caps = true;
  /// Flat triangular faces whose normal is far from every axis and whose neighbours carry one label
  /// of each axis (a tetrahedron's slanted face) are cut into three quads from their corners, each
  /// labelled with the axis its neighbours lack (split_oblique_faces.h), before the label repair;
  /// false: labels as given (the repair then merges such a face with a neighbour or gives up).
  bool oblique_faces = true;
  /// The cap's radius in element sizes (ApexCapOptions::radius = this * size).
  double apex_cap_radius = 1.0;
  /// The blocks under a cap collapse to tets and prisms (collapse_apexes); false: they stay hexes,
  /// the cap a face of its own (route of a frustum).
  bool collapse_apexes = true;
  /// When given: the result of the first repair of these same labels at this same size (see
  /// RepairedLabels; AutoPolycube::repaired of an earlier run), used instead of repairing again.
  const RepairedLabels* repaired = nullptr;
  /// The frame the labels refer to (CvtOptions::frame): the polycube is built from the surface
  /// turned into it (x_frame = frame * x) and the structure, patches, labels and polycube come back
  /// in the input's coordinates; `repaired` stays in the frame. The identity: the model's axes.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  /// The time budget: checked before each relabel-and-retry round and inside the loops where the
  /// time goes (the label repair's rounds and bands, each chart's map and untangling, each sliver
  /// strip). Once passed, autopolycube throws TimeoutError naming the step ("autopolycube (slivers):
  /// stopped after the time budget of 5 s"); a polycube half built is no result. None: no limit.
  Deadline deadline;
  LogCallback log;
};

struct AutoPolycube {
  /// Blocks over the grid cells (VTK order), region = block number: hexes, and prisms where a
  /// sliver strip collapsed (see AutoPolycubeOptions::sliver_ratio).
  mesh::Mesh structure;
  /// Input geometry re-split along the grid; patch = boundary square (a sliver strip's squares
  /// joined to a neighbouring square's patch), one patch per boundary face of the structure.
  mesh::SurfaceMesh patches;
  mesh::SurfaceMesh labels;    ///< the repaired labels on the surface the map used (chords split)
  RepairedLabels repaired;     ///< the first repair's result (before relabelling charts the map blamed)
  mesh::SurfaceMesh polycube;  ///< the polycube (labels' triangles at their polycube positions)
  double cell = 0;             ///< h
  int charts = 0, relabelled = 0, chords = 0, planes = 0, pushed = 0;
  int squares = 0, blocks = 0, boundary_vertices = 0, interior_vertices = 0;
  int slivers = 0, prism_blocks = 0, tet_blocks = 0;  ///< strips collapsed; blocks that are not hexes
  int oblique_faces = 0;                 ///< oblique triangular faces split from their corners
  int apexes = 0, apexes_collapsed = 0;  ///< apex caps added; of them, collapsed to tet / prism blocks
  /// PolycubeMap::widened over every map this run made; 0: keep_widths changed nothing.
  int widened = 0;
  double min_block_quality = 0;  ///< worst block scaled Jacobian after untangling
  int inverted_blocks = 0;

  /// Calls f(name, value) for each figure above (cell to inverted_blocks), names as the fields':
  /// the one list the bindings and reports read, so that a new figure is added here only.
  template <class F>
  void for_each_figure(F&& f) const {
    f("cell", cell);
    f("charts", charts), f("relabelled", relabelled), f("chords", chords), f("planes", planes), f("pushed", pushed);
    f("squares", squares), f("blocks", blocks), f("boundary_vertices", boundary_vertices);
    f("interior_vertices", interior_vertices);
    f("slivers", slivers), f("prism_blocks", prism_blocks), f("tet_blocks", tet_blocks);
    f("oblique_faces", oblique_faces), f("apexes", apexes), f("apexes_collapsed", apexes_collapsed);
    f("widened", widened), f("min_block_quality", min_block_quality), f("inverted_blocks", inverted_blocks);
  }
};

/// Builds the structure and the patch surface from `labels` (closed surface, label 1..6 per
/// triangle). When `progress` is given it holds, also when this throws, the repaired labels and
/// the last polycube computed, for inspection. Throws GeometryError naming the charts or corners
/// when the labelling cannot be repaired, MeshingError when a solve fails, TimeoutError when
/// options.deadline passes.
AutoPolycube autopolycube(const mesh::SurfaceMesh& labels, const AutoPolycubeOptions& options = {},
                          AutoPolycube* progress = nullptr);

}  // namespace hexdom::autopolycube
