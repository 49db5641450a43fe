#include "hexdom/optimize/curve_mid_nodes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "hexdom/common/error.h"
#include "hexdom/common/stopwatch.h"
#include "hexdom/mesh/cell_faces.h"
#include "hexdom/mesh/closest_point.h"
#include "hexdom/mesh/edge_key.h"
#include "hexdom/mesh/second_order.h"
#include "hexdom/quality/second_order.h"

namespace hexdom::optimize {

namespace {

double cell_sj(const mesh::Mesh& m, int c) {
  double p[mesh::kMaxSecondOrderNodes][3];
  mesh::second_order_points(m, c, p);
  return quality::second_order_scaled_jacobian(m.type(c), p);
}

/// The cell's value with its mid-edge nodes on the midpoints of its edges.
double straight_sj(const mesh::Mesh& m, int c) {
  double p[mesh::kMaxSecondOrderNodes][3];
  const int n = mesh::second_order_points(m, c, p);
  const int nc = mesh::node_count(m.type(c));
  const auto [edges, ne] = mesh::cell_edges(m.type(c));
  for (int e = 0; e < n - nc; ++e)
    for (int k = 0; k < 3; ++k) p[nc + e][k] = 0.5 * (p[edges[e][0]][k] + p[edges[e][1]][k]);
  return quality::second_order_scaled_jacobian(m.type(c), p);
}

}  // namespace

CurveReport curve_mid_nodes(mesh::Mesh& m, const Eigen::MatrixXd& target, const std::vector<char>& has_target,
                            const CurveOptions& opt) {
  if (!m.second_order()) throw InputError("curving mid-edge nodes takes a second-order mesh: the mesh is first order");
  const int nv = m.num_nodes(), nc = m.num_cells();
  if (target.rows() != nv || target.cols() != 3 || static_cast<int>(has_target.size()) != nv)
    throw std::invalid_argument("curve_mid_nodes: " + std::to_string(nv) + " nodes, but targets for " +
                                std::to_string(target.rows()) + " and flags for " + std::to_string(has_target.size()));
  const std::vector<std::array<int, 2>> ends = mesh::mid_edge_ends(m);
  // Cells around each mid-edge node, and the share t of each targeted node's offset in use.
  std::vector<std::vector<int>> cells_of(nv);
  for (int c = 0; c < nc; ++c)
    for (int e = 0; e < mesh::edge_count(m.type(c)); ++e) cells_of[m.mid(c, e)].push_back(c);
  std::vector<double> share(nv, 0);
  CurveReport r;
  auto place = [&](int v) {
    const Eigen::RowVector3d mid = 0.5 * (m.V.row(ends[v][0]) + m.V.row(ends[v][1]));
    if (share[v] == 0) m.V.row(v) = mid;
    else if (share[v] == 1) m.V.row(v) = target.row(v);
    else m.V.row(v) = mid + share[v] * (target.row(v) - mid);
  };
  std::vector<int> judge;  // cells to judge in the next pass
  std::vector<char> queued(nc, 0);
  for (int v = 0; v < nv; ++v) {
    if (!has_target[v] || ends[v][0] < 0) continue;
    r.targets++;
    share[v] = 1;
    place(v);
    for (int c : cells_of[v])
      if (!queued[c]) queued[c] = 1, judge.push_back(c);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> straight(nc, nan), sj(nc, nan);  // sj: the cell's value as it stands, NaN when unknown
  const double smallest = std::ldexp(1.0, -opt.halvings);
  // Every pass lowers the share of some node, and a share takes halvings + 2 values at most, so the
  // loop ends; a cell whose mid-edge nodes all have share 0 has its straight shape and is accepted.
  while (!judge.empty()) {
    std::sort(judge.begin(), judge.end());
    std::vector<int> lower;
    for (int c : judge) {
      queued[c] = 0;
      if (std::isnan(straight[c])) straight[c] = straight_sj(m, c);
      sj[c] = cell_sj(m, c);
      if (!(sj[c] < std::min(opt.min_sj, straight[c]))) continue;
      for (int e = 0; e < mesh::edge_count(m.type(c)); ++e)
        if (share[m.mid(c, e)] > 0) lower.push_back(m.mid(c, e));
    }
    judge.clear();
    std::sort(lower.begin(), lower.end());
    lower.erase(std::unique(lower.begin(), lower.end()), lower.end());
    for (int v : lower) {
      share[v] = share[v] > smallest ? share[v] / 2 : 0;
      place(v);
      for (int c : cells_of[v]) {
        sj[c] = nan;
        if (!queued[c]) queued[c] = 1, judge.push_back(c);
      }
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (!has_target[v] || ends[v][0] < 0) continue;
    r.placed += share[v] == 1;
    r.straight += share[v] == 0;
    r.shortened += share[v] > 0 && share[v] < 1;
    r.max_gap = std::max(r.max_gap, (m.V.row(v) - target.row(v)).norm());
  }
  r.worst_sj = nan;
  for (int c = 0; c < nc; ++c) {
    const double q = std::isnan(sj[c]) ? cell_sj(m, c) : sj[c];
    r.worst_sj = std::isnan(r.worst_sj) ? q : std::min(r.worst_sj, q);
    r.inverted += !(q > 0);
  }
  return r;
}

mesh::Mesh second_order_on_surface(const mesh::Mesh& linear, const mesh::SurfaceMesh& surface, const CurveOptions& opt,
                                   SecondOrderReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  SecondOrderReport rep;
  mesh::Mesh m = mesh::add_mid_edge_nodes(linear);
  if (linear.num_nodes() > 0) rep.diagonal = (linear.V.colwise().maxCoeff() - linear.V.colwise().minCoeff()).norm();
  std::unordered_set<mesh::EdgeKey> boundary;
  for (const mesh::BoundaryFace& f : mesh::boundary_faces(linear))
    for (int i = 0; i < f.n; ++i) boundary.insert(mesh::undirected_edge(f.v[i], f.v[(i + 1) % f.n]));
  const mesh::TriangleProjector tp(surface.V, surface.F);
  const std::vector<std::array<int, 2>> ends = mesh::mid_edge_ends(m);
  Eigen::MatrixXd target = m.V;
  std::vector<char> has_target(m.num_nodes(), 0);
  for (int v = linear.num_nodes(); v < m.num_nodes() && !tp.empty(); ++v) {
    if (!boundary.count(mesh::undirected_edge(ends[v][0], ends[v][1]))) continue;
    target.row(v) = tp.project(m.V.row(v).transpose()).transpose();
    has_target[v] = 1;
    rep.boundary_mid_nodes++;
    rep.face_targets++;
    rep.max_offset = std::max(rep.max_offset, (target.row(v) - m.V.row(v)).norm());
  }
  rep.curve = curve_mid_nodes(m, target, has_target, opt);
  rep.seconds = seconds_since(t0);
  if (report) *report = rep;
  return m;
}

}  // namespace hexdom::optimize
