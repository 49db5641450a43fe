// Mesh quality improvement: pillowing, smoothing by node kind, and Jacobian optimisation, in the
// recommended sequence or as chosen stages.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "hexdom/common/deadline.h"
#include "hexdom/common/error.h"
#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/pillow.h"
#include "hexdom/quality/report.h"

namespace hexdom::optimize {

struct ImproveOptions {
  /// Stages. With all three off (the default), the recommended sequence runs: pillow once, then
  /// smoothing and optimisation rounds until the worst scaled Jacobian stops improving, then mean
  /// passes (see mean_passes) on the best of the runs made. The runs, each made only when the ones
  /// before end inverted or below 0.4: a layer over the smooth regions (faces joined across edges
  /// that are not sharp) in which a cell has two faces meeting at an edge, i.e. where a polycube
  /// edge lies on a smooth surface, and over the regions across a reflex edge from them; a layer
  /// everywhere; no layer.
  bool pillow = false;
  int smooth = 0;    ///< smoothing passes
  int optimize = 0;  ///< optimisation rounds
  int max_rounds = 40;  ///< cap of the worst-cell rounds of the recommended sequence
  /// Cap of the recommended sequence's mean passes, run after the worst cell has stopped improving:
  /// node moves that raise the sum of their cells' scaled Jacobians while no cell that gets worse
  /// falls below the worst cell of its type, so the worst hex, prism and tet are kept (0: none).
  int mean_passes = 12;
  /// Edge-ratio target (largest over shortest edge of a cell, quality::edge_ratio); 0: none. After
  /// the mean passes, the nodes of the cells above it step down the gradient of their cells'
  /// largest ratio (steps of their typical edge, then of their own shortest edge where that is far
  /// shorter: a thin layer). A move never inverts a cell, never lowers a cell below `ratio_sj_floor`
  /// (nor one already below it), and at first never lowers a type's worst scaled Jacobian; while
  /// cells stay above the target, that bar is lowered to half the worst's margin above the floor,
  /// then to the floor: at most 3 x `ratio_rounds` rounds. The ratio gives way to the scaled
  /// Jacobian target; the worst cell above that target gives way to the ratio, one step at a time.
  double max_edge_ratio = 0;
  double ratio_sj_floor = 0.3;
  int ratio_rounds = 30;
  /// With explicit stages (smooth / optimize), run the mean passes after them too (the recommended
  /// sequence always does): smoothing lowers the mean of an optimised mesh.
  bool mean_after = false;
  /// Boundary edges whose faces meet at more than this angle (degrees between normals) are sharp.
  double feature_angle = 35.0;
  /// Sharp-feature nodes given by the user (0-based indices into the input mesh), used instead of
  /// the angle test when not empty: boundary edges between two of them are sharp.
  std::vector<int> sharp_nodes;
  /// Surface the boundary nodes must stay on; empty: the mesh's own initial boundary.
  mesh::SurfaceMesh surface;
  /// Where not empty (#V of the input), every node's kind, used instead of the classification by
  /// sharp edges, with `curve_neighbours` (#V lists; a curve node's neighbours along its curve, the
  /// target of its smoothing) for a mesh whose boundary nodes were put on known features (the
  /// overlay path); with `project` it says where each goes. The recommended sequence then makes no
  /// pillowed runs (the kinds are the input's nodes').
  std::vector<NodeKind> kinds;
  std::vector<std::vector<int>> curve_neighbours;
  /// Nodes that never move (0-based indices into the input mesh), e.g. boundary nodes already put
  /// on the exact CAD geometry; after pillowing, a fixed boundary node's boundary copy is fixed.
  std::vector<int> fixed_nodes;
  /// Where set, replaces the projection of the boundary nodes that move (onto `surface` and the
  /// feature curves): returns where node `node` (0-based, input numbering) goes for a candidate
  /// position x, e.g. onto its exact CAD face or edge. Not used on a pillowed mesh.
  std::function<Eigen::Vector3d(int node, const Eigen::Vector3d& x)> project;
  /// Whether `project` may be called from several threads at once for different nodes (it reads
  /// shared data only). Otherwise the boundary nodes it places move on the calling thread.
  bool project_concurrent = false;
  /// Where not empty (#V x 3): the node positions at which the input was optimised before (by an
  /// earlier improve), its cells unchanged since, e.g. before the snap moved its boundary. The mean
  /// stage then starts from the nodes of the cells whose scaled Jacobian has changed since by more
  /// than 1e-3, not from every node, and the first smoothing pass from those of such cells that are
  /// inverted, below the worst cell of the mesh as optimised, or (with max_edge_ratio) above the
  /// ratio target and worse than before: the optimisation rounds and the mean stage raise the
  /// others, and smoothing them would only undo what the mean stage reached. Each later pass
  /// revisits the nodes near a move of the pass before, as always: the rest is where the earlier
  /// run left it. While cells are inverted, each untangling round visits the nodes around those and
  /// around every node moved so far, not every node. Not used on a pillowed mesh.
  Eigen::MatrixXd optimised_at;
  /// With optimised_at: nodes whose constraint changed since (e.g. let off a curve onto a face,
  /// kinds), although their cells did not; the passes (smoothing included) start from them too.
  std::vector<int> changed_nodes;
  /// Threads of the passes (0: one per core). The mesh is the same whatever their number
  /// (Improver: nodes move colour by colour).
  int threads = 0;
  /// A cell at or above this scaled Jacobian may not drop below it, not even while cells are
  /// inverted (untangling otherwise lets any cell drop to the level of the worst); cells below it
  /// move freely, so untangling them is not held back. E.g. after the snap to the B-rep, the cells
  /// it did not break keep the quality they had. -2: no such floor.
  double floor = -2;
  /// Pillow layer thickness at each node: pillow_depth x its shortest boundary edge, or where
  /// thicker pillow_share x the height of the cells under it, up to that shortest edge
  /// (optimize::pillow_faces; 0: the first alone).
  double pillow_depth = 0.2;
  double pillow_share = 0.4;
  /// The time budget. Looked at after every round (smoothing, optimisation or mean pass): once
  /// passed, the round running ends, no further round, run (with or without a layer) or mean pass
  /// starts, and the best of the runs made so far is returned (by the recommended sequence's order)
  /// with `stopped` set and a log line saying so. At least one round is always made. Never throws.
  Deadline deadline;
  LogCallback log;
};

struct ImproveResult {
  mesh::Mesh mesh;
  quality::QualityReport before, after;
  int pillow_cells = 0;  ///< cells added by pillowing
  int rounds = 0;        ///< smoothing/optimisation rounds run
  int feature_nodes = 0, corner_nodes = 0;
  bool stopped = false;  ///< options.deadline passed: rounds, runs or mean passes were left out
};

/// Improves a hex / prism / tet mesh. Boundary nodes stay on `options.surface` (or the initial
/// boundary), nodes on sharp edges stay on their feature curves, feature corners stay fixed. Every
/// smoothing and optimisation move keeps or raises the worst scaled Jacobian of the cells it
/// touches (inverted cells are untangled first) and, once nothing is inverted, does not push a
/// cell below the worst of its type; mean passes then raise the sum of the scaled Jacobians without
/// lowering any type's worst. Throws GeometryError for a mesh that is not a conforming volume mesh,
/// InterruptedError when the calling thread's interrupt is raised (common/interrupt.h).
ImproveResult improve(const mesh::Mesh& mesh, const ImproveOptions& options = {});

}  // namespace hexdom::optimize
