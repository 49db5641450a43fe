#include "hexdom/optimize/relax_nodes.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "hexdom/common/parallel_for.h"
#include "hexdom/quality/jacobian_samples.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::optimize {

using mesh::CellType;
using Vec3 = Eigen::Vector3d;

namespace {

// Type and node count of every cell, read once.
struct CellShapes {
  std::vector<signed char> count;
  std::vector<CellType> type;
  explicit CellShapes(const mesh::Mesh& M) {
    const int nc = M.num_cells();
    count.resize(nc);
    type.resize(nc);
    for (int c = 0; c < nc; ++c) {
      type[c] = M.type(c);
      count[c] = static_cast<signed char>(mesh::node_count(type[c]));
    }
  }
};

}  // namespace

std::string relax_poor(mesh::Mesh& M, const mesh::NodeCells& adj, const std::vector<signed char>& kind, int sweeps, double poor,
                       int threads, std::vector<int>* left, double left_threshold) {
  const int nn = M.num_nodes(), nc = M.num_cells();
  const CellShapes shapes(M);
  auto cell_sj = [&](int c) {
    const double sj = quality::scaled_jacobian(M.type(c), quality::cell_points(M, c));
    return quality::is_inverted(sj) ? -1.0 : sj;
  };
  const int* cells = M.cells.data();  // row-major, 8 per cell
  const int stride = static_cast<int>(M.cells.cols());
  const std::vector<signed char>& cnt = shapes.count;
  auto points = [&](int c, double (*p)[3]) {
    for (int i = 0; i < cnt[c]; ++i)
      for (int d = 0; d < 3; ++d) p[i][d] = M.V(cells[c * stride + i], d);
  };
  // Poor cells, in parallel over chunks of cells (each chunk writes its own flags).
  std::vector<char> is_poor(nc, 0);
  const int chunk = 4096;
  parallel_for((nc + chunk - 1) / chunk, threads, [&](int q) {
    for (int c = q * chunk; c < std::min(nc, (q + 1) * chunk); ++c) {
      double p[8][3];
      points(c, p);
      // The root-free test is a superset up to rounding; the quality module decides.
      is_poor[c] = quality::some_jacobian_sample_at_most(shapes.type[c], p, poor + 1e-9) && cell_sj(c) <= poor;
    }
  });
  std::vector<int> poor_cells;
  std::vector<char> candidate(nn, 0);
  for (int c = 0; c < nc; ++c) {
    if (!is_poor[c]) continue;
    poor_cells.push_back(c);
    for (int i = 0; i < cnt[c]; ++i)
      if (kind[cells[c * stride + i]] == NodeKind::Interior) candidate[cells[c * stride + i]] = 1;
  }
  // Cells that may be below left_threshold at the end: the poor ones and those around moved nodes.
  auto report_left = [&](const std::vector<int>& inc) {
    if (!left) return;
    left->clear();
    std::vector<int> all(poor_cells);
    all.insert(all.end(), inc.begin(), inc.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    for (int c : all) {
      double p[8][3];
      points(c, p);
      if (quality::some_jacobian_sample_at_most(shapes.type[c], p, left_threshold + 1e-9)) left->push_back(c);
    }
  };
  std::vector<int> nodes;
  for (int v = 0; v < nn; ++v)
    if (candidate[v]) nodes.push_back(v);
  if (nodes.empty()) {
    report_left({});
    return "relaxation: no node next to a poor cell";
  }
  const std::vector<int>& start = adj.start;
  const std::vector<int>& inc = adj.cells;
  std::vector<int> around;  // cells of the candidate nodes
  for (int v : nodes) around.insert(around.end(), inc.begin() + start[v], inc.begin() + start[v + 1]);
  std::vector<double> sj(nc, 2.0);  // cached scaled Jacobian of the cells around the nodes
  for (int c : around)
    if (sj[c] == 2.0) sj[c] = cell_sj(c);
  std::vector<double> trial;
  // A node whose last try failed is skipped until a node of one of its cells moves: its try would
  // fail again (same positions, same cached values), so skipping changes nothing but the time.
  std::vector<char> dirty(candidate);
  long long moves = 0;
  int sweep = 0;
  for (; sweep < sweeps; ++sweep) {
    int moved = 0;
    for (int v : nodes) {
      if (!dirty[v]) continue;
      dirty[v] = 0;
      double before = 2;
      Vec3 avg = Vec3::Zero();
      int ne = 0;
      for (int r = start[v]; r < start[v + 1]; ++r) {
        const int c = inc[r];
        before = std::min(before, sj[c]);
        int lv = 0;
        while (M.cells(c, lv) != v) ++lv;
        const int (*E)[3] = quality::corner_neighbours(M.type(c));
        for (int q = 0; q < 3; ++q, ++ne) avg += M.V.row(M.cells(c, E[lv][q])).transpose();
      }
      if (!ne) continue;
      avg /= ne;
      const Vec3 old = M.V.row(v).transpose();
      for (double step : {1.0, 0.5, 0.25}) {
        M.V.row(v) = (old + step * (avg - old)).transpose();
        trial.clear();
        double after = 2;
        for (int r = start[v]; r < start[v + 1]; ++r) {
          trial.push_back(cell_sj(inc[r]));
          after = std::min(after, trial.back());
        }
        if (after > before + 1e-12) {
          for (int r = start[v]; r < start[v + 1]; ++r) {
            sj[inc[r]] = trial[r - start[v]];
            for (int i = 0; i < mesh::node_count(M.type(inc[r])); ++i) dirty[M.cells(inc[r], i)] = candidate[M.cells(inc[r], i)];
          }
          ++moved;
          break;
        }
        M.V.row(v) = old.transpose();
      }
    }
    moves += moved;
    if (!moved) break;
  }
  report_left(around);
  return "relaxation: " + std::to_string(nodes.size()) + " nodes next to poor cells, " + std::to_string(moves) + " moves in " +
         std::to_string(sweep) + " sweeps";
}

namespace {

// The state of one untangle_nodes run: positions in a flat array, the poor cells, the nodes a
// visit may reach, and the visited node's cells and edge neighbours.
class Untangler {
 public:
  Untangler(mesh::Mesh& M, const mesh::NodeCells& adj, NodeFreedom& F, double trigger, double poor, double poor_surface,
            double box)
      : M_(M), adj_(adj), F_(F), shapes_(M), trigger_(trigger), poor_(poor), poor_surface_(poor_surface), box_(box),
        nn_(M.num_nodes()), nc_(M.num_cells()), x_(3 * static_cast<size_t>(nn_)) {
    for (int v = 0; v < nn_; ++v)
      for (int d = 0; d < 3; ++d) x_[3 * v + d] = M.V(v, d);
  }

  /// Finds the poor cells among `candidates` (all cells when null) and the nodes a visit may
  /// reach; false when there is no poor cell.
  bool find_poor(const std::vector<int>* candidates);
  /// Rounds of visits, at most `sweeps`.
  void run(int sweeps);
  /// Writes the positions back into the mesh and, when `left` is given, the cells still at most
  /// the trigger.
  void finish(std::vector<int>* left);
  std::string summary() const {
    return "untangling: " + std::to_string(first_active_) + " nodes next to poor cells, " + std::to_string(visits_) +
           " visits, " + std::to_string(moves_) + " moves, " + std::to_string(evals_) + " evaluations";
  }

 private:
  struct Local { int c, lv; unsigned mask; };  // a cell of the visited node, its local index, its samples

  void points(int c, double (*p)[3]) const {
    for (int i = 0; i < shapes_.count[c]; ++i)
      for (int d = 0; d < 3; ++d) p[i][d] = x_[3 * M_.cells(c, i) + d];
  }
  double cell_sj(int c) const {
    double p[8][3], s[9];
    points(c, p);
    const int ns = quality::jacobian_samples(shapes_.type[c], p, s);
    return *std::min_element(s, s + ns);
  }
  void enqueue_cell(int c, std::vector<int>& list);
  bool too_short(const double* q) const;
  double evaluate_at(const double* q, double* penalty);
  void visit(int v, std::vector<int>& next);
  // Gathers the visited node's cells and ring, the centroid of its edge neighbours, the mean edge
  // length h and the shortest length allowed; false when the node has no cell.
  bool gather(int v, double* centroid, double& h);
  // Descent of the penalty from the node's current position, raising `best` (the worst sample);
  // false when a surface node cannot measure its parameter scale (the visit then ends).
  bool descend(int v, double& best, double h);

  mesh::Mesh& M_;
  const mesh::NodeCells& adj_;
  NodeFreedom& F_;
  const CellShapes shapes_;
  const double trigger_, poor_, poor_surface_, box_;
  const int nn_, nc_;
  std::vector<double> x_;
  long long visits_ = 0, moves_ = 0, evals_ = 0;
  size_t first_active_ = 0;
  std::vector<double> sj_;     // exact for poor cells, 1 for the others until they change
  std::vector<char> mark_;     // 1: node of a poor cell, 2: node a visit may reach
  std::vector<int> poor_cells_, reach_, active_;
  std::vector<char> queued_;
  std::vector<Local> loc_;
  std::vector<int> ring_;      // edge neighbours of the visited node
  double shortest_ = 0;        // no trial may bring an edge of the visited node below this
};

bool Untangler::find_poor(const std::vector<int>* candidates) {
  // Only nodes of poor cells and of the cells around them can be visited.
  sj_.assign(nc_, 1.0);
  mark_.assign(nn_, 0);
  for (int q = 0, qn = candidates ? static_cast<int>(candidates->size()) : nc_; q < qn; ++q) {
    const int c = candidates ? (*candidates)[q] : q;
    double p[8][3];
    points(c, p);
    if (!quality::some_jacobian_sample_at_most(shapes_.type[c], p, trigger_)) continue;
    sj_[c] = cell_sj(c);
    poor_cells_.push_back(c);
    for (int i = 0; i < shapes_.count[c]; ++i) mark_[M_.cells(c, i)] = 1;
  }
  if (poor_cells_.empty()) return false;
  const std::vector<int>& start = adj_.start;
  const std::vector<int>& inc = adj_.cells;
  std::vector<int> ones;  // nodes of poor cells
  for (int c : poor_cells_)
    for (int i = 0; i < shapes_.count[c]; ++i) ones.push_back(M_.cells(c, i));
  std::sort(ones.begin(), ones.end());
  ones.erase(std::unique(ones.begin(), ones.end()), ones.end());
  for (int v : ones)  // nodes of the cells around the poor cells' nodes
    for (int r = start[v]; r < start[v + 1]; ++r)
      for (int i = 0; i < shapes_.count[inc[r]]; ++i) {
        const int u = M_.cells(inc[r], i);
        if (!mark_[u]) {
          mark_[u] = 2;
          reach_.push_back(u);
        }
      }
  reach_.insert(reach_.end(), ones.begin(), ones.end());
  queued_.assign(nn_, 0);
  for (int c : poor_cells_) enqueue_cell(c, active_);
  first_active_ = active_.size();
  return true;
}

void Untangler::enqueue_cell(int c, std::vector<int>& list) {
  for (int i = 0; i < shapes_.count[c]; ++i) {
    const int v = M_.cells(c, i);
    const int k = F_.kind[v];
    if (!mark_[v] || k == NodeKind::Corner || queued_[v] || (k != NodeKind::Interior && sj_[c] > poor_surface_)) continue;
    queued_[v] = 1;
    list.push_back(v);
  }
}

bool Untangler::too_short(const double* q) const {
  for (int u : ring_) {
    const double* a = &x_[3 * u];
    if ((a[0] - q[0]) * (a[0] - q[0]) + (a[1] - q[1]) * (a[1] - q[1]) + (a[2] - q[2]) * (a[2] - q[2]) < shortest_ * shortest_)
      return true;
  }
  return false;
}

// Worst affected sample (and penalty) with the visited node at q.
double Untangler::evaluate_at(const double* q, double* penalty) {
  ++evals_;
  double worst = 2, pen = 0;
  for (const Local& l : loc_) {
    double p[8][3], s[9];
    for (int i = 0; i < shapes_.count[l.c]; ++i) {
      const double* src = i == l.lv ? q : &x_[3 * M_.cells(l.c, i)];
      p[i][0] = src[0];
      p[i][1] = src[1];
      p[i][2] = src[2];
    }
    const int ns = quality::jacobian_samples(shapes_.type[l.c], p, s);
    for (int k = 0; k < ns; ++k) {
      if (!(l.mask >> k & 1u)) continue;
      worst = std::min(worst, s[k]);
      if (s[k] < poor_) pen += (poor_ - s[k]) * (poor_ - s[k]);
    }
  }
  if (penalty) *penalty = pen;
  return worst;
}

void Untangler::run(int sweeps) {
  std::vector<int> next;
  for (int sweep = 0; sweep < sweeps && !active_.empty(); ++sweep) {
    next.clear();
    for (int v : active_) visit(v, next);
    active_.swap(next);
  }
}

bool Untangler::gather(int v, double* centroid, double& h) {
  loc_.clear();
  ring_.clear();
  double lmin = 1e300;
  h = 0;
  int ne = 0;
  const double* xv = &x_[3 * v];
  for (int r = adj_.start[v]; r < adj_.start[v + 1]; ++r) {
    const int c = adj_.cells[r];
    int lv = 0;
    while (M_.cells(c, lv) != v) ++lv;
    loc_.push_back({c, lv, quality::jacobian_samples_of_node(shapes_.type[c], lv)});
    const int (*E)[3] = quality::corner_neighbours(shapes_.type[c]);
    for (int q = 0; q < 3; ++q) {
      ring_.push_back(M_.cells(c, E[lv][q]));
      const double* u = &x_[3 * ring_.back()];
      for (int d = 0; d < 3; ++d) centroid[d] += u[d];
      const double l = std::sqrt((u[0] - xv[0]) * (u[0] - xv[0]) + (u[1] - xv[1]) * (u[1] - xv[1]) + (u[2] - xv[2]) * (u[2] - xv[2]));
      h += l;
      lmin = std::min(lmin, l);
      ++ne;
    }
  }
  if (!ne) return false;
  for (int d = 0; d < 3; ++d) centroid[d] /= ne;
  h /= ne;
  shortest_ = std::min(0.1 * h, lmin);
  return true;
}

void Untangler::visit(int v, std::vector<int>& next) {
  ++visits_;
  queued_[v] = 0;
  double centroid[3] = {0, 0, 0}, h = 0;
  if (!gather(v, centroid, h)) return;
  double* xv = &x_[3 * v];
  double best = evaluate_at(xv, nullptr);
  const double before = best;
  if (F_.kind[v] == NodeKind::Interior) {
    double trial[3];
    for (double step : {1.0, 0.5, 0.25}) {
      for (int d = 0; d < 3; ++d) trial[d] = xv[d] + step * (centroid[d] - xv[d]);
      if (too_short(trial)) continue;
      const double w = evaluate_at(trial, nullptr);
      if (w > best + 1e-12) {
        best = w;
        std::copy(trial, trial + 3, xv);
        break;
      }
    }
  }
  if (!descend(v, best, h) || best <= before + 1e-12) return;
  ++moves_;
  if (best < before + 1e-4) return;  // too small a gain to revisit the neighbours
  for (const Local& l : loc_) {
    sj_[l.c] = cell_sj(l.c);
    if (sj_[l.c] <= trigger_) enqueue_cell(l.c, next);
  }
}

// Descent on the penalty of poor samples, by finite differences in the node's own coordinates (3D,
// or its curve or patch parameters), while it raises the worst sample. Parameter steps are scaled
// by the ratio of parameter to 3D length near the node.
bool Untangler::descend(int v, double& best, double h) {
  const int kind = F_.kind[v];
  const int dims = kind == NodeKind::Interior ? 3 : kind;
  double* xv = &x_[3 * v];
  double scale = 1;  // 3D length per unit parameter
  auto position = [&](const double* q, double* out) {
    if (kind == NodeKind::Interior) std::copy(q, q + 3, out);
    else F_.place(v, q, out);
  };
  double* pv = kind == NodeKind::Interior ? xv : F_.now[v].data();
  if (kind != NodeKind::Interior) {
    double probe[3], tp[2];
    std::copy(pv, pv + dims, tp);
    tp[0] += 1e-3;
    F_.clamp(v, tp);
    position(tp, probe);
    const double dq = std::fabs(tp[0] - pv[0]);
    const double dl = std::sqrt((probe[0] - xv[0]) * (probe[0] - xv[0]) + (probe[1] - xv[1]) * (probe[1] - xv[1]) +
                                (probe[2] - xv[2]) * (probe[2] - xv[2]));
    if (!(dq > 0) || !(dl > 0)) return false;
    scale = dl / dq;
  }
  const double descent = 0.5 * poor_;  // nodes whose worst sample is below this descend
  for (int it = 0; it < (best < 0 ? 8 : 2) && best < descent; ++it) {
    double pen = 0, g[3] = {0, 0, 0}, q[3], pos[3];
    evaluate_at(xv, &pen);
    const double eps = 1e-6 * h / scale;
    for (int d = 0; d < dims; ++d) {
      std::copy(pv, pv + dims, q);
      q[d] += eps;
      position(q, pos);
      double pd = 0;
      evaluate_at(pos, &pd);
      g[d] = (pd - pen) / eps;
    }
    double gn = 0;
    for (int d = 0; d < dims; ++d) gn += g[d] * g[d];
    gn = std::sqrt(gn);
    if (!(gn > 0)) break;
    bool moved = false;
    for (double step = 0.5 * h / scale; step > 1e-3 * h / scale; step *= 0.5) {
      for (int d = 0; d < dims; ++d) q[d] = pv[d] - step * g[d] / gn;
      if (kind != NodeKind::Interior) {
        // Within `box` of its lattice parameters, so that surface nodes keep their order.
        for (int d = 0; d < dims; ++d) q[d] = std::clamp(q[d], F_.param[v][d] - box_, F_.param[v][d] + box_);
        F_.clamp(v, q);
      }
      position(q, pos);
      if (too_short(pos)) continue;
      const double w = evaluate_at(pos, nullptr);
      if (w > best + 1e-12) {
        best = w;
        std::copy(q, q + dims, pv);
        std::copy(pos, pos + 3, xv);
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  return true;
}

void Untangler::finish(std::vector<int>* left) {
  for (int v = 0; v < nn_; ++v)
    for (int d = 0; d < 3; ++d) M_.V(v, d) = x_[3 * v + d];
  if (!left) return;
  // Cells still at most the trigger: only cells of marked nodes can have changed.
  std::vector<int> all;
  for (int v : reach_) all.insert(all.end(), adj_.cells.begin() + adj_.start[v], adj_.cells.begin() + adj_.start[v + 1]);
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  left->clear();
  for (int c : all) {
    double p[8][3];
    points(c, p);
    if (quality::some_jacobian_sample_at_most(shapes_.type[c], p, trigger_)) left->push_back(c);
  }
}

}  // namespace

std::string untangle_nodes(mesh::Mesh& M, const mesh::NodeCells& adj, NodeFreedom& F, int sweeps, double trigger, double poor,
                           double poor_surface, double box, const std::vector<int>* candidates, std::vector<int>* left) {
  Untangler u(M, adj, F, trigger, poor, poor_surface, box);
  if (!u.find_poor(candidates)) {
    if (left) left->clear();
    return "untangling: no poor cell";
  }
  u.run(sweeps);
  u.finish(left);
  return u.summary();
}

}  // namespace hexdom::optimize
