#include "hexdom/optimize/compass_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hexdom/mesh/adjacency.h"
#include "hexdom/quality/metrics.h"

namespace hexdom::optimize {

namespace {
double cell_value(const mesh::Mesh& m, int c) { return quality::signed_sj(m.type(c), quality::cell_points(m, c)); }
}  // namespace

Eigen::VectorXd compass_untangle(mesh::Mesh& T, const std::vector<char>& fixed,
                                 const std::vector<std::vector<int>>& nbr, const CompassOptions& opt) {
  const int n = T.num_nodes();
  const mesh::NodeCells cells_of = mesh::node_cells(T);
  Eigen::VectorXd q(T.num_cells());
  for (int b = 0; b < T.num_cells(); ++b) q(b) = cell_value(T, b);
  std::vector<double> shortest_allowed(n, 0.0);
  for (int v = 0; v < n; ++v) {
    if (fixed[v] || nbr[v].empty()) continue;
    double len = 0;
    for (int u : nbr[v]) len += (T.V.row(u) - T.V.row(v)).norm();
    shortest_allowed[v] = opt.min_edge_share * len / static_cast<double>(nbr[v].size());
  }
  auto shortest_edge = [&](int v) {
    double e = std::numeric_limits<double>::infinity();
    for (int u : nbr[v]) e = std::min(e, (T.V.row(u) - T.V.row(v)).norm());
    return e;
  };
  for (int round = 0; round < opt.rounds; ++round) {
    int moved = 0;
    for (int v = 0; v < n; ++v) {
      if (fixed[v]) continue;
      double worst = 1e300;
      for (int b : cells_of[v]) worst = std::min(worst, q(b));
      if (worst >= opt.target) continue;
      double len = 0;
      for (int u : nbr[v]) len += (T.V.row(u) - T.V.row(v)).norm();
      len /= std::max<size_t>(nbr[v].size(), 1);
      const Eigen::RowVector3d start = T.V.row(v);
      for (double step = 0.25 * len; step > 1e-3 * len; step *= 0.5) {
        bool improved = true;
        while (improved) {
          improved = false;
          for (int dir = 0; dir < 6; ++dir) {
            const Eigen::RowVector3d keep = T.V.row(v);
            const double shortest_before = shortest_edge(v);
            T.V(v, dir / 2) += dir % 2 ? -step : step;
            const double shortest_after = shortest_edge(v);
            double w = 1e300;
            for (int b : cells_of[v]) w = std::min(w, cell_value(T, b));
            if (w > worst + 1e-9 && (shortest_after >= shortest_allowed[v] || shortest_after >= shortest_before)) {
              worst = w;
              improved = true;
            } else {
              T.V.row(v) = keep;
            }
          }
        }
      }
      if ((T.V.row(v) - start).norm() > 0) {
        ++moved;
        for (int b : cells_of[v]) q(b) = cell_value(T, b);
      }
    }
    if (moved == 0) break;
  }
  return q;
}

}  // namespace hexdom::optimize
