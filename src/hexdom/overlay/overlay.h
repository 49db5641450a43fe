// The overlay path: a hex mesh of any closed surface from a grid laid over it, in the manner of the
// overlay-grid all-hex methods (Schneiders 1996; Sandia's Sculpt; Marechal 2009). It does not need a
// polycube, so it meshes what the polycube path cannot, at the cost of alignment with the part.
//
// Method: the surface is turned into the frame its faces fit (segmentation::cube_frame); a grid of
// cubes of the element size is laid over it (grid.h); the cells well inside are the core (core.h),
// its boundary a 2-manifold; one buffer hexahedron on each boundary quad of the core reaches the
// surface, its outer nodes put on the surface's smooth regions, sharp curves and corners (buffer.h);
// then the shared optimiser untangles and smooths every node, the outer ones kept on what they were
// put on. Where the core falls apart (a part thinner than the grid's cells) or cells stay inverted,
// the grid is made again with half the spacing, a bounded number of times; where the curves of
// FeatureOptions::patch_edges have cells left inverted within a spacing of them, a grid of up to
// max_cells_for_extra cells is meshed without them too.
#pragma once

#include <string>
#include <vector>

#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/node_kinds.h"
#include "hexdom/overlay/features.h"
#include "hexdom/overlay/local_size.h"
#include "hexdom/quality/report.h"
#include "hexdom/segmentation/cube_frame.h"

namespace hexdom::overlay {

struct OverlayOptions {
  double size = 0;      ///< grid spacing (element size); 0: the frame's bounding-box diagonal / 30
  int threads = 0;      ///< threads of the optimiser (0: one per core); the mesh does not depend on it
  /// Along an axis the part is thin in (a plate, a rod), the spacing is made smaller so that its
  /// extent spans at least this many cells, and no cell is longer than max_cell_ratio times its
  /// shortest side (overlay::grid_spacing).
  double across = 3;
  double max_cell_ratio = 5;
  /// Walls (overlay::wall_thickness with wall_quantile: the thickness half the surface's area lies
  /// on walls no thicker than, by default) get at least this many cells across: where they are
  /// thinner than wall_across cells of the spacing, every spacing is made smaller alike, down to
  /// 1 / max_wall_refinement of it and not below min_size. Measured in the space the grid's cells
  /// are cubes in (a plate's thin axis already has its own spacing). 0 (the default): the spacing
  /// as it is (docs/overlay.md: not yet a gain over the whole corpus).
  double wall_across = 0;
  /// With wall_across 0: when a grid keeps inverted cells and the walls are thinner than this
  /// many cells, one more grid with the spacing wall_across would give (the better kept): right
  /// after the first grid when it is coarser than a halving (cheapest first; no halving follows
  /// when it meets the targets the halvings are for), else after the halvings.
  double wall_fallback = 2;
  double wall_quantile = 0.5;
  /// How much finer than the first grid the walls' spacing (wall_across, wall_fallback) may be: at
  /// 16, walls down to an eighth of a cell thick get two cells across.
  double max_wall_refinement = 16;
  /// No cell shorter than this (0: no bound): the thin-axis rule above, the halvings and the octree
  /// stop at it, so a part thinner than `across` times min_size gets fewer cells across.
  double min_size = 0;
  /// Which cells make the core. By centres (core_cells_by_centres): the cells whose centre is at
  /// least centre_margin spacings inside, so that a wall about one cell thick keeps its cells; the
  /// core's boundary nodes are then moved buffer_depth spacings inside the surface
  /// (pull_inner_nodes) to make room for the buffer layer. By corners (core_cells): the cells whose
  /// corners are at least `margin` spacings inside, so that the buffer layer is that thick without
  /// moving them; a wall needs about three cells across to keep a core.
  bool core_by_centres = true;
  double centre_margin = 0.1;
  double buffer_depth = 0.5;
  double margin = 0.4;
  /// Octree refinement of each grid (overlay::octree_mesh), up to this many levels, each dividing
  /// the cells by 3, where the solid is thinner than `wall_cells` cells: a cell that the surface
  /// passes near is split when the ball of diameter wall_cells times its size, touching the nearest
  /// surface point from inside, reaches the other side of the wall (a triangle facing against the
  /// first). A grid so refined is not halved further. 0: the grid's cells only.
  int octree_levels = 0;
  double wall_cells = 2;
  /// Cell sizes asked on patches (CAD faces; local_size.h). Each grid the path lays (the first,
  /// the halvings where cells stay inverted, the grid for walls) has its spacing made to meet the
  /// smallest size within a factor 1.2 at some octree level (local_levels: the spacing as it is when
  /// it does, else at most 1.2 times coarser or up to 2.1 times finer), and the octree refines down
  /// to each size near its patch, its templates grading back to the grid's cells. Sizes below
  /// min_size are taken as it; patches the surface does not have are passed over
  /// (check_local_sizes is the caller's). Not with the core by corners (it has no octree).
  std::vector<LocalSize> local_sizes;
  /// How fast the cells grow from a local size back to the grid's (LocalSizeField): the band of
  /// each level is drawn so that sizes grow by about this much per cell; in (1, 3].
  double growth_rate = kGrowthRate;
  bool align = true;    ///< lay the grid in the frame the faces fit (see pipeline::MeshSurfaceOptions::align)
  segmentation::CubeFrameOptions frame_options;
  FeatureOptions features;
  /// Laplacian passes over the outer nodes the closest points crowded (an outer edge under a
  /// quarter of the spacing: near reflex curves), before the optimiser (overlay::spread).
  int spread_passes = 0;
  /// Sheets of wedges along the curves (overlay::pillow_curves), so that no outer quad of a face
  /// has a node on a curve; each copy of a curve node starts `pillow_offset` of the way into its
  /// face's quads. Off: the grid's staircase along a curve is followed by quad diagonals.
  bool pillow_curves = false;
  double pillow_offset = 0.5;
  /// The optimiser's recommended sequence without pillowing (optimize::improve): worst-cell rounds
  /// until the worst stops improving, at most this many, then passes raising the mean.
  int max_rounds = 40;
  int mean_passes = 8;
  /// Edge-ratio target of the optimiser (optimize::ImproveOptions::max_edge_ratio); 0: none.
  double max_edge_ratio = 10;
  /// Halvings of the spacing allowed when the core falls apart or is empty (a part thinner than the
  /// cells), and, of those, how many when cells stay inverted, the volume is off by more than
  /// target_volume or the worst hex SJ is below refine_below_sj (each costs 8 times the cells); the
  /// better mesh is kept.
  int refinements = 3;
  int refinements_for_quality = 3;
  /// A finer grid for quality alone (cells inverted or the volume off while the part is whole) is
  /// made only when it would have at most about this many cells (8 times the current mesh's).
  double max_cells_for_quality = 2e5;
  /// Extra meshes for quality are made only up to this many cells: a finer grid for a worst SJ
  /// below refine_below_sj alone, the core by corners on a grid whose core by centres left
  /// inverted cells, and a grid without the curves of FeatureOptions::patch_edges where cells stay
  /// inverted within a spacing of them.
  double max_cells_for_extra = 5e4;
  double target_volume = 0.01;
  double refine_below_sj = 0.3;
  /// A grid whose mesh is off the volume by more than this has lost part of the solid (features
  /// thinner than its cells): any mesh of a finer grid that keeps the part is preferred to it, even
  /// one with inverted cells, and of two that both lost part of it the one that lost less. Between
  /// meshes within it: fewer inverted cells, then the volume, then the worst scaled Jacobian.
  double lost_volume = 0.05;
  /// No grid beyond this many cells is made (a bound on time and memory: about 25 bytes per grid
  /// cell, 200 MB here). A thin-walled part needs a grid of cells finer than its walls over its
  /// whole box, of which it keeps only a few percent.
  double max_grid_cells = 8e6;
  /// Looked at before each grid and after each optimisation (which it also bounds: the optimiser
  /// ends its round): once passed or cancelled, TimeoutError. None by default: the path runs to
  /// its end.
  Deadline deadline;
  LogCallback log;
};

struct OverlayResult {
  mesh::Mesh mesh;                   ///< in the input's coordinates; region 1 core, 2 buffer layer
  quality::QualityReport quality;
  double spacing = 0, thinnest = 0;  ///< the grid spacing of the result: largest and smallest over the axes
  int core_cells = 0, buffer_cells = 0, dropped = 0;
  int parted = 0;                    ///< core cells dropped as they faced a kept neighbour across the surface
  int curve_nodes = 0, corner_nodes = 0, corners_missed = 0, demoted = 0;
  int prisms = 0;                    ///< wedges of pillow_curves
  /// #V: what each node of `mesh` is held on (optimize::NodeKind: Corner, Curve, Surface for the
  /// outer nodes on a smooth region, Interior); a Surface node near a curve was let off it on purpose
  /// (a staircase node, a loosened one).
  std::vector<optimize::NodeKind> node_kind;
  int grids = 0;                     ///< grids made
  /// Whether the mesh follows the edges FeatureOptions::patch_edges makes curves (false when it
  /// adds none, or when they left cells inverted on the grid kept and the mesh without them was
  /// better).
  bool patch_edges = false;
  int octree_levels = 0;             ///< levels of octree refinement in the result's grid (0: none)
  segmentation::CubeFrame frame;
  double seconds = 0;  ///< the whole run (a grid's own while overlay_mesh ranks the grids)
};

/// A hex mesh of `surface` (closed, 2-manifold, oriented outward; its patch ids CAD faces, or
/// anything for triangle input). Its boundary nodes lie on the surface. Inverted cells that remain
/// are reported in `quality`, not thrown. Throws GeometryError when no grid within
/// max_grid_cells gives a core (the part is too thin for it), TimeoutError once options.deadline
/// has passed or was cancelled.
OverlayResult overlay_mesh(const mesh::SurfaceMesh& surface, const OverlayOptions& options = {});

/// "overlay: grid 2.5, 1234 core + 567 buffer cells, ..." on one line.
std::string to_text(const OverlayResult& r);

}  // namespace hexdom::overlay
