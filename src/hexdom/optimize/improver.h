// The node-move optimiser behind improve(): moves one node at a time, each move projected by the
// node's kind (NodeKinds, BoundaryConstraints) and kept only when its cells' scaled Jacobians allow
// it (see try_move and try_move_mean).
//
// Order and threads: every pass visits the nodes colour by colour (a greedy colouring in node order
// in which no two nodes of one colour share a cell), in increasing order within a colour. Nodes of
// one colour read and write nothing another of them reads or writes, so they may move at the same
// time; the nodes moved are marked for the next passes once their colour is done. The meshes are
// therefore the same whatever the number of threads (the constructor's).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "hexdom/mesh/mesh.h"
#include "hexdom/optimize/node_kinds.h"

namespace hexdom::optimize {

/// The optimiser's value of a cell: its scaled Jacobian, an inverted cell's lowered by 1e-9 (so
/// that a cell at exactly 0 counts as inverted) and -1 for a degenerate cell (DBL_MAX, NaN).
double cell_sj(const mesh::Mesh& m, int c);

/// Per-cell scaled Jacobians of a mesh kept up to date while nodes move. Passes: smoothing
/// (smooth_pass), the worst cells' climb (optimize_round), the mean (mean_pass). Every accepted move
/// keeps or raises the worst value of the node's cells (the mean pass: raises their sum), never
/// puts a worsened cell below the floor of its type (set_floors) or across the keep level
/// (set_keep), and never shortens the node's shortest edge below 0.2 of its mean edge.
class Improver {
 public:
  using Vec = Eigen::Vector3d;
  using CellType = mesh::CellType;
  /// Works on `m` in place; `t` and `c` must outlive the improver (it keeps references). The
  /// first measure of the cells and the passes run on `threads` threads (see threads()).
  Improver(mesh::Mesh& m, const NodeKinds& t, const BoundaryConstraints& c, int threads = 1);

  // Worst hex when there are hexes (the figure the paper reports), else the worst cell.
  double worst_hex() const;
  int inverted() const;
  double worst() const { return sj_.empty() ? 1.0 : *std::min_element(sj_.begin(), sj_.end()); }
  double sj(int q) const { return sj_[q]; }  ///< cell q's value (cell_sj) where the nodes are now
  // " at (x, y, z)": the centroid of the worst cell, for the log.
  std::string worst_place() const;
  double local_min(int v) const;
  // The forward differences of local_min(v) along the three axes with step h, taken over the cells
  // within 0.01 of the lowest (scaled to the step: h = 1e-4 of the node's typical edge): a cell
  // further above cannot be the lowest after the step unless its scaled Jacobian falls faster than
  // 100 per typical edge length. The same slopes as over all cells, for a third of the evaluations
  // or less.
  Vec min_slopes(int v, double h);

  // out[k]: cell q's value (cell_sj) with its node v moved by h along axis k, the node left in place.
  void axis_steps(int q, int v, double h, double out[3]) const;

  // Projects a candidate position according to the node's kind.
  Vec constrain(int v, const Vec& x) const;

  double shortest_edge(int v, const Vec& x) const;

  // Nodes whose neighbourhood changed since they were last visited by a pass: only they can move.
  void mark_around(int v);
  void mark_all();
  // Every node may climb again (optimize_round), the smoothing's marks left as they are: a node a
  // smoothing pass left unmarked would be refused the same move again while the floors stay (its
  // cells, their values and its edge neighbours are where they were), but the climb's pattern
  // moves depend on the worst cell of the whole mesh.
  void climb_all();
  // Only the nodes of the cells around `nodes` and around every node moved so far.
  void mark_only(const std::vector<int>& nodes);
  // Moves shorter than this are not worth an evaluation (and would keep converged nodes busy).
  bool negligible(int v, const Vec& x) const { return (x - m_.V.row(v).transpose()).squaredNorm() < 1e-8 * edge_[v] * edge_[v]; }

  // Moves v to x if that raises (or, with allow_equal, keeps) the worst SJ of its cells, and no
  // cell that gets worse ends below the floor of its type (set_floors; by default the type's
  // worst, so that raising a prism never costs the worst hex). A move
  // may not shorten the node's shortest edge below a quarter of its typical edge: scaled Jacobians
  // ignore size, and collapsing an edge would buy angles with a useless element. A move taken sets
  // v's moved flag; the sweep running marks v's neighbourhood once v's colour is done.
  bool try_move(int v, const Vec& x, bool allow_equal);

  // Smoothing target by kind: interior nodes toward the volume-weighted centre of their cells,
  // surface nodes toward the area-weighted centre of their boundary faces, curve nodes toward the
  // midpoint of their curve neighbours. False for corners and nodes without a target.
  bool smoothing_target(int v, Vec* out) const;

  // One smoothing pass: every node toward its smoothing target, projected, and accepted only if
  // the local worst SJ does not drop.
  int smooth_pass();

  // Mean stage: moves that raise the sum of scaled Jacobians of a node's cells, where no cell that
  // gets worse ends below the floor of its type (hex, prism, tet). With each floor at least the
  // worst cell of its type, no type's worst cell drops; cells well above it may give a little to
  // raise their neighbours.
  double local_sum(int v) const;
  // Floors: each type's worst cell, raised to `extra`. With `only_above` > 0, a type whose worst is
  // within only_above of the worst cell of the mesh gets no floor: it is what the worst stage
  // raises, and holding it back there costs more than it saves.
  void set_floors(double extra, double only_above = 0);
  void clear_floors() { floor_[0] = floor_[1] = floor_[2] = -2; }
  // ImproveOptions::floor: a cell at or above it may not get worse than it. Cells already below
  // it (the inverted ones being untangled) are free, or untangling would stall.
  void set_keep(double x) { keep_ = x; }
  void set_pattern(bool on) { pattern_ = on; }
  bool crosses_keep(int q, double sj) const { return sj_[q] >= keep_ && sj < keep_; }
  int type_slot(int q) const { return m_.type(q) == CellType::Hex ? 0 : m_.type(q) == CellType::Wedge ? 1 : 2; }
  bool try_move_mean(int v, const Vec& x);

  // One pass of the mean stage over the nodes whose neighbourhood changed: each takes a step up
  // the numerical gradient of the sum of its cells' scaled Jacobians. (The smoothing targets were
  // tried here too and measured: they rarely raise the sum and cost evaluations; the worst stage
  // smooths.) Returns the number of nodes moved.
  int mean_pass();

  double mean() const;

  // Largest edge ratio (quality::edge_ratio) of the cells of node v, with v at x.
  double local_ratio(int v, const Vec& x);
  // Moves v to x if that lowers the largest edge ratio of its cells (`ratio_now` with v where it
  // is), none of them becomes inverted or crosses the keep level, and no cell whose scaled
  // Jacobian drops ends below `bar[type]` (or its own value, when that is lower).
  bool try_move_ratio(int v, const Vec& x, double ratio_now, const double bar[3]);
  // One edge-ratio round: the nodes of the cells whose edge ratio is above `target` step down the
  // numerical gradient of their cells' largest ratio (try_move_ratio). Returns the nodes moved.
  int ratio_round(double target, const double bar[3]);
  // Largest edge ratio over the mesh and the worst scaled Jacobian of each type (hex, prism, tet).
  double max_ratio() const;
  void worst_by_type(double out[3]) const;

  // One optimisation round: nodes of the worst cells climb the local worst scaled Jacobian along
  // its numerical gradient (untangling inverted cells on the way).
  int optimize_round(double threshold);

  /// Threads the passes share a colour's nodes among (1: the calling thread only; under a thread
  /// grant, common/thread_grant.h, the grant's count at each sweep instead). Boundary nodes
  /// whose projection hook is not BoundaryConstraints::project_concurrent move on the calling thread.
  int threads() const { return threads_; }
  int colours() const { return static_cast<int>(colours_.size()); }
  int colour(int v) const { return colour_[v]; }

 private:
  mesh::Mesh& m_;
  const NodeKinds& t_;
  const BoundaryConstraints& c_;
  // Visits the nodes (all, or `nodes` in their order) colour by colour, calling visit(v) for each
  // (together on the threads where concurrent(v)); a visit that moves v sets moved_[v]. Returns
  // the number of nodes moved.
  template <class Visit>
  int sweep(const std::vector<int>* nodes, Visit&& visit);
  bool concurrent(int v) const;
  // Takes node v's move: its cells' scaled Jacobians become `trial` (in node_cells order) and v is
  // marked moved for the sweep.
  void accept(int v, const std::vector<double>& trial);

  std::vector<double> sj_, edge_;
  std::vector<char> dirty_;  // nodes for the next smoothing or mean pass
  std::vector<char> climb_;  // nodes worth another optimisation step
  std::vector<char> moved_;  // nodes moved in the colour being swept
  std::vector<char> touched_;  // nodes moved since the improver was made
  std::vector<int> colour_;  // per node
  // Per node: the triangle of its last projection onto the surface and onto the curves, as a first
  // bound for the next (TriangleProjector::project's hint: the same answer, sooner). Each written
  // only by the thread that moves its node.
  mutable std::vector<int> surface_hint_, curve_hint_;
  std::vector<std::vector<int>> colours_;  // per colour: its nodes, increasing
  int threads_ = 1;
  double keep_ = -2;  // ImproveOptions::floor
  bool pattern_ = false;  // optimisation rounds also search a pattern of directions (optimize_round)
  double floor_[3] = {-2, -2, -2};  // lowest scaled Jacobian a worsened hex, prism, tet may reach
};

}  // namespace hexdom::optimize
