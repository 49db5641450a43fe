#include "hexdom/optimize/improver.h"

#include "hexdom/common/interrupt.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdom/common/format.h"
#include "hexdom/common/parallel_for.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::optimize {

using mesh::CellType;
using quality::CellPoints;
using quality::cell_points;
using quality::is_inverted;
using quality::scaled_jacobian;
using quality::volume;
using Vec = Eigen::Vector3d;

namespace {

// Weight of a cell in the volume-weighted centre: its volume, for hexes and prisms taken from the
// Jacobian at the centre (exact for parallelepipeds and straight prisms, and far cheaper than
// quadrature, which matters in a loop over every node's cells).
double centre_volume(CellType t, const CellPoints& P) {
  auto r = [&](int i) { return Vec(P.row(i).transpose()); };
  if (t == CellType::Hex) {
    const Vec a = r(1) - r(0) + r(2) - r(3) + r(5) - r(4) + r(6) - r(7);
    const Vec b = r(3) - r(0) + r(2) - r(1) + r(7) - r(4) + r(6) - r(5);
    const Vec c = r(4) - r(0) + r(5) - r(1) + r(6) - r(2) + r(7) - r(3);
    return a.dot(b.cross(c)) / 64.0;
  }
  if (t == CellType::Wedge) {
    const Vec a = r(1) - r(0) + r(4) - r(3), b = r(2) - r(0) + r(5) - r(3);
    const Vec c = r(3) - r(0) + r(4) - r(1) + r(5) - r(2);
    return -a.dot(b.cross(c)) / 24.0;  // VTK wedges: first triangle's normal points away from the second
  }
  return volume(t, P);
}

// Each thread's buffer of trial scaled Jacobians (try_move and its kin).
std::vector<double>& scratch() {
  thread_local std::vector<double> trial;
  return trial;
}

// A sweep's colour goes to the threads only when it has this many nodes that may run together:
// below it, starting the threads costs more than the moves.
constexpr size_t kMinConcurrent = 32;

}  // namespace

namespace {
// A cell's value for the optimiser from its scaled Jacobian (cell_sj).
double value_of(double sj) { return is_inverted(sj) ? (sj <= 0 ? sj - 1e-9 : -1.0) : sj; }
}  // namespace

double cell_sj(const mesh::Mesh& m, int c) { return value_of(scaled_jacobian(m.type(c), cell_points(m, c))); }

void Improver::axis_steps(int q, int v, double h, double out[3]) const {
  const CellPoints P = cell_points(m_, q);
  const int n = mesh::node_count(m_.type(q));
  int i = 0;
  while (i < n && m_.cells(q, i) != v) ++i;
  if (m_.type(q) == CellType::Hex) {
    quality::hex_sj_axis_steps(P, i, h, out);
    for (int k = 0; k < 3; ++k) out[k] = value_of(out[k]);
    return;
  }
  for (int k = 0; k < 3; ++k) {
    CellPoints Q = P;
    Q(i, k) += h;
    out[k] = value_of(scaled_jacobian(m_.type(q), Q));
  }
}

Improver::Improver(mesh::Mesh& m, const NodeKinds& t, const BoundaryConstraints& c, int threads)
    : m_(m), t_(t), c_(c), threads_(std::max(1, threads)) {
  sj_.resize(m.num_cells());
  parallel_for(m.num_cells(), threads_, [&](int q) { sj_[q] = cell_sj(m, q); });
  dirty_.assign(m.num_nodes(), 1);
  climb_.assign(m.num_nodes(), 1);
  surface_hint_.assign(m.num_nodes(), -1);
  curve_hint_.assign(m.num_nodes(), -1);
  edge_.assign(m.num_nodes(), 0.0);
  parallel_for(m.num_nodes(), threads_, [&](int v) {
    double s = 0;
    int k = 0;
    for (int q : t.node_cells[v]) {
      auto P = cell_points(m, q);
      const int n = mesh::node_count(m.type(q));
      for (int i = 0; i < n; ++i) { s += (P.row(i) - m.V.row(v)).norm(); ++k; }
    }
    edge_[v] = k ? s / k : 0.0;  // mean distance to the corners of incident cells
  });
  // Greedy colouring in node order: each node takes the lowest colour no node of its cells has.
  moved_.assign(m.num_nodes(), 0);
  touched_.assign(m.num_nodes(), 0);
  colour_.assign(m.num_nodes(), -1);
  std::vector<int> taken_by;  // per colour: the last node that found it taken
  for (int v = 0; v < m.num_nodes(); ++v) {
    for (int q : t.node_cells[v])
      for (int i = 0; i < mesh::node_count(m.type(q)); ++i) {
        const int c = colour_[m.cells(q, i)];
        if (c >= 0) taken_by[c] = v;
      }
    int c = 0;
    while (c < static_cast<int>(taken_by.size()) && taken_by[c] == v) ++c;
    if (c == static_cast<int>(taken_by.size())) {
      taken_by.push_back(-1);
      colours_.emplace_back();
    }
    colour_[v] = c;
    colours_[c].push_back(v);
  }
}

bool Improver::concurrent(int v) const {
  return !(c_.project && !c_.project_concurrent && (t_.kind[v] == Surface || t_.kind[v] == Curve));
}

template <class Visit>
int Improver::sweep(const std::vector<int>* nodes, Visit&& visit) {
  std::vector<std::vector<int>> listed;
  if (nodes) {
    listed.resize(colours_.size());
    for (int v : *nodes) listed[colour_[v]].push_back(v);
  }
  int moved = 0;
  std::vector<int> together, alone;
  for (size_t c = 0; c < colours_.size(); ++c) {
    check_interrupt("optimise");
    const std::vector<int>& bucket = nodes ? listed[c] : colours_[c];
    together.clear();
    alone.clear();
    for (int v : bucket) (concurrent(v) ? together : alone).push_back(v);
    const int threads = granted_threads(threads_);
    if (threads > 1 && together.size() >= kMinConcurrent) {
      parallel_for(static_cast<int>(together.size()), threads, [&](int i) { visit(together[i]); });
    } else {
      for (int v : together) visit(v);
    }
    for (int v : alone) visit(v);
    // The moves of one colour touch disjoint cells: their neighbourhoods are marked once all are made.
    for (int v : bucket)
      if (moved_[v]) {
        moved_[v] = 0;
        mark_around(v);
        ++moved;
      }
  }
  return moved;
}

double Improver::worst_hex() const {
  double w = 2;
  for (int q = 0; q < m_.num_cells(); ++q)
    if (m_.type(q) == CellType::Hex) w = std::min(w, sj_[q]);
  return w < 2 ? w : worst();
}

int Improver::inverted() const {
  int n = 0;
  for (double x : sj_) n += x <= 0;
  return n;
}

std::string Improver::worst_place() const {
  if (sj_.empty()) return "";
  const int q = static_cast<int>(std::min_element(sj_.begin(), sj_.end()) - sj_.begin());
  const auto P = cell_points(m_, q);
  const Vec c = P.topRows(mesh::node_count(m_.type(q))).colwise().mean().transpose();
  return fmt(" at (%.4g, %.4g, %.4g)", c(0), c(1), c(2));
}

Vec Improver::min_slopes(int v, double h) {
  const double f0 = local_min(v);
  // A cell further above f0 than this is not the lowest after a step h: its scaled Jacobian would
  // have to fall by `window` over h, a slope of 100 per edge length.
  const double window = 1e-2 * h / (1e-4 * edge_[v]);
  Vec g = Vec::Constant(2.0);
  double s[3];
  for (int q : t_.node_cells[v])
    if (sj_[q] <= f0 + window) {
      axis_steps(q, v, h, s);
      for (int k = 0; k < 3; ++k) g(k) = std::min(g(k), s[k]);
    }
  for (int k = 0; k < 3; ++k) g(k) = (g(k) - f0) / h;
  return g;
}

double Improver::local_min(int v) const {
  double w = 2;
  for (int q : t_.node_cells[v]) w = std::min(w, sj_[q]);
  return w;
}

Vec Improver::constrain(int v, const Vec& x) const {
  if (c_.project && (t_.kind[v] == Surface || t_.kind[v] == Curve)) return c_.project(v, x);
  switch (t_.kind[v]) {
    case Surface: return c_.surface.project(x, &surface_hint_[v], surface_hint_[v]);
    // On the feature curve (chords of the boundary), then back onto the surface it bounds.
    case Curve:
      return c_.surface.project(c_.curves.empty() ? x : c_.curves.project(x, &curve_hint_[v], curve_hint_[v]),
                                &surface_hint_[v], surface_hint_[v]);
    case Corner: return m_.V.row(v).transpose();
    default: return x;
  }
}

double Improver::shortest_edge(int v, const Vec& x) const {
  // One square root: it is monotonic and correctly rounded, so this is the least of the lengths.
  double s = std::numeric_limits<double>::max();
  for (int u : t_.edge_nbrs[v]) s = std::min(s, (m_.V.row(u).transpose() - x).squaredNorm());
  return std::sqrt(s);
}

void Improver::mark_around(int v) {
  for (int q : t_.node_cells[v])
    for (int i = 0; i < mesh::node_count(m_.type(q)); ++i) {
      dirty_[m_.cells(q, i)] = 1;
      climb_[m_.cells(q, i)] = 1;
    }
}

void Improver::mark_all() {
  std::fill(dirty_.begin(), dirty_.end(), 1);
  std::fill(climb_.begin(), climb_.end(), 1);
}

void Improver::climb_all() { std::fill(climb_.begin(), climb_.end(), 1); }

void Improver::mark_only(const std::vector<int>& nodes) {
  std::fill(dirty_.begin(), dirty_.end(), 0);
  for (int v : nodes) mark_around(v);
  for (int v = 0; v < m_.num_nodes(); ++v)
    if (touched_[v]) mark_around(v);
}

void Improver::accept(int v, const std::vector<double>& trial) {
  for (size_t i = 0; i < trial.size(); ++i) sj_[t_.node_cells[v][i]] = trial[i];
  moved_[v] = 1;
  touched_[v] = 1;
}

bool Improver::try_move(int v, const Vec& x, bool allow_equal) {
  if (negligible(v, x)) return false;
  const double before = local_min(v);
  const Vec old = m_.V.row(v).transpose();
  const double s_old = shortest_edge(v, old), s_new = shortest_edge(v, x);
  if (s_new < s_old && s_new < 0.2 * edge_[v]) return false;
  m_.V.row(v) = x.transpose();
  double after = 2;
  const auto& cells = t_.node_cells[v];
  const int n = static_cast<int>(cells.size());
  std::vector<double>& trial = scratch();
  trial.assign(n, 0.0);
  bool below_floor = false;
  // A cell at or below this fails the move whatever the others give: the rest are not evaluated.
  // The lowest cell, the likeliest to fail, goes first.
  const double fails = allow_equal ? before - 1e-12 : before + 1e-12;
  int lowest = 0;
  for (int i = 1; i < n; ++i)
    if (sj_[cells[i]] < sj_[cells[lowest]]) lowest = i;
  int evaluated = 0;
  for (int k = 0; k < n; ++k) {
    const int i = k == 0 ? lowest : k <= lowest ? k - 1 : k;
    const int q = cells[i];
    const double sj = cell_sj(m_, q);
    trial[i] = sj;
    ++evaluated;
    after = std::min(after, sj);
    below_floor |= sj < sj_[q] && (sj < floor_[type_slot(q)] || crosses_keep(q, sj));
    if (below_floor || sj < fails || (!allow_equal && sj <= fails)) break;
  }
  if (below_floor) after = -3;  // would lower the worst cell of a type: never taken
  if (evaluated == n && (after > before + 1e-12 || (allow_equal && after >= before - 1e-12 && after > 0))) {
    accept(v, trial);
    return true;
  }
  m_.V.row(v) = old.transpose();
  return false;
}

bool Improver::smoothing_target(int v, Vec* out) const {
  if (t_.kind[v] == Corner || t_.node_cells[v].empty()) return false;
  Vec target = Vec::Zero();
  double wsum = 0;
  if (t_.kind[v] == Interior) {
    for (int q : t_.node_cells[v]) {
      const CellPoints P = cell_points(m_, q);
      const int n = mesh::node_count(m_.type(q));
      // Valid cells: the cheap centre volume; inverted or tangled ones: the true volume (the centre
      // volume of a tangled hex misweights it, and untangling stalls).
      const double vol = sj_[q] > 0 ? centre_volume(m_.type(q), P) : volume(m_.type(q), P);
      const double w = std::max(std::fabs(vol), 1e-300);
      target += w * P.topRows(n).colwise().mean().transpose();
      wsum += w;
    }
  } else if (t_.kind[v] == Surface) {
    for (int f : t_.node_faces[v]) {
      const auto& bf = t_.faces[f];
      Vec c = Vec::Zero();
      for (int i = 0; i < bf.n; ++i) c += m_.V.row(bf.v[i]).transpose();
      const double w = mesh::face_area_vector(m_, bf).norm();
      target += w * c / bf.n;
      wsum += w;
    }
  } else {
    for (int u : t_.curve_nbrs[v]) target += m_.V.row(u).transpose();
    wsum = static_cast<double>(t_.curve_nbrs[v].size());
  }
  if (!(wsum > 0)) return false;
  *out = target / wsum;
  return true;
}

int Improver::smooth_pass() {
  return sweep(nullptr, [&](int v) {
    if (!dirty_[v]) return;
    dirty_[v] = 0;
    Vec target;
    if (!smoothing_target(v, &target)) return;
    const Vec old = m_.V.row(v).transpose();
    for (double step : {1.0, 0.5, 0.25})
      if (try_move(v, constrain(v, old + step * (target - old)), true)) return;
  });
}

double Improver::local_sum(int v) const {
  double s = 0;
  for (int q : t_.node_cells[v]) s += sj_[q];
  return s;
}

void Improver::set_floors(double extra, double only_above) {
  worst_by_type(floor_);
  const double w = std::min({floor_[0], floor_[1], floor_[2]});
  for (double& f : floor_) f = only_above > 0 && f < w + only_above ? -2 : std::max(f, extra);
}

bool Improver::try_move_mean(int v, const Vec& x) {
  if (negligible(v, x)) return false;
  const Vec old = m_.V.row(v).transpose();
  const double s_old = shortest_edge(v, old), s_new = shortest_edge(v, x);
  if (s_new < s_old && s_new < 0.2 * edge_[v]) return false;
  m_.V.row(v) = x.transpose();
  double before_sum = 0, after_sum = 0;
  bool ok = true;
  std::vector<double>& trial = scratch();
  trial.clear();
  for (int q : t_.node_cells[v]) {
    const double sj = cell_sj(m_, q);
    trial.push_back(sj);
    before_sum += sj_[q];
    after_sum += sj;
    if (sj < sj_[q] && (sj < floor_[type_slot(q)] || sj <= 0 || crosses_keep(q, sj))) { ok = false; break; }
  }
  if (ok && after_sum > before_sum + 1e-7) {
    accept(v, trial);
    return true;
  }
  m_.V.row(v) = old.transpose();
  return false;
}

int Improver::mean_pass() {
  return sweep(nullptr, [&](int v) {
    if (!dirty_[v]) return;
    dirty_[v] = 0;
    if (t_.kind[v] == Corner || t_.node_cells[v].empty()) return;
    const Vec x0 = m_.V.row(v).transpose();
    const double h = 1e-4 * edge_[v];
    if (!(h > 0)) return;
    const double f0 = local_sum(v);
    double f[3] = {0, 0, 0}, s[3];
    for (int q : t_.node_cells[v]) {
      axis_steps(q, v, h, s);
      for (int k = 0; k < 3; ++k) f[k] += s[k];
    }
    const Vec g((f[0] - f0) / h, (f[1] - f0) / h, (f[2] - f0) / h);
    if (!(g.norm() > 0)) return;
    const Vec d = g.normalized();
    for (double a : {0.1, 0.02})
      if (try_move_mean(v, constrain(v, x0 + a * edge_[v] * d))) return;
  });
}

double Improver::local_ratio(int v, const Vec& x) {
  const Vec old = m_.V.row(v).transpose();
  m_.V.row(v) = x.transpose();
  double r = 0;
  for (int q : t_.node_cells[v]) r = std::max(r, quality::edge_ratio(m_.type(q), cell_points(m_, q)));
  m_.V.row(v) = old.transpose();
  return r;
}

bool Improver::try_move_ratio(int v, const Vec& x, double ratio_now, const double bar[3]) {
  if (negligible(v, x)) return false;
  const Vec old = m_.V.row(v).transpose();
  if (!(local_ratio(v, x) < ratio_now * (1 - 1e-6))) return false;
  m_.V.row(v) = x.transpose();
  std::vector<double>& trial = scratch();
  trial.clear();
  for (int q : t_.node_cells[v]) {
    const double sj = cell_sj(m_, q);
    trial.push_back(sj);
    if (sj < sj_[q] && (sj <= 0 || sj < std::min(sj_[q], bar[type_slot(q)]) || crosses_keep(q, sj))) {
      m_.V.row(v) = old.transpose();
      return false;
    }
  }
  accept(v, trial);
  return true;
}

int Improver::ratio_round(double target, const double bar[3]) {
  std::vector<char> mark(m_.num_nodes(), 0);
  std::vector<int> nodes;
  for (int q = 0; q < m_.num_cells(); ++q) {
    if (!(quality::edge_ratio(m_.type(q), cell_points(m_, q)) > target)) continue;
    for (int i = 0; i < mesh::node_count(m_.type(q)); ++i) {
      const int v = m_.cells(q, i);
      if (!mark[v] && t_.kind[v] != Corner) { mark[v] = 1; nodes.push_back(v); }
    }
  }
  return sweep(&nodes, [&](int v) {
    const Vec x0 = m_.V.row(v).transpose();
    const double h = 1e-4 * edge_[v];
    if (!(h > 0)) return;
    const double f0 = local_ratio(v, x0);
    Vec g;
    for (int k = 0; k < 3; ++k) {
      Vec x = x0;
      x(k) += h;
      g(k) = (local_ratio(v, x) - f0) / h;
    }
    if (!(g.norm() > 0) || !g.allFinite()) return;
    const Vec d = -g.normalized();
    auto step = [&](double length) { return try_move_ratio(v, constrain(v, x0 + length * d), f0, bar); };
    for (double a : {0.3, 0.15, 0.07, 0.03, 0.01})
      if (step(a * edge_[v])) return;
    // The ratio is set by the short edges: where the node's own shortest edge is far below its
    // typical one (a thin layer), steps of that shortest edge, so that two short edges sharing
    // the node can be evened out.
    const double s = shortest_edge(v, x0);
    for (double a : {0.1, 0.03, 0.01})
      if (a * s < 0.01 * edge_[v] && step(a * s)) return;
  });
}

double Improver::max_ratio() const {
  double r = 0;
  for (int q = 0; q < m_.num_cells(); ++q) r = std::max(r, quality::edge_ratio(m_.type(q), cell_points(m_, q)));
  return r;
}

void Improver::worst_by_type(double out[3]) const {
  out[0] = out[1] = out[2] = 2;
  for (int q = 0; q < m_.num_cells(); ++q) out[type_slot(q)] = std::min(out[type_slot(q)], sj_[q]);
}

double Improver::mean() const {
  double s = 0;
  for (double x : sj_) s += x;
  return sj_.empty() ? 1.0 : s / static_cast<double>(sj_.size());
}

int Improver::optimize_round(double threshold) {
  std::vector<char> mark(m_.num_nodes(), 0);
  std::vector<int> nodes;
  for (int q = 0; q < m_.num_cells(); ++q) {
    if (sj_[q] > threshold) continue;
    for (int i = 0; i < mesh::node_count(m_.type(q)); ++i) {
      const int v = m_.cells(q, i);
      if (!mark[v] && t_.kind[v] != Corner) { mark[v] = 1; nodes.push_back(v); }
    }
  }
  // With the pattern on and the worst cell below 0.4 (the bar of the recommended sequence), the
  // nodes of the cells within 0.02 of the worst one also try a pattern of directions where the
  // gradient step fails (below). Above the bar it costs more than it gains.
  std::vector<char> near_worst;
  if (pattern_ && worst() < 0.4) {
    near_worst.assign(m_.num_nodes(), 0);
    const double band = std::min(threshold, worst() + 0.02);
    for (int q = 0; q < m_.num_cells(); ++q)
      if (sj_[q] <= band)
        for (int i = 0; i < mesh::node_count(m_.type(q)); ++i) near_worst[m_.cells(q, i)] = 1;
  }
  return sweep(&nodes, [&](int v) {
    // A node that found no better place stays put until its neighbourhood changes.
    if (!climb_[v]) return;
    climb_[v] = 0;
    const Vec x0 = m_.V.row(v).transpose();
    const double h = 1e-4 * edge_[v];
    if (!(h > 0)) return;
    const Vec g = min_slopes(v, h);
    if (g.norm() > 0) {
      const Vec d = g.normalized();
      for (double a : {0.3, 0.15, 0.07, 0.03, 0.01, 0.003})
        if (try_move(v, constrain(v, x0 + a * edge_[v] * d), false)) return;
    }
    if (near_worst.empty() || !near_worst[v]) return;
    // The numerical gradient of a minimum sees only the corner that is lowest now: where two
    // corners of the worst cell tie (a node between two faces on a round), every step along it
    // lowers the other, and the climb stalls. A pattern of the 26 directions of the unit cube,
    // at three step lengths, finds the moves that raise both.
    for (double a : {0.1, 0.03, 0.01})
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            if (!dx && !dy && !dz) continue;
            if (try_move(v, constrain(v, x0 + a * edge_[v] * Vec(dx, dy, dz).normalized()), false)) return;
          }
  });
}

}  // namespace hexdom::optimize
