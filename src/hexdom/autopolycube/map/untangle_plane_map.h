// A fold-free map of one chart into its plane polygon: the interior vertices move to minimise a
// barrier-regularised distortion energy (Garanzha et al., "Foldover-free maps in 50 lines of code",
// SIGGRAPH 2021) while the boundary stays where it is. Unlike a harmonic (Tutte) map it untangles
// charts whose polygons are not convex or have holes (a ring around a bore, an L-shaped face).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hexdom/common/deadline.h"

namespace hexdom::autopolycube {

struct UntangleOptions {
  int outer = 60;    ///< rounds of the regularisation parameter epsilon
  int inner = 300;   ///< L-BFGS iterations per round
  double theta = 1.0 / 128;  ///< weight of the area term against the shape term
  /// An L-BFGS run (one round) also ends at the first step that lowers the energy by no more than
  /// this share of it. Smaller values polish each round's map longer; the fold count after the
  /// rounds is what the caller reads.
  double step_tolerance = 1e-7;
  /// Checked before every round: once passed, untangle_plane_map throws TimeoutError
  /// ("autopolycube (chart maps): ...").
  Deadline deadline;
};

struct UntangleResult {
  int folded_before = 0, folded_after = 0;  ///< triangles with orientation <= 0 in the plane
  int folded_fixed = 0;  ///< of folded_after: triangles without a free vertex (no move can help)
  int rounds = 0;
  int iterations = 0;   ///< L-BFGS steps taken, over all rounds
  int evaluations = 0;  ///< passes over the triangles (energy, with or without its gradient)
};

/// Moves the vertices with `free_vertex[v]` of the triangles `tris` of F within the plane of axis
/// `axis` (coordinates (axis+1)%3 and (axis+2)%3 of D, grid units) so that every triangle is
/// positively oriented for the outward sign `sign`; the reference shape of each triangle is its
/// shape in V (scaled to the polygon's area). Vertices not free are fixed; coordinate `axis` of D is
/// left alone. Returns how many triangles were folded before and after.
/// The results are kept (about 24 MB, the oldest dropped first): a call whose inputs (the chart's
/// triangles, their vertices in V and D, the free flags, axis, sign and options) are those of an
/// earlier call in the process gives that call's output at once. The label repair and the further
/// candidates map unchanged charts again; the untangling is deterministic, so the output is the same.
/// \note The boundary polygon must admit a fold-free map (a simple polygon, holes inside); nothing
/// is thrown when it does not: the folded count says so.
UntangleResult untangle_plane_map(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& tris,
                                  const std::vector<char>& free_vertex, int axis, int sign, Eigen::MatrixXd& D,
                                  const UntangleOptions& options = {});

}  // namespace hexdom::autopolycube
